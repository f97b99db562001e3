#include "vision/motion_stage.hpp"

#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace vision {

namespace {

Size reduced(Size frameSize, int downscale)
{
    if (downscale < 1 || downscale > 4) {
        throw std::runtime_error("MotionStage: downscale must be 1..4");
    }
    return {frameSize.width / downscale, frameSize.height / downscale};
}

}  // namespace

MotionStage::MotionStage(Size frameSize, const MotionStageOptions& options)
    : downscale_(options.downscale),
      detector_(reduced(frameSize, options.downscale), options.detector),
      gray_(detector_.size().width, detector_.size().height, PixelFormat::Gray8),
      mask_(detector_.size().width, detector_.size().height, PixelFormat::Gray8),
      integral_(detector_.size())
{
    std::memset(mask_.view().data, 0, mask_.bytes());
    integral_.compute(mask_.view());
}

void MotionStage::process(FrameState& state) noexcept
{
    if (!state.valid) {
        return;
    }
    ok_ = downscaleToGray(state.frame.image, downscale_, gray_.view());
    if (ok_) {
        foreground_ = detector_.apply(gray_.view(), mask_.view());
        ok_ = foreground_ >= 0;
    }
    if (!ok_) {
        const ConstImageView& im = state.frame.image;
        std::snprintf(error_, sizeof error_, "motion: cannot use a %dx%d %s frame", im.width,
                      im.height, pixelFormatName(im.format));
        std::memset(mask_.view().data, 0, mask_.bytes());
        foreground_ = 0;
    } else {
        error_[0] = '\0';
    }
    integral_.compute(mask_.view());
    if (ok_)
        state.motionMask = mask_.view();
}

}  // namespace vision
