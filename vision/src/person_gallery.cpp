#include "vision/person_gallery.hpp"

#include <algorithm>
#include <cmath>

namespace vision {
namespace {

// A first distance: the mean squared difference of each part, the appearance already in units
// of each mode's standard deviation, the shape units in tenths of a CANDIDE unit (their spread
// across people). score = 1 / (1 + d^2): 1 for identical signatures, falling with distance.
float scoreOf(const FaceSignature& a, const FaceSignature& b, const PersonGalleryOptions& o) noexcept
{
    if (a.samples == 0 || b.samples == 0)
        return 0.f;
    float d2 = 0.f, weights = 0.f;
    if (o.shapeWeight > 0.f) {
        float sum = 0.f;
        for (int i = 0; i < kAamShapeUnits; ++i) {
            const float d = (a.shapeUnits[i] - b.shapeUnits[i]) / 0.1f;
            sum += d * d;
        }
        d2 += o.shapeWeight * sum / kAamShapeUnits;
        weights += o.shapeWeight;
    }
    const int n = std::min(a.appearanceCount, b.appearanceCount);
    if (o.appearanceWeight > 0.f && n > 0) {
        float sum = 0.f;
        for (int i = 0; i < n; ++i) {
            const float d = a.appearance[i] - b.appearance[i];
            sum += d * d;
        }
        d2 += o.appearanceWeight * sum / n;
        weights += o.appearanceWeight;
    }
    if (weights <= 0.f || !std::isfinite(d2))
        return 0.f;
    return 1.f / (1.f + d2 / weights);
}

}  // namespace

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
