#include "vision/card_stage.hpp"

#include <algorithm>
#include <cmath>

namespace vision {

Rect centralRegion(Size size, float fraction) noexcept
{
    const float f = std::clamp(fraction, 0.f, 1.f);
    const int w = std::max(1, static_cast<int>(std::lround(static_cast<float>(size.width) * f)));
    const int h = std::max(1, static_cast<int>(std::lround(static_cast<float>(size.height) * f)));
    return {(size.width - w) / 2, (size.height - h) / 2, w, h};
}

CardStage::CardStage(Size size, const CardTrackerOptions& options, const CardTrainingLimits& limits)
    : tracker_(size, options), limits_(limits)
{
}

void CardStage::requestTraining(float centralFraction) noexcept
{
    pending_.store(std::clamp(centralFraction, 0.01f, 1.f));
}

void CardStage::process(FrameState& state) noexcept
{
    if (state.chroma.r.empty()) {
        // Without chromaticity there is nothing to test; the frame is still usable by others.
        state.card = nullptr;
        return;
    }
    const ConstImageView& rgb = state.frame.image;
    const float fraction = pending_.exchange(0.f);
    if (fraction > 0.f) {
        // Step 1 only on a region that is the card: anything else would be learnt for good.
        const Rect region = centralRegion(rgb.size(), fraction);
        lastCheck_ = checkCardTrainingRegion(rgb, state.chroma, region, limits_);
        lastTrainingOk_ = lastCheck_.ok() && tracker_.train(rgb, state.chroma, region);
    }
    state.card = &tracker_.process(rgb, state.chroma);
}

}  // namespace vision
