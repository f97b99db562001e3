#pragma once
// One-Euro filter (Casiez, Roussel, Vogel 2012) for the card's corners: a first-order low-pass
// whose cutoff rises with the signal's speed, so a card at rest does not jitter (low cutoff) and a
// moving card does not lag (high cutoff).

namespace vision {

class OneEuroFilter {
public:
    /// minCutoffHz: cutoff at rest; beta: cutoff increase per unit/s of speed; derivativeCutoffHz:
    /// low-pass on the speed estimate.
    OneEuroFilter(float minCutoffHz = 1.f, float beta = 0.05f,
                  float derivativeCutoffHz = 1.f) noexcept;

    /// Filters one sample taken `dt` seconds after the previous one. The first sample after
    /// construction or reset() passes through unchanged.
    float filter(float x, float dt) noexcept;
    void reset() noexcept { initialized_ = false; }
    float value() const noexcept { return x_; }

    void setParameters(float minCutoffHz, float beta, float derivativeCutoffHz) noexcept;

private:
    float minCutoff_, beta_, dCutoff_;
    float x_ = 0.f, dx_ = 0.f;
    bool initialized_ = false;
};

}  // namespace vision
