#pragma once
// Pyramidal Lucas-Kanade point tracking (METHOD.md §3, "Tracking"), in fixed point.
//
// For each point, coarse to fine over the pyramid levels: the previous frame's window around the
// point is sampled once per level with 14-bit bilinear weights (as cv::calcOpticalFlowPyrLK does)
// into values with 5 fractional bits, its Scharr gradients are taken on that sampled window (for a
// window at one sub-pixel offset, interpolation and the derivative filter commute, so no gradient
// image of the whole frame is needed), and the 2x2 gradient matrix is summed in 64-bit integers.
// Then, up to maxIterations times, the next frame's window at the current estimate is sampled the
// same way and the Newton step solves the 2x2 system; iteration stops when the step is below
// epsilon (squared step against squared epsilon, and OpenCV's half-step stop when two steps
// cancel). A forward-backward check tracks the result back into the previous frame and rejects
// points that do not come back within fbThreshold pixels.
//
// Windows are rows padded to a multiple of 8 values with zero gradients, so the inner loops run
// on whole SIMD vectors. The scalar kernels are the reference; on x86-64 AVX2 copies written with
// intrinsics (pixel pairs times weight pairs in one multiply-add) are chosen at run time, and
// since all sums are exact integers both give identical results. Near the border the window's
// pixels are first copied with the edge repeated outwards, then the same kernels run on the copy;
// a coarse level whose window would lie mostly outside is skipped. A
// point is Lost when it ends outside the image or a level-0 window is too flat (min eigenvalue
// under minEigThreshold). On the FGNet frames the result equals cv::calcOpticalFlowPyrLK's to
// 1e-3 px (tests/peer/optical_flow_peer_test.cpp).

#include "vision/geometry.hpp"
#include "vision/image_pyramid.hpp"

#include <cstdint>
#include <memory>

namespace vision {

struct OpticalFlowOptions {
    int window = 15;         ///< odd window side in pixels (3..31)
    int maxLevel = 3;        ///< coarsest level used (0 = no pyramid); capped by the pyramids
    int maxIterations = 30;  ///< Newton steps per level
    float epsilon = 0.01f;   ///< stop when a step is shorter than this (pixels)
    float minEigThreshold = 1e-4f;  ///< min eigenvalue of the gradient matrix, in OpenCV's units
    float fbThreshold = 1.0f;       ///< forward-backward distance limit in pixels; <= 0 disables
};

enum class FlowStatus : std::uint8_t {
    Tracked,                ///< tracked and (when enabled) passed the forward-backward check
    Lost,                   ///< left the image, or its window has too little texture
    ForwardBackwardFailed,  ///< tracked, but the backward track ended too far from the start
};

/// Tracks points from one pyramid to the next. Holds its scratch windows, allocated by the
/// constructor; track() never allocates.
class PyramidalLucasKanade {
public:
    /// Throws std::runtime_error on an even or out-of-range window.
    explicit PyramidalLucasKanade(const OpticalFlowOptions& options = {});

    const OpticalFlowOptions& options() const noexcept { return options_; }

    /// Tracks n points from `prev` to `next` (pyramids of the same frame size). nextPts[i]
    /// receives the tracked position (the start when lost), status[i] its status and, when
    /// fbError is given, fbError[i] the forward-backward distance (-1 when not computed). Returns
    /// the number of points Tracked.
    int track(const ImagePyramid& prev, const ImagePyramid& next, const Point2f* prevPts,
              Point2f* nextPts, FlowStatus* status, int n, float* fbError = nullptr) noexcept;

    /// One point, no forward-backward check: true when tracked. `guess` is the starting estimate
    /// in `next` (usually `from`).
    bool trackPoint(const ImagePyramid& prev, const ImagePyramid& next, Point2f from, Point2f guess,
                    Point2f& to) noexcept;

private:
    /// Samples rows x cols values of `img` from (x, y) on (top-left) into `out` (values scaled by
    /// 32, rows outStride apart). Pixels outside the image repeat the border.
    void sampleWindow(ConstImageView img, float x, float y, int rows, int cols, int outStride,
                      std::int16_t* out) noexcept;
    /// The (rows + 1) x (cols + 1) pixels of `img` from (x0, y0) on, copied into edge_ with the
    /// image's edge pixels repeated outwards, so that windows near the border run the same
    /// kernels as windows inside.
    ConstImageView edgeCopy(ConstImageView img, int x0, int y0, int rows, int cols) noexcept;

    OpticalFlowOptions options_;
    int lanes_ = 0;  ///< window rows padded to a multiple of 8 values (the padding's gradients 0)
    std::unique_ptr<std::int16_t[]> patch_;  ///< (window + 2)^2 samples of the previous frame
    std::unique_ptr<std::int16_t[]> ival_;   ///< window samples of the previous frame (padded rows)
    std::unique_ptr<std::int16_t[]> ix_;     ///< window x gradients
    std::unique_ptr<std::int16_t[]> iy_;     ///< window y gradients
    std::unique_ptr<std::uint8_t[]> edge_;   ///< pixels near the border, edges repeated
};

}  // namespace vision
