// Roll by the point symmetry of a face's corners (§4), and the dissertation's line-fit baseline.
//
// Why the defaults of RollEstimatorOptions:
//  - Angles: the detector finds faces up to ~20 degrees from vertical, so +-30 covers it; whole
//    steps as in the dissertation, then a golden-section refinement on [best - step, best + step].
//  - trimFraction: hair, collar and background corners have no mirror partner; with the plain
//    mean (0, the dissertation's) a few of them decide the angle, trimmed they are not counted.
//  - capFraction (a truncated mean): an unmatched point costs a fixed penalty however far it
//    lands. Trimming, cap and axis offsets together halve the mean error on the rotated IMM
//    faces (about 5 -> 2.5 degrees, see the peer test). Weighting points by their distance from
//    the centre (the lever arm) was tried and made it worse (about 2.3 -> 3.1 degrees): the outer
//    points are the ones most often hair and background.
//  - Axis offsets: the box centre need not lie on the face's axis (detectors are off by a few
//    pixels, more for rotated faces), so the axis is also shifted sideways; with boxes 5% off
//    centre this matters most (about 6.6 -> 2.3 degrees mean error). 0: through the centre only.

#include "vision/roll_estimator.hpp"

#include "golden_section.hpp"
#include "vision/geometry.hpp"

#include <algorithm>
#include <cmath>

namespace vision {

namespace {

constexpr int kMaxAngles = 721;      // candidate angles scored for the confidence
constexpr int kMaxAxisOffsets = 21;  // 2 * 10 + 1 sideways axis positions

/// The points in the candidate upright frame: rotated by -roll about the centre, relative to it.
struct UprightPoints {
    float x[kMaxRollPoints];
    float y[kMaxRollPoints];
    int n = 0;
};

void makeUpright(std::span<const Point2f> points, Point2f centre, float rollDegrees,
                 UprightPoints& out) noexcept
{
    const float a = toRadians(rollDegrees);
    const float c = std::cos(a), s = std::sin(a);
    out.n = static_cast<int>(std::min<std::size_t>(points.size(), kMaxRollPoints));
    for (int i = 0; i < out.n; ++i) {
        const float dx = points[i].x - centre.x, dy = points[i].y - centre.y;
        // Inverse of x' = c x - s y, y' = s x + c y.
        out.x[i] = c * dx + s * dy;
        out.y[i] = -s * dx + c * dy;
    }
}

/// Trimmed, capped mean nearest distance of the points reflected across x = offset.
float reflectedScore(const UprightPoints& p, float offset, float trimFraction, float cap) noexcept
{
    if (p.n == 0)
        return 0.f;
    float nearest[kMaxRollPoints];
    const float cap2 = cap > 0.f ? cap * cap : INFINITY;
    for (int i = 0; i < p.n; ++i) {
        const float rx = 2.f * offset - p.x[i], ry = p.y[i];
        float best = cap2;
        for (int j = 0; j < p.n; ++j) {
            const float dx = rx - p.x[j], dy = ry - p.y[j];
            best = std::min(best, dx * dx + dy * dy);
        }
        nearest[i] = best;  // squared for now; sqrt only of the kept ones
    }
    const int drop = static_cast<int>(std::clamp(trimFraction, 0.f, 0.9f) * p.n);
    const int keep = std::max(1, p.n - drop);
    if (keep < p.n)
        std::nth_element(nearest, nearest + keep, nearest + p.n);
    float sum = 0.f;
    for (int i = 0; i < keep; ++i)
        sum += std::sqrt(nearest[i]);
    return sum / static_cast<float>(keep);
}

/// Best score over the sideways axis positions at one angle.
float angleScore(std::span<const Point2f> points, Point2f centre, float rollDegrees,
                 const float* offsets, int offsetCount, float trimFraction, float cap) noexcept
{
    UprightPoints upright;
    makeUpright(points, centre, rollDegrees, upright);
    float best = INFINITY;
    for (int k = 0; k < offsetCount; ++k)
        best = std::min(best, reflectedScore(upright, offsets[k], trimFraction, cap));
    return best;
}

}  // namespace

float symmetryDistance(std::span<const Point2f> points, Point2f centre, float rollDegrees,
                       float offset, float trimFraction, float cap) noexcept
{
    UprightPoints upright;
    makeUpright(points, centre, rollDegrees, upright);
    return reflectedScore(upright, offset, trimFraction, cap);
}

RollEstimate estimateRollBySymmetry(std::span<const Point2f> points, Point2f centre, float boxSize,
                                    const RollEstimatorOptions& options) noexcept
{
    RollEstimate result;
    result.points = static_cast<int>(std::min<std::size_t>(points.size(), kMaxRollPoints));
    if (result.points < 3 || !(boxSize > 0.f) || !(options.stepDegrees > 0.f) ||
        !(options.maxDegrees >= options.minDegrees))
        return result;
    points = points.first(static_cast<std::size_t>(result.points));

    float offsets[kMaxAxisOffsets];
    const int steps = std::clamp(options.axisOffsetSteps, 0, (kMaxAxisOffsets - 1) / 2);
    const float maxOffset = std::max(0.f, options.maxAxisOffsetFraction) * boxSize;
    int offsetCount = 0;
    if (steps == 0 || maxOffset <= 0.f) {
        offsets[offsetCount++] = 0.f;
    } else {
        for (int k = -steps; k <= steps; ++k)
            offsets[offsetCount++] = maxOffset * static_cast<float>(k) / static_cast<float>(steps);
    }
    const float cap = options.capFraction > 0.f ? options.capFraction * boxSize : 0.f;
    const float trim = options.trimFraction;
    auto score = [&](float degrees) {
        return angleScore(points, centre, degrees, offsets, offsetCount, trim, cap);
    };

    // Whole-step scan.
    const float span = options.maxDegrees - options.minDegrees;
    const float step = std::max(options.stepDegrees, span / static_cast<float>(kMaxAngles - 1));
    // At least the first angle, so scores[bestIndex] is always written (an empty or inverted range
    // scans minDegrees alone).
    const int count =
        std::clamp(static_cast<int>(std::floor(span / step + 1e-4f)) + 1, 1, kMaxAngles);
    float scores[kMaxAngles] = {};
    int bestIndex = 0;
    for (int i = 0; i < count; ++i) {
        scores[i] = score(options.minDegrees + step * static_cast<float>(i));
        if (scores[i] < scores[bestIndex])
            bestIndex = i;
    }
    float bestDegrees = options.minDegrees + step * static_cast<float>(bestIndex);
    float bestScore = scores[bestIndex];

    // Sub-step refinement: golden-section search between the neighbouring steps. The score is a
    // sum of nearest-point distances, V-shaped rather than parabolic near its minimum, so a
    // parabola through three samples would be biased towards the whole step; golden section is
    // not. The result is kept only when it scores at least as well as the whole step.
    if (options.refineToleranceDegrees > 0.f && count > 1) {
        const GoldenSectionBracket g =
            goldenSection(std::max(options.minDegrees, bestDegrees - step),
                          std::min(options.maxDegrees, bestDegrees + step),
                          options.refineToleranceDegrees, score, 40);
        const float mid = 0.5f * (g.lo + g.hi);
        const float fmid = score(mid);
        if (fmid <= bestScore) {
            bestDegrees = mid;
            bestScore = fmid;
        }
    }

    // Confidence: how much better the best angle is than a typical one (the median score). A
    // point set that looks alike at every angle (a ring, a blob) has no roll to offer.
    std::nth_element(scores, scores + count / 2, scores + count);
    const float typical = scores[count / 2];
    result.rollDegrees = bestDegrees;
    result.symmetryDistance = bestScore / boxSize;
    result.confidence =
        typical > 1e-6f * boxSize ? std::clamp(1.f - bestScore / typical, 0.f, 1.f) : 0.f;
    return result;
}

RollEstimate estimateRollByLineFit(std::span<const Point2f> points) noexcept
{
    RollEstimate result;
    result.points = static_cast<int>(std::min<std::size_t>(points.size(), kMaxRollPoints));
    if (result.points < 2)
        return result;
    double sx = 0.0, sy = 0.0;
    for (int i = 0; i < result.points; ++i) {
        sx += points[i].x;
        sy += points[i].y;
    }
    const double mx = sx / result.points, my = sy / result.points;
    double mu20 = 0.0, mu02 = 0.0, mu11 = 0.0;
    for (int i = 0; i < result.points; ++i) {
        const double dx = points[i].x - mx, dy = points[i].y - my;
        mu20 += dx * dx;
        mu02 += dy * dy;
        mu11 += dx * dy;
    }
    // The orthogonal least-squares line is the scatter matrix's major axis (Eq. 39's angle).
    const double trace = mu20 + mu02;
    const double spread = std::sqrt((mu20 - mu02) * (mu20 - mu02) + 4.0 * mu11 * mu11);
    if (!(trace > 1e-12))
        return result;
    double degrees = 0.5 * std::atan2(2.0 * mu11, mu20 - mu02) / kRadiansPerDegree;
    // A face's axes are only known up to a multiple of 90 degrees: fold into [-45, 45).
    degrees = degrees - 90.0 * std::floor((degrees + 45.0) / 90.0);
    result.rollDegrees = static_cast<float>(degrees);
    result.confidence = static_cast<float>(spread / trace);
    return result;
}

}  // namespace vision
