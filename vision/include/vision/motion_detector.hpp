#pragma once
// MotionDetector: Stauffer-Grimson adaptive background mixture (METHOD.md §3), fixed point.
//
// Every pixel of a grey image is modelled by K Gaussians; apply() marks the pixels that match none
// of the background distributions as foreground, then updates the model. A sudden change of the
// light turns almost every pixel foreground, like a stopped object, for
// framesToBecomeBackground() frames; callers that cannot wait may reset(). The update rules, the
// fixed-point formats and why grey: motion_detector.cpp.

#include "vision/image.hpp"

#include <cstdint>
#include <memory>

namespace vision {

struct MotionDetectorOptions {
    int components = 3;             ///< K, 1..5
    float learningRate = 0.005f;    ///< a, (0, 0.5]
    float backgroundRatio = 0.7f;   ///< T, (0, 1)
    float matchThreshold = 2.5f;    ///< lambda, in standard deviations
    float initialVariance = 36.0f;  ///< grey^2, of a new distribution
    float minVariance = 4.0f;       ///< grey^2 floor (8-bit data quantises the variance to 0)
    float maxVariance = 255.0f;     ///< grey^2 ceiling, <= 255.99 (q8 in uint16)
};

class MotionDetector {
public:
    /// Allocates the model for grey images of `size`. Throws std::runtime_error naming the option
    /// out of range.
    MotionDetector(Size size, const MotionDetectorOptions& options = {});

    /// Classifies every pixel of `gray` (Gray8 of the constructed size) into `mask` (Gray8, same
    /// size, 255 = foreground, 0 = background) and updates the model. The first frame (and the
    /// first after reset()) becomes the background. Returns the number of foreground pixels, or
    /// -1 on a size/format mismatch (model and mask untouched).
    int apply(const ConstImageView& gray, const ImageView& mask) noexcept;

    /// Forgets the model: the next frame is the new background.
    void reset() noexcept;

    /// Frames a stopped object (or new illumination) stays foreground, under the model: the old
    /// background's weight must fall to T, (1 - a)^n <= T.
    int framesToBecomeBackground() const noexcept;

    Size size() const noexcept { return size_; }
    const MotionDetectorOptions& options() const noexcept { return options_; }

    /// Fixed-point model of one pixel (tests, HUD): component k's weight (q15), mean (q8) and
    /// variance (q8), sorted by weight, heaviest first.
    std::uint16_t weight(int x, int y, int k) const noexcept { return at(k, x, y); }
    std::uint16_t mean(int x, int y, int k) const noexcept { return at(K_ + k, x, y); }
    std::uint16_t variance(int x, int y, int k) const noexcept { return at(2 * K_ + k, x, y); }

private:
    std::uint16_t at(int plane, int x, int y) const noexcept
    {
        return model_[plane * planeSize_ + static_cast<std::ptrdiff_t>(y) * size_.width + x];
    }
    void initialise(const ConstImageView& gray, const ImageView& mask) noexcept;
    template <int K>
    int applyK(const ConstImageView& gray, const ImageView& mask) noexcept;

    Size size_;
    MotionDetectorOptions options_;
    int K_ = 3;
    std::uint32_t alpha_ = 0;       // q16
    std::uint32_t threshold_ = 0;   // T, q15
    std::uint32_t lambda2_ = 0;     // q8
    std::uint16_t initVar_ = 0;     // q8
    std::uint16_t minVar_ = 0;      // q8
    std::uint16_t maxVar_ = 0;      // q8
    std::ptrdiff_t planeSize_ = 0;  // pixels
    bool empty_ = true;  // no frame since construction or reset(): the next one is background
    std::unique_ptr<std::uint16_t[]> rowIn_, rowOut_;  // one row of grey q8 and of 0/1 results
    std::unique_ptr<std::uint16_t[]> model_;           // planes: w[K], mean[K], var[K]
};

/// Converts RGB24, BGR24, XRGB8888 or Gray8 `src` to grey and shrinks it by `factor` (1..4) with a
/// box filter, in fixed point, into Gray8 `dst` of exactly (src.width / factor, src.height /
/// factor) (a last odd row/column is dropped). Grey = (77 R + 150 G + 29 B) / 256 (BT.601 luma).
/// Returns false on a format or size mismatch.
bool downscaleToGray(const ConstImageView& src, int factor, const ImageView& dst) noexcept;

}  // namespace vision
