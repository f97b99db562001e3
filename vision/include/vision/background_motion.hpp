#pragma once
// BackgroundMotion: how the whole view moved between two frames (a camera that shakes), from
// corners on the background, for telling a face that moves from one that the camera moves
// (METHOD.md §3, "Detection": static regions are not faces). A print on the wall moves with the
// background; a living face moves relative to it. Shi-Tomasi corners away from the faces (and the
// bodies below them) are followed by pyramidal Lucas-Kanade (§3, "Tracking") and a similarity is
// fitted to them robustly; a face's flow less this motion is its own.
//
// Use: update() once a frame with the last and this frame's pyramids, this frame's grey image and
// the faces' boxes; then displacement() says how far the view carried a point. Nothing
// allocates after construction.
#include "vision/corner_detector.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"
#include "vision/image_pyramid.hpp"
#include "vision/motion_model.hpp"
#include "vision/optical_flow.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace vision {

class BackgroundMotion {
public:
    static constexpr int kMaxCorners = 64;  ///< background corners followed at most
    /// Fewer inliers than this: no reliable view motion (a plain wall), taken as none.
    static constexpr int kMinInliers = 12;

    BackgroundMotion(Size imageSize, const OpticalFlowOptions& flow);

    /// This frame: follows the corners from `previous` to `current` (null `previous`: the first
    /// frame), fits the view's motion, and finds new corners in `gray` away from `faces` when
    /// too few are left (not every frame when a search finds too few).
    void update(const ImagePyramid* previous, const ImagePyramid& current,
                const ConstImageView& gray, std::span<const Rect> faces) noexcept;
    /// How far the view carried image point `p` from the last frame to this one (zero when the
    /// view's motion is unknown).
    Point2f displacement(Point2f p) const noexcept;
    /// The farthest the view carried any image point this frame (its corners'), 0 when unknown.
    float largestDisplacement() const noexcept;
    /// The view's motion is known this frame.
    bool known() const noexcept { return known_; }
    const MotionModel& model() const noexcept { return model_; }
    void reset() noexcept;

private:
    void follow(const ImagePyramid& previous, const ImagePyramid& current) noexcept;
    void replenish(const ConstImageView& gray, std::span<const Rect> faces) noexcept;

    Size size_;
    CornerDetector corners_;
    PyramidalLucasKanade flow_;
    MotionModel model_{};
    bool known_ = false;
    int count_ = 0;
    int sinceSearch_ = 0;        ///< frames since replenish() last ran
    bool searchFilled_ = false;  ///< it left at least kMinInliers corners
    std::array<Point2f, kMaxCorners> points_{};
    std::array<Point2f, kMaxCorners> next_{};
    std::array<FlowStatus, kMaxCorners> status_{};
    std::array<Point2f, kMaxCorners> from_{};
    std::array<Point2f, kMaxCorners> to_{};
    std::array<std::uint8_t, kMaxCorners> inliers_{};
    std::array<Corner, kMaxCorners> found_{};
};

}  // namespace vision
