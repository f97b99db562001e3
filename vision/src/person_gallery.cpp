#include "vision/person_gallery.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>

namespace vision {
namespace {

// The distance (§6), chosen by `mirror-eval people` (docs/people-evaluation.md) without the 10
// persons the demo model leaves out: on its 30 training persons, and on a development model built
// from 20 of them that leaves the other 10 out (persons the model has not seen, as every user
// is). Whitened Euclidean: each difference divided by how much that value varies between
// photographs of one person (the tables below), d^2 the weighted mean of the two parts' mean
// squares, score = 1 / (1 + d^2). Rank-1 on IMM's frontal probes (types 2, 5; enrolled from type
// 1), the 30 training persons / the development model's 10 unseen:
//   appearance, plain Euclidean (mode std units) 0.52; cosine 0.48; shape units alone 0.23-0.28;
//   appearance whitened 0.78 / 0.45; with the whitened shape units at weight 0.1: 0.80 / 0.50
//   (0.25: 0.77 / 0.45); norm-relative or cosine scores: no better, more strangers accepted.
// The texture descriptor (AamFitter: uniform LBP per cell of a 4x4 grid of the face warped to the
// mean shape, 255 * sqrt of each share) added as a third part, its Hellinger distance in units of
// its within-person rms deviation (7: 6.96 over the development model's 20 training persons, 7.19
// over the demo model's 30), chosen on the development model's 10 unseen persons (signatures with
// TrackedFaceFitterOptions::signatureMaxResidual 1.0): rank-1 frontal / turned, appearance and
// shape units as before 0.40 / 0.45; texture alone 0.85 / 0.25; shape 0.5, appearance 1, texture
// 10 0.85 / 0.55 (a plateau over shape 0.25-1, texture 8-12; grids 3 and 5 worse). The texture's
// scores are close together, so acceptScore is sharp: 0.33 accepts 1.1% of the strangers on both
// the development and the demo model's training persons (0.32: 1.7% and 2.2%; 0.35: none, but
// a third fewer enrolled probes accepted as themselves). docs/people-evaluation.md.
float scoreOf(const FaceSignature& a, const FaceSignature& b,
              const PersonGalleryOptions& o) noexcept
{
    if (a.samples == 0 || b.samples == 0)
        return 0.f;
    float d2 = 0.f, weights = 0.f;
    if (o.shapeWeight > 0.f) {
        float sum = 0.f;
        for (int i = 0; i < kAamShapeUnits; ++i) {
            const float d = (a.shapeUnits[i] - b.shapeUnits[i]) /
                            std::max(o.shapeSpread[static_cast<std::size_t>(i)], 1e-3f);
            sum += d * d;
        }
        d2 += o.shapeWeight * sum / kAamShapeUnits;
        weights += o.shapeWeight;
    }
    const int n = std::min(a.appearanceCount, b.appearanceCount);
    if (o.appearanceWeight > 0.f && n > 0) {
        float sum = 0.f;
        for (int i = 0; i < n; ++i) {
            const float d = (a.appearance[static_cast<std::size_t>(i)] -
                             b.appearance[static_cast<std::size_t>(i)]) /
                            std::max(o.appearanceSpread[static_cast<std::size_t>(i)], 1e-3f);
            sum += d * d;
        }
        d2 += o.appearanceWeight * sum / static_cast<float>(n);
        weights += o.appearanceWeight;
    }
    const int t = std::min(a.textureCount, b.textureCount);
    if (o.textureWeight > 0.f && t > 0 && a.textureCount == b.textureCount) {
        // Integer: every difference at most 255, so the sum stays far inside 32 bits.
        std::int32_t sum = 0;
        for (int i = 0; i < t; ++i) {
            const std::int32_t d =
                static_cast<std::int32_t>(a.texture[static_cast<std::size_t>(i)]) -
                static_cast<std::int32_t>(b.texture[static_cast<std::size_t>(i)]);
            sum += d * d;
        }
        const float spread = std::max(o.textureSpread, 1e-3f);
        d2 += o.textureWeight * static_cast<float>(sum) / static_cast<float>(t) / (spread * spread);
        weights += o.textureWeight;
    }
    if (weights <= 0.f || !std::isfinite(d2))
        return 0.f;
    return 1.f / (1.f + d2 / weights);
}

}  // namespace

// The within-person std of each signature value: over the 6 IMM photographs of each of the demo
// model's (out/aam/imm-demo.aam) 30 training persons, deviations from the person's mean
// (`mirror-eval people` prints them for the model it runs; a model built otherwise wants its own).
// The first mode, 3 and 7 vary most within a person (lighting: IMM's type 5 is lit from one side).
std::array<float, kFaceSignatureMaxAppearance> defaultAppearanceSpread() noexcept
{
    std::array<float, kFaceSignatureMaxAppearance> spread{};
    spread.fill(1.f);
    constexpr float kMeasured[] = {1.72f, 0.36f, 0.61f, 1.68f, 0.72f, 0.86f, 0.66f, 1.30f,
                                   0.57f, 0.48f, 0.71f, 0.61f, 0.59f, 0.56f, 0.62f, 0.71f,
                                   0.56f, 0.68f, 0.39f, 0.69f, 0.63f, 0.62f, 0.48f, 0.43f};
    std::copy(std::begin(kMeasured), std::end(kMeasured), spread.begin());
    return spread;
}

std::array<float, kAamShapeUnits> defaultShapeSpread() noexcept
{
    return {0.222f, 0.229f, 0.034f, 0.070f, 0.135f, 0.273f, 0.236f, 0.157f, 0.027f, 0.138f};
}

PersonGallery::PersonGallery(const PersonGalleryOptions& options) noexcept : options_(options) {}

bool PersonGallery::enrol(int personId, const FaceSignature& signature) noexcept
{
    if (personId <= 0 || signature.samples <= 0)
        return false;
    for (int i = 0; i < count_; ++i)
        if (entries_[i].personId == personId) {
            entries_[i].signature = signature;
            return true;
        }
    if (count_ == kMaxPeople)
        return false;
    entries_[count_++] = Entry{personId, signature};
    return true;
}

void PersonGallery::forget(int personId) noexcept
{
    for (int i = 0; i < count_; ++i)
        if (entries_[i].personId == personId) {
            entries_[i] = entries_[--count_];
            entries_[count_] = Entry{};
            return;
        }
}

void PersonGallery::clear() noexcept
{
    entries_.fill(Entry{});
    count_ = 0;
}

bool PersonGallery::contains(int personId) const noexcept
{
    for (int i = 0; i < count_; ++i)
        if (entries_[i].personId == personId)
            return true;
    return false;
}

PersonMatch PersonGallery::match(const FaceSignature& signature) const noexcept
{
    PersonMatch best;
    for (int i = 0; i < count_; ++i) {
        const float s = scoreOf(signature, entries_[i].signature, options_);
        if (s > best.nearestScore) {
            best.nearestScore = s;
            best.nearestId = entries_[i].personId;
        }
    }
    if (best.nearestId != 0 && best.nearestScore >= options_.acceptScore) {
        best.personId = best.nearestId;
        best.score = best.nearestScore;
    }
    return best;
}

float PersonGallery::score(int personId, const FaceSignature& signature) const noexcept
{
    for (int i = 0; i < count_; ++i)
        if (entries_[i].personId == personId)
            return scoreOf(signature, entries_[i].signature, options_);
    return 0.f;
}

}  // namespace vision
