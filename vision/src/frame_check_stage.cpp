#include "vision/frame_check_stage.hpp"

namespace vision {

void FrameCheckStage::process(FrameState& state) noexcept
{
    const ConstImageView& img = state.frame.image;
    if (img.data == nullptr)
        state.problem = "frame has no data";
    else if (img.size() != expected_)
        state.problem = "frame size differs from the configured size";
    else if (img.format != format_)
        state.problem = "frame format differs from the source's format";
    else if (img.stride < img.width * bytesPerPixel(img.format))
        state.problem = "frame stride is smaller than a row";
    else
        return;
    state.valid = false;
}

}  // namespace vision
