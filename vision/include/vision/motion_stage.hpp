#pragma once
// MotionStage ("motion"): the camera frame, converted to grey at a reduced resolution, through the
// MotionDetector; the foreground mask (Gray8 0/255) and its integral image are kept by the stage
// for the face detector (masked scan) and the HUD.

#include "vision/geometry.hpp"
#include "vision/integral_image.hpp"
#include "vision/motion_detector.hpp"
#include "vision/stage.hpp"

namespace vision {

struct MotionStageOptions {
    int downscale = 2;  ///< 1..4: 720x480 -> 360x240 at 2
    MotionDetectorOptions detector{};
};

class MotionStage final : public Stage {
public:
    /// For camera frames of `frameSize`; allocates the model, grey image, mask and integral image
    /// at frameSize / downscale. Throws std::runtime_error on bad options.
    MotionStage(Size frameSize, const MotionStageOptions& options = {});

    const char* name() const noexcept override { return "motion"; }
    /// Skips invalid frames. A frame of another size or format leaves ok() false, lastError()
    /// set and the mask all 0; the frame itself stays valid for the other stages.
    void process(FrameState& state) noexcept override;

    /// True when the last processed frame produced a mask.
    bool ok() const noexcept { return ok_; }
    const char* lastError() const noexcept { return error_; }
    /// The foreground mask of the last frame at the reduced size (255 = moving).
    ConstImageView mask() const noexcept { return mask_.view(); }
    /// The reduced grey frame the mask was computed from.
    ConstImageView gray() const noexcept { return gray_.view(); }
    const IntegralImage& maskIntegral() const noexcept { return integral_; }
    /// Foreground pixels in the last mask.
    int foregroundPixels() const noexcept { return foreground_; }
    /// Full-resolution pixels per mask pixel along each axis.
    int downscale() const noexcept { return downscale_; }
    /// A point of the reduced grey frame in frame coordinates (pixel centres: x_frame =
    /// (x + 0.5) * k - 0.5 for the integer factor k); lengths scale by downscale().
    Point2f toFrame(Point2f p) const noexcept
    {
        const float k = static_cast<float>(downscale_);
        const float shift = 0.5f * k - 0.5f;
        return {p.x * k + shift, p.y * k + shift};
    }
    MotionDetector& detector() noexcept { return detector_; }

private:
    int downscale_;
    MotionDetector detector_;
    ImageBuffer gray_;
    ImageBuffer mask_;
    IntegralImage integral_;
    int foreground_ = 0;
    bool ok_ = false;
    char error_[64] = "";
};

}  // namespace vision
