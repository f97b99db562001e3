#include "vision/one_euro_filter.hpp"

#include <cmath>
#include <numbers>

namespace vision {

namespace {

float smoothingFactor(float cutoffHz, float dt) noexcept
{
    const float tau = 1.f / (2.f * std::numbers::pi_v<float> * cutoffHz);
    return 1.f / (1.f + tau / dt);
}

}  // namespace

OneEuroFilter::OneEuroFilter(float minCutoffHz, float beta, float derivativeCutoffHz) noexcept
    : minCutoff_(minCutoffHz), beta_(beta), dCutoff_(derivativeCutoffHz)
{
}

void OneEuroFilter::setParameters(float minCutoffHz, float beta, float derivativeCutoffHz) noexcept
{
    minCutoff_ = minCutoffHz;
    beta_ = beta;
    dCutoff_ = derivativeCutoffHz;
}

float OneEuroFilter::filter(float x, float dt) noexcept
{
    if (!initialized_ || !(dt > 0.f) || !std::isfinite(x)) {
        if (std::isfinite(x)) {
            x_ = x;
            dx_ = 0.f;
            initialized_ = true;
        }
        return x_;
    }
    const float dx = (x - x_) / dt;
    dx_ += smoothingFactor(dCutoff_, dt) * (dx - dx_);
    const float cutoff = minCutoff_ + beta_ * std::fabs(dx_);
    x_ += smoothingFactor(cutoff, dt) * (x - x_);
    return x_;
}

}  // namespace vision
