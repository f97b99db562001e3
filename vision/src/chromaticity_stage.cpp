#include "vision/chromaticity_stage.hpp"

namespace vision {

ChromaticityStage::ChromaticityStage(Size size)
    : table_(std::make_unique<ChromaticityTable>()),
      r_(size.width, size.height, PixelFormat::Gray8),
      g_(size.width, size.height, PixelFormat::Gray8),
      b_(size.width, size.height, PixelFormat::Gray8)
{
}

void ChromaticityStage::process(FrameState& state) noexcept
{
    const ChromaticityPlanes planes{r_.view(), g_.view(), b_.view()};
    if (convertChromaticity(*table_, state.frame.image, planes)) {
        state.chroma = planes;
    } else {
        state.valid = false;
        state.problem = "chromaticity: unsupported pixel format";
    }
}

}  // namespace vision
