#include "vision/scene_cut.hpp"

namespace vision {

bool SceneCut::update(int foregroundPixels, int pixels) noexcept
{
    if (pixels <= 0 || foregroundPixels < 0) {
        reset();
        return false;
    }
    const float fraction = static_cast<float>(foregroundPixels) / static_cast<float>(pixels);
    const bool cut =
        frames_ >= kWarmUpFrames && fraction >= kMinFraction && fraction - previous_ >= kMinJump;
    previous_ = fraction;
    frames_ = frames_ < kWarmUpFrames ? frames_ + 1 : frames_;
    return cut;
}

}  // namespace vision
