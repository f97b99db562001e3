#pragma once
// CardStage: runs the colour-card tracker (§2) on every frame and publishes its observation in
// FrameState::card. Needs the chromaticity stage before it (FrameState::chroma).
//
// Training is a product feature: requestTraining() (from the console command `card train` or a
// button, possibly on another thread) makes the NEXT frame train the colour model on its central
// region, then that frame is tracked as usual. A region that is not one uniform, saturated, lit
// colour (checkCardTrainingRegion) is refused: the model trained before stays.

#include "vision/card_tracker.hpp"
#include "vision/card_training_check.hpp"
#include "vision/stage.hpp"

#include <atomic>

namespace vision {

class CardStage final : public Stage {
public:
    explicit CardStage(Size size, const CardTrackerOptions& options = {},
                       const CardTrainingLimits& limits = {});
    const char* name() const noexcept override { return "card"; }
    void process(FrameState& state) noexcept override;

    /// The next frame trains on the central `centralFraction` (0..1] of its width and height.
    void requestTraining(float centralFraction) noexcept;
    /// True between requestTraining() and the frame that trained.
    bool trainingPending() const noexcept { return pending_.load() > 0.f; }
    /// Result of the last training: false when it failed (no chromaticity planes) or the region
    /// was refused (lastTrainingCheck() says why).
    bool lastTrainingSucceeded() const noexcept { return lastTrainingOk_; }
    /// The measurements of the region the last training looked at.
    const CardTrainingCheck& lastTrainingCheck() const noexcept { return lastCheck_; }

    CardTracker& tracker() noexcept { return tracker_; }
    const CardTracker& tracker() const noexcept { return tracker_; }

private:
    CardTracker tracker_;
    CardTrainingLimits limits_;
    std::atomic<float> pending_{0.f};  // > 0: fraction to train on at the next frame
    bool lastTrainingOk_ = false;
    CardTrainingCheck lastCheck_;
};

/// The central `fraction` of a frame of `size` (at least one pixel).
Rect centralRegion(Size size, float fraction) noexcept;

}  // namespace vision
