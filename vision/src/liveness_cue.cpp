#include "vision/liveness_cue.hpp"

#include <algorithm>
#include <cmath>

// How the thresholds were chosen (`mirror-eval liveness`, corners and flow as the tracker has
// them, on truth boxes; a window starting at every frame of every face):
//  - living: the FGNet talking face (999 windows), and the same frames at 360x288 and JPEG
//    quality 60, as its 360x288 video has them. The summed median flow after 1 step: median
//    0.18 px, a tenth of the windows under 0.031 px (a calm person: 0.01-0.03 px per frame);
//  - prints: facegen's static faces (seeds 1, 7, 23, every scenario, passers-by included) and
//    FGNet frames 0, 400 and 640 held still under camera noise (sigma 3-6), a light drift and
//    JPEG (quality 60-85, 720x576 and 360x288; two of them 3000 frames long). With every half
//    following (kMinHalfShare), their summed median reaches at most 0.031 px after 1 step, 0.042
//    after 3, 0.070 after 6 and 0.12 after 12: the changing light biases the flow of a print's
//    strong edges by up to 0.01 px per frame, the same way frame after frame. Its noise (the
//    median of 40 corners' flows) is 0.001-0.009 px a step. A passer-by alone drags a print's
//    median as far as a calm head's (up to 0.28 px in a step), but only on its side: its halves
//    share little of it.
// With the thresholds below, FGNet's windows swayed within 1 step in 75% of the windows, 2 in
// 86%, 3 in 91%, 6 in 98% and 12 in 100% (the 360x288 copy: 70%, 83%, 88%, 96%, 99.6%); no
// print's window did. At 0.7 of their values, 3 of the 2975 windows of the noisiest print did.
// A print on a camera that shakes moves all its corners as one, as a head does: the tracker gives
// the cue a face's flow less the view's (BackgroundMotion), and no step of a frame in which the
// camera moved the view by more than a quarter pixel (StaticFaceRule::addFlowStep).

namespace vision {

namespace {

constexpr float kMinSway = 0.04f;          ///< pixels, whatever the number of steps
constexpr float kSwayPerStep = 0.01f;      ///< pixels per step more (the light's drift)
constexpr float kMinSwayOverNoise = 4.5f;  ///< summed median / its noise
/// A median of n noisy flows has pi / 2 times the variance of their mean.
constexpr double kMedianVariance = 1.5707963;
constexpr float kMinHalfShare = 0.3f;  ///< of the sway each half followed at least
/// Corners a half needs for its median to count (fewer: that half did not move).
constexpr int kMinHalfCorners = 2;

float dot(Point2f a, Point2f b) noexcept
{
    return a.x * b.x + a.y * b.y;
}

}  // namespace

void SwayHistory::push(const Step& step) noexcept
{
    steps_[static_cast<std::size_t>(next_)] = step;
    next_ = (next_ + 1) % kSteps;
    count_ = std::min(count_ + 1, kSteps);
}

const SwayHistory::Step& SwayHistory::latest(int k) const noexcept
{
    return steps_[static_cast<std::size_t>((next_ - 1 - k + 2 * kSteps) % kSteps)];
}

bool LivenessCue::medianFlow(std::span<const Point2f> from, std::span<const Point2f> to,
                             std::span<const std::uint8_t> inliers, Point2f centre, int half,
                             int least, Point2f& flow) noexcept
{
    std::size_t n = 0;
    const std::size_t pairs = std::min({from.size(), to.size(), inliers.size(), dx_.size()});
    for (std::size_t i = 0; i < pairs; ++i) {
        const float side = half < 2 ? from[i].x - centre.x : from[i].y - centre.y;
        const bool onSide = half < 0 || (half % 2 == 0 ? side < 0.f : side >= 0.f);
        if (!inliers[i] || !onSide)
            continue;
        dx_[n] = to[i].x - from[i].x;
        dy_[n] = to[i].y - from[i].y;
        ++n;
    }
    if (static_cast<int>(n) < least)
        return false;
    const auto mid = static_cast<std::ptrdiff_t>(n / 2);
    std::nth_element(dx_.begin(), dx_.begin() + mid, dx_.begin() + static_cast<std::ptrdiff_t>(n));
    std::nth_element(dy_.begin(), dy_.begin() + mid, dy_.begin() + static_cast<std::ptrdiff_t>(n));
    flow = {dx_[n / 2], dy_[n / 2]};
    return true;
}

void LivenessCue::addFlowStep(SwayHistory& history, std::span<const Point2f> from,
                              std::span<const Point2f> to, std::span<const std::uint8_t> inliers,
                              const MotionModel& model, Point2f view) noexcept
{
    SwayHistory::Step step;
    step.view = view;
    if (!medianFlow(from, to, inliers, model.centre, -1, 3, step.common))
        return;
    // The noise of the median: the corners' scatter about the fit, over their number.
    const std::size_t pairs = std::min({from.size(), to.size(), inliers.size(), dx_.size()});
    double scatter = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < pairs; ++i) {
        if (!inliers[i])
            continue;
        const Point2f p = model.apply(from[i]);
        const double ex = to[i].x - p.x, ey = to[i].y - p.y;
        scatter += 0.5 * (ex * ex + ey * ey);
        ++n;
    }
    step.variance = static_cast<float>(kMedianVariance * scatter / n / n);
    for (int h = 0; h < 4; ++h)
        medianFlow(from, to, inliers, model.centre, h, kMinHalfCorners,
                   step.halves[static_cast<std::size_t>(h)]);
    history.push(step);
}

bool LivenessCue::swayed(const SwayHistory& history) noexcept
{
    // Every span of the latest steps: a sway shows in a few frames, a print's drift only over
    // many, and a calm head may have swayed a moment ago and not since.
    Point2f sum{};
    Point2f view{};
    std::array<Point2f, 4> halves{};
    float variance = 0.f;
    for (int k = 0; k < history.size(); ++k) {
        const SwayHistory::Step& s = history.latest(k);
        sum = {sum.x + s.common.x, sum.y + s.common.y};
        view = {view.x + s.view.x, view.y + s.view.y};
        for (std::size_t h = 0; h < halves.size(); ++h)
            halves[h] = {halves[h].x + s.halves[h].x, halves[h].y + s.halves[h].y};
        variance += s.variance;
        const float sway2 = dot(sum, sum);
        // The view's motion taken off the flow may be wrong by as much as it is: on a still
        // camera, a face coming in untracked at the edge biased it by 0.02-0.1 px a frame for a
        // few frames, and a print's corrected corners swayed together by as much (facegen seeds
        // 21 and 57's `enter-leave`: a print shown for the rest of the sequence).
        const float least =
            kMinSway + kSwayPerStep * static_cast<float>(k + 1) + std::sqrt(dot(view, view));
        if (sway2 < least * least || sway2 < kMinSwayOverNoise * kMinSwayOverNoise * variance)
            continue;
        bool shared = true;
        for (const Point2f& h : halves)
            shared = shared && dot(h, sum) >= kMinHalfShare * sway2;
        if (shared)
            return true;
    }
    return false;
}

bool LivenessCue::stirred(const SwayHistory& history) noexcept
{
    if (history.size() == 0)
        return false;
    const Point2f m = history.latest(0).common;
    return dot(m, m) >= kMinSway * kMinSway;
}

}  // namespace vision
