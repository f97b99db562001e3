#include "vision/deinterlace_stage.hpp"

#include "vision/deinterlace.hpp"

namespace vision {

DeinterlaceStage::DeinterlaceStage(Size size, PixelFormat format)
    : frame_(size.width, size.height, format)
{
}

void DeinterlaceStage::process(FrameState& state) noexcept
{
    const ImageView out = frame_.view();
    if (!deinterlace(state.frame.image, out)) {
        state.valid = false;
        state.problem = "deinterlace: frame size or format differs from the configured one";
        return;
    }
    state.frame.image = out;
}

}  // namespace vision
