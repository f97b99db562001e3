// RollByImageSymmetry: coarse-to-fine search for the angle at which the face patch best matches
// its own mirror image and its features lie along the rows.
//
// How the defaults (RollByImageSymmetryOptions) were chosen. They were developed on the IMM faces
// rotated synthetically (tests/peer/roll_image_symmetry_peer_test.cpp: about 1.2 degrees mean
// error, every face within 5). IMM does not tell the last knobs apart, so patch 40 (rather than
// 32), axis offset 0.15 (the detector's boxes sit ~0.1 of their side off the face centre) and
// gradient saturation 8 were picked on `mirror-eval roll` with seeds 7 and 11, and blurPasses 2
// and rowCoherenceWeight 0.5 with seeds 7, 11 and 42 (checked on 3, 99, 123, 500), never on the
// reported 2006/2007.
//  - supersample: large faces would alias into the small patch without it.
//  - blurPasses 2 rather than 1 (with the row cue): CMU/MIT set A 3.55 -> 3.27 deg mean error
//    over seeds 7, 11, 42, 3, 99, 123, 500 (B 3.49 -> 3.50); IMM unchanged; FGNet tracking roll
//    +0.1 deg.
//  - The mirror axis is searched in half-pixel steps, then continuously (golden section).
//  - The compared region keeps to the face, not the background at the patch's corners.
//  - gradientSaturation: one strong edge (hair against a wall, a collar) must not outweigh the
//    eyes, nose and mouth.
//  - axisWeightSigma: weighting the middle of the face (nose, mouth, inner eyes) over its outline
//    made CMU/MIT set A worse with saturation on (0.2: 3.7 -> 4.3 deg), so it is off.
//  - The row cue, the row coherence of the vertical derivatives (1 when, along every row of the
//    compared region, they share their sign: the brows, eyes, nostrils and mouth lie along the
//    rows), scores each angle as asymmetry + weight x (1 - coherence). Symmetry alone drifts on
//    faces whose halves differ (a turned head, one-sided light, hair); the rows do not care about
//    left and right. The weight was picked on CMU/MIT seeds 7, 11, 42 among 0.3-1.0 (0.4-0.6
//    alike; 1.0 lets the rows win on their own).
//  - The row cue joins only when the symmetry alone is less sure than rowCueBelowConfidence (its
//    confidence: 1 - best / median asymmetry of the coarse scan). On a clear face it would only
//    add its own bias, the eye line not being square to the eye-mouth axis on every face: always
//    on, the FGNet tracking roll error went 2.45 -> 3.08 deg; gated at 0.3, 2.57, while CMU/MIT
//    kept its gain (0.2 lost some on set A, 0.25-0.4 alike).

#include "vision/roll_by_image_symmetry.hpp"

#include "golden_section.hpp"
#include "symmetry_pairs.hpp"
#include "vision/upright_patch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace vision {

namespace {

constexpr int kMaxCoarseAngles = 512;

}  // namespace

RollByImageSymmetry::RollByImageSymmetry(const RollByImageSymmetryOptions& options)
    : options_(options)
{
    const auto& o = options_;
    if (o.patchSize < 8 || o.patchSize > 256)
        throw std::invalid_argument("RollByImageSymmetry: patchSize must be in [8, 256]");
    if (o.supersample < 1 || o.supersample > 8)
        throw std::invalid_argument("RollByImageSymmetry: supersample must be in [1, 8]");
    if (o.blurPasses < 0 || o.blurPasses > 8)
        throw std::invalid_argument("RollByImageSymmetry: blurPasses must be in [0, 8]");
    if (!(o.boxScale > 0.f && o.boxScale <= 4.f))
        throw std::invalid_argument("RollByImageSymmetry: boxScale must be in (0, 4]");
    if (!(o.coarseStepDegrees > 0.f) || !(o.maxDegrees >= o.minDegrees) ||
        !std::isfinite(o.minDegrees) || !std::isfinite(o.maxDegrees) ||
        (o.maxDegrees - o.minDegrees) / o.coarseStepDegrees >= kMaxCoarseAngles - 3)
        throw std::invalid_argument(
            "RollByImageSymmetry: need minDegrees <= maxDegrees and at most 509 coarse steps");
    if (!(o.refineToleranceDegrees >= 0.f))
        throw std::invalid_argument("RollByImageSymmetry: refineToleranceDegrees must be >= 0");
    if (!(o.maxAxisOffsetFraction >= 0.f && o.maxAxisOffsetFraction <= 0.25f))
        throw std::invalid_argument(
            "RollByImageSymmetry: maxAxisOffsetFraction must be in [0, "
            "0.25]");
    if (!(o.regionHalfWidthFraction > 0.f && o.regionHalfWidthFraction <= 0.5f) ||
        !(o.regionTop >= 0.f && o.regionTop < o.regionBottom && o.regionBottom <= 1.f))
        throw std::invalid_argument("RollByImageSymmetry: region must lie inside the patch");
    n_ = o.patchSize;
    maxShift_ =
        static_cast<int>(std::lround(2.f * o.maxAxisOffsetFraction * static_cast<float>(n_)));
    const int big = n_ * o.supersample;
    big_ = ImageBuffer(big, big, PixelFormat::Gray8);
    const auto cells = static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_);
    patch_.assign(cells, 0.f);
    tmp_.assign(cells, 0.f);
    a_.assign(cells, 0.f);
    b_.assign(cells, 0.f);
    weight_.assign(static_cast<std::size_t>(2 * n_ + 2 * maxShift_ + 2), 1.f);
    uniformWeights_ = !(o.axisWeightSigma > 0.f);
    if (o.axisWeightSigma > 0.f) {
        const float sigma2 = 2.f * o.axisWeightSigma * static_cast<float>(n_);  // in |x - x'| units
        for (std::size_t d = 0; d < weight_.size(); ++d) {
            const float t = static_cast<float>(d) / sigma2;
            weight_[d] = std::exp(-0.5f * t * t);
        }
    }
    if (!(o.gradientSaturation >= 0.f) || !(o.axisWeightSigma >= 0.f) ||
        !(o.rowCoherenceWeight >= 0.f) || !std::isfinite(o.rowCoherenceWeight) ||
        !std::isfinite(o.rowCueBelowConfidence))
        throw std::invalid_argument(
            "RollByImageSymmetry: gradientSaturation, axisWeightSigma and rowCoherenceWeight "
            "must be >= 0, rowCueBelowConfidence finite");
}

void RollByImageSymmetry::boxAverage(const ImageView& big, int s) noexcept
{
    // The supersampled warp's s x s blocks averaged down to the patch. The sums are small whole
    // numbers, exact in float in any order.
    const int n = n_;
    const float inv = 1.f / static_cast<float>(s * s);
    for (int y = 0; y < n; ++y) {
        float* out = &patch_[static_cast<std::size_t>(y * n)];
        if (s == 1) {
            const std::uint8_t* in = big.row(y);
            for (int x = 0; x < n; ++x)
                out[x] = static_cast<float>(in[x]);
            continue;
        }
        if (s == 2) {
            const std::uint8_t* in0 = big.row(2 * y);
            const std::uint8_t* in1 = big.row(2 * y + 1);
            for (int x = 0; x < n; ++x)
                out[x] = static_cast<float>(in0[2 * x] + in0[2 * x + 1] + in1[2 * x] +
                                            in1[2 * x + 1]) *
                         inv;
            continue;
        }
        for (int x = 0; x < n; ++x) {
            int sum = 0;
            for (int dy = 0; dy < s; ++dy) {
                const std::uint8_t* in = big.row(y * s + dy) + x * s;
                for (int dx = 0; dx < s; ++dx)
                    sum += in[dx];
            }
            out[x] = static_cast<float>(sum) * inv;
        }
    }
}

void RollByImageSymmetry::blur121() noexcept
{
    // One [1 2 1] pass each way, the border repeated: the comparison is about features, not
    // pixel noise. The border columns apart, so the row loop has no clamps (the same sums).
    const int n = n_;
    for (int y = 0; y < n; ++y) {
        const float* in = &patch_[static_cast<std::size_t>(y * n)];
        float* out = &tmp_[static_cast<std::size_t>(y * n)];
        out[0] = 0.25f * (in[0] + 2.f * in[0] + in[1]);
        for (int x = 1; x < n - 1; ++x)
            out[x] = 0.25f * (in[x - 1] + 2.f * in[x] + in[x + 1]);
        out[n - 1] = 0.25f * (in[n - 2] + 2.f * in[n - 1] + in[n - 1]);
    }
    for (int y = 0; y < n; ++y) {
        const float* up = &tmp_[static_cast<std::size_t>(std::max(y - 1, 0) * n)];
        const float* mid = &tmp_[static_cast<std::size_t>(y * n)];
        const float* down = &tmp_[static_cast<std::size_t>(std::min(y + 1, n - 1) * n)];
        float* out = &patch_[static_cast<std::size_t>(y * n)];
        for (int x = 0; x < n; ++x)
            out[x] = 0.25f * (up[x] + 2.f * mid[x] + down[x]);
    }
}

void RollByImageSymmetry::gradients() noexcept
{
    // Central differences inside the patch, 0 on its border; saturated so that one strong edge
    // does not outweigh the eyes, nose and mouth.
    const int n = n_;
    const bool saturate = options_.gradientSaturation > 0.f;
    const float invSat = saturate ? 1.f / options_.gradientSaturation : 0.f;
    std::fill_n(a_.begin(), n, 0.f);
    std::fill_n(b_.begin(), n, 0.f);
    std::fill_n(a_.end() - n, n, 0.f);
    std::fill_n(b_.end() - n, n, 0.f);
    for (int y = 1; y < n - 1; ++y) {
        const float* p = &patch_[static_cast<std::size_t>(y * n)];
        float* gx = &a_[static_cast<std::size_t>(y * n)];
        float* gy = &b_[static_cast<std::size_t>(y * n)];
        gx[0] = gy[0] = gx[n - 1] = gy[n - 1] = 0.f;
        for (int x = 1; x < n - 1; ++x) {
            gx[x] = p[x + 1] - p[x - 1];
            gy[x] = p[x + n] - p[x - n];
        }
        if (saturate) {
            for (int x = 1; x < n - 1; ++x) {
                gx[x] /= 1.f + std::fabs(gx[x]) * invSat;
                gy[x] /= 1.f + std::fabs(gy[x]) * invSat;
            }
        }
    }
}

bool RollByImageSymmetry::prepare(const ConstImageView& gray, Point2f centre, float boxSize,
                                  float rollDegrees) noexcept
{
    const int n = n_;
    // Supersampling only pays where the square has more pixels than the patch: a small face is
    // warped straight into it.
    const float side = boxSize * options_.boxScale;
    const int s = std::clamp(static_cast<int>(std::ceil(side / static_cast<float>(n) - 0.25f)), 1,
                             options_.supersample);
    ImageView big = big_.view();
    big.width = n * s;
    big.height = n * s;
    if (!warpUpright(gray, centre, rollDegrees, side, big))
        return false;

    boxAverage(big, s);
    for (int pass = 0; pass < options_.blurPasses; ++pass)
        blur121();

    if (options_.feature == SymmetryFeature::Gradient) {
        gradients();
    } else {
        // Intensities about the mean of the compared region (centred axis).
        const int y0 = std::clamp(static_cast<int>(std::lround(options_.regionTop * n)), 0, n - 1);
        const int y1 =
            std::clamp(static_cast<int>(std::lround(options_.regionBottom * n)), y0 + 1, n);
        const float half = options_.regionHalfWidthFraction * static_cast<float>(n);
        const int x0 = std::clamp(static_cast<int>(std::ceil(0.5f * (n - 1) - half)), 0, n - 1);
        const int x1 = std::clamp(static_cast<int>(std::floor(0.5f * (n - 1) + half)), x0, n - 1);
        double sum = 0.0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x <= x1; ++x)
                sum += patch_[static_cast<std::size_t>(y * n + x)];
        const auto mean = static_cast<float>(sum / ((y1 - y0) * (x1 - x0 + 1)));
        for (std::size_t i = 0; i < a_.size(); ++i)
            a_[i] = patch_[i] - mean;
    }
    return true;
}

float RollByImageSymmetry::asymmetryAbout(float a2) const noexcept
{
    // Mirror pairs (x, a2 - x) with x < a2 / 2: the axis is at a2 / 2 in patch pixel indices. A
    // fractional a2 reads the mirror partner by linear interpolation, so the axis offset is
    // continuous and its quantisation does not bias the angle.
    const int n = n_;
    const bool gradient = options_.feature == SymmetryFeature::Gradient;
    // Gradient pixels have no value on the patch border.
    const int lo = gradient ? 1 : 0;
    const int hi = gradient ? n - 2 : n - 1;
    const int y0 = std::clamp(static_cast<int>(std::lround(options_.regionTop * n)), lo, hi);
    const int y1 =
        std::clamp(static_cast<int>(std::lround(options_.regionBottom * n)), y0 + 1, hi + 1);
    const float half = options_.regionHalfWidthFraction * static_cast<float>(n);
    // Partners a2 - x must lie in [lo, hi - 1] (two samples for the interpolation).
    const int xFirst = std::max({lo, static_cast<int>(std::ceil(0.5f * a2 - half)),
                                 static_cast<int>(std::ceil(a2 - static_cast<float>(hi - 1)))});
    const int xEnd = static_cast<int>(std::ceil(0.5f * a2));
    if (xFirst >= xEnd)
        return 1.f;
    const symmetry_detail::PairPlanes planes{a_.data(), b_.data(),
                                             uniformWeights_ ? nullptr : weight_.data(),
                                             n, y0, y1, hi, gradient};
    // The coarse scan's half-pixel axes: the same sum without the interpolation (a flat patch
    // compares nothing and scores 1 either way).
    if (gradient && uniformWeights_ && a2 == std::floor(a2))
        return symmetry_detail::pairAsymmetryWholeAxis(planes, xFirst, xEnd,
                                                       static_cast<int>(a2));
    return symmetry_detail::pairAsymmetry(planes, xFirst, xEnd, a2);
}

float RollByImageSymmetry::rowCoherence() const noexcept
{
    // Upright, the brows, eyes, nostrils and mouth run along the rows: each row's vertical
    // derivatives add up instead of cancelling. The region is the compared one about the patch
    // centre (the axis offset is small next to its width).
    const int n = n_;
    const int y0 = std::clamp(static_cast<int>(std::lround(options_.regionTop * n)), 1, n - 2);
    const int y1 =
        std::clamp(static_cast<int>(std::lround(options_.regionBottom * n)), y0 + 1, n - 1);
    const float half = options_.regionHalfWidthFraction * static_cast<float>(n);
    const int x0 = std::clamp(static_cast<int>(std::ceil(0.5f * (n - 1) - half)), 1, n - 2);
    const int x1 = std::clamp(static_cast<int>(std::floor(0.5f * (n - 1) + half)), x0, n - 2);
    float coherent = 0.f, total = 0.f;
    for (int y = y0; y < y1; ++y) {
        const float* gy = &b_[static_cast<std::size_t>(y * n)];
        float row = 0.f;
        for (int x = x0; x <= x1; ++x) {
            row += gy[x];
            total += std::fabs(gy[x]);
        }
        coherent += std::fabs(row);
    }
    return total > 1e-3f ? coherent / total : 0.f;
}

float RollByImageSymmetry::bestOverOffsets(bool continuous) noexcept
{
    // Half-pixel steps of the axis, then golden section between the neighbours of the best.
    const float centre2 = static_cast<float>(n_ - 1);
    float best = INFINITY, bestA2 = centre2;
    for (int k = -maxShift_; k <= maxShift_; ++k) {
        const float score = asymmetryAbout(centre2 + static_cast<float>(k));
        if (score < best) {
            best = score;
            bestA2 = centre2 + static_cast<float>(k);
        }
    }
    if (continuous && maxShift_ > 0) {
        const GoldenSectionBracket g =
            goldenSection(std::max(centre2 - static_cast<float>(maxShift_), bestA2 - 1.f),
                          std::min(centre2 + static_cast<float>(maxShift_), bestA2 + 1.f), 0.05f,
                          [this](float a2) { return asymmetryAbout(a2); });
        best = std::min({best, g.fa, g.fb});
    }
    return std::isfinite(best) ? best : 1.f;
}

float RollByImageSymmetry::scoreAngle(const ConstImageView& gray, Point2f centre, float boxSize,
                                      float rollDegrees, bool continuous) noexcept
{
    if (!prepare(gray, centre, boxSize, rollDegrees))
        return -1.f;
    lastAsymmetry_ = bestOverOffsets(continuous);
    lastRowTerm_ =
        options_.feature == SymmetryFeature::Gradient && options_.rowCoherenceWeight > 0.f
            ? 1.f - rowCoherence()
            : 0.f;
    // Both terms are 0 at best, so the sum stays >= 0 (negative means bad input).
    return lastAsymmetry_ + rowWeight_ * lastRowTerm_;
}

float RollByImageSymmetry::asymmetry(const ConstImageView& gray, Point2f centre, float boxSize,
                                     float rollDegrees) noexcept
{
    if (gray.empty() || gray.format != PixelFormat::Gray8 || !(boxSize > 0.f) ||
        !std::isfinite(boxSize) || !std::isfinite(rollDegrees))
        return -1.f;
    rowWeight_ = options_.rowCoherenceWeight;
    return scoreAngle(gray, centre, boxSize, rollDegrees, true);
}

RollEstimate RollByImageSymmetry::estimate(const ConstImageView& gray, Point2f centre,
                                           float boxSize) noexcept
{
    RollEstimate result;
    lastError_[0] = '\0';
    if (gray.empty() || gray.format != PixelFormat::Gray8) {
        std::snprintf(lastError_, sizeof lastError_, "roll by image symmetry: need a Gray8 image");
        return result;
    }
    if (!(boxSize >= 4.f) || !std::isfinite(boxSize) || !std::isfinite(centre.x) ||
        !std::isfinite(centre.y)) {
        std::snprintf(lastError_, sizeof lastError_,
                      "roll by image symmetry: box size must be finite and >= 4 px");
        return result;
    }
    const auto& o = options_;
    const int count =
        static_cast<int>(std::floor((o.maxDegrees - o.minDegrees) / o.coarseStepDegrees + 1e-4f)) +
        1;
    // The coarse scan reaches one step beyond each end of the range: a minimum counts only where
    // the curve rises again on both sides. A best score at an end of the range without that is
    // the curve still falling, not a symmetry (hair, collars and turned heads pull it there); on
    // CMU/MIT picking the best local minimum instead removed most of the 30-50 degree errors
    // (seeds 7, 11, 42, 3, 99, 123, 500: mean A 3.44 -> 3.27, B 3.61 -> 3.45 deg). Without any (a
    // monotone curve), the plain best in the range.
    float extended[kMaxCoarseAngles] = {};
    float asymmetries[kMaxCoarseAngles] = {};
    float rowTerms[kMaxCoarseAngles] = {};
    rowWeight_ = 0.f;
    for (int k = 0; k < count + 2; ++k) {
        if (scoreAngle(gray, centre, boxSize,
                       o.minDegrees + o.coarseStepDegrees * static_cast<float>(k - 1),
                       false) < 0.f) {
            std::snprintf(lastError_, sizeof lastError_,
                          "roll by image symmetry: face square outside the image");
            return result;
        }
        asymmetries[k] = lastAsymmetry_;
        rowTerms[k] = lastRowTerm_;
    }
    // The row cue joins only where the symmetry alone is unsure (its best angle hardly better
    // than the median one): on clear, large faces it would only add its own bias (the eye line
    // need not be square to the eye-mouth axis).
    float symmetryConfidence = 0.f;
    {
        std::copy(asymmetries + 1, asymmetries + 1 + count, extended);
        const float best = *std::min_element(extended, extended + count);
        std::nth_element(extended, extended + count / 2, extended + count);
        const float median = extended[count / 2];
        symmetryConfidence = median > 1e-6f ? 1.f - best / median : 0.f;
    }
    if (symmetryConfidence < o.rowCueBelowConfidence)
        rowWeight_ = o.rowCoherenceWeight;
    for (int k = 0; k < count + 2; ++k)
        extended[k] = asymmetries[k] + rowWeight_ * rowTerms[k];
    float* scores = extended + 1;  // scores[i]: the angle minDegrees + i x step, i < count
    int bestIndex = -1;
    for (int i = 0; i < count; ++i)
        if (scores[i] <= scores[i - 1] && scores[i] <= scores[i + 1] &&
            (bestIndex < 0 || scores[i] < scores[bestIndex]))
            bestIndex = i;
    if (bestIndex < 0) {
        bestIndex = 0;
        for (int i = 1; i < count; ++i)
            if (scores[i] < scores[bestIndex])
                bestIndex = i;
    }
    float bestDegrees = o.minDegrees + o.coarseStepDegrees * static_cast<float>(bestIndex);
    // The coarse scan reads the axis in half-pixel steps only (it just picks the basin); the
    // refinement compares continuous offsets, the coarse best included.
    float bestScore = scores[bestIndex];
    if (o.refineToleranceDegrees > 0.f && count > 1) {
        const float continuous = scoreAngle(gray, centre, boxSize, bestDegrees, true);
        bestScore = continuous >= 0.f ? continuous : bestScore;
    }

    // Golden section between the neighbouring coarse angles; kept only when it scores at least
    // as well as the coarse best.
    if (o.refineToleranceDegrees > 0.f && count > 1) {
        const GoldenSectionBracket g = goldenSection(
            std::max(o.minDegrees, bestDegrees - o.coarseStepDegrees),
            std::min(o.maxDegrees, bestDegrees + o.coarseStepDegrees), o.refineToleranceDegrees,
            [&](float degrees) { return scoreAngle(gray, centre, boxSize, degrees, true); }, 40);
        const float mid = 0.5f * (g.lo + g.hi);
        const float fmid = scoreAngle(gray, centre, boxSize, mid, true);
        if (fmid >= 0.f && fmid <= bestScore) {
            bestDegrees = mid;
            bestScore = fmid;
        }
    }

    std::nth_element(scores, scores + count / 2, scores + count);
    const float typical = scores[count / 2];
    result.rollDegrees = bestDegrees;
    result.symmetryDistance = bestScore;
    result.confidence = typical > 1e-6f ? std::clamp(1.f - bestScore / typical, 0.f, 1.f) : 0.f;
    const float half = o.regionHalfWidthFraction * static_cast<float>(n_);
    const int rows = static_cast<int>(std::lround((o.regionBottom - o.regionTop) * n_));
    result.points = static_cast<int>(half) * rows;
    return result;
}

}  // namespace vision
