#include "face_search.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace vision {

namespace {

FaceDetectorOptions scanOptions(const FaceTrackerOptions& o)
{
    FaceDetectorOptions d = o.detector;
    d.maxFrameSize = o.imageSize;
    return d;
}

}  // namespace

FaceSearch::FaceSearch(const HaarCascade& cascade, const FaceTrackerOptions& options)
    : options_(options),
      detector_(cascade, scanOptions(options)),
      mask_(options.imageSize.width, options.imageSize.height, PixelFormat::Gray8),
      maskIntegral_(options.imageSize),
      hits_(static_cast<std::size_t>(std::max(1, options.detector.maxFaces)))
{
    std::memset(mask_.view().data, 0, mask_.bytes());
    maskIntegral_.compute(mask_.view());
}

std::span<const Rect> FaceSearch::hits() const noexcept
{
    return {hits_.data(), static_cast<std::size_t>(count_)};
}

long FaceSearch::windowsLeft() const noexcept
{
    return budget_ > 0 ? budget_ - detector_.windowsEvaluated() : std::numeric_limits<long>::max();
}

void FaceSearch::remember(Rect box, int frameIndex) noexcept
{
    RecentArea* slot = &recent_[0];
    for (RecentArea& a : recent_)
        if (a.expires < slot->expires)
            slot = &a;
    slot->box = box;
    slot->expires = frameIndex + options_.recentFaceFrames;
}

void FaceSearch::reset(bool wholeImage) noexcept
{
    count_ = 0;
    detector_.resetIncremental();
    recent_.fill(RecentArea{});
    coldStart_ = true;
    wholeImage_ = wholeImage;
    pass_ = 0;
    lastPass_ = 0;
}

long FaceSearch::scan(const Frame& frame) noexcept
{
    // Tracked faces are not searched: tracking handles them faster (§3; dissertation 5.1.3).
    int excludedCount = 0;
    if (options_.mode != FaceTrackingMode::None)
        for (const Track& t : frame.tracks)
            excluded_[static_cast<std::size_t>(excludedCount++)] = t.face.box();
    const std::span<const Rect> exclude(excluded_.data(), static_cast<std::size_t>(excludedCount));
    const bool haveMotion = frame.motion != nullptr;
    const Size s = options_.imageSize;
    if (coldStart_ && !wholeImage_ && haveMotion && frame.motion->sum(0, 0, s.width, s.height) > 0)
        coldStart_ = false;
    wholeImage_ = false;
    cold_ = coldStart_;
    if (haveMotion)
        prepareMask(frame);
    // A cold start's scan is not spread over frames: the faces in view when the mirror starts
    // (or its camera comes back) are all found in that one frame, which may take longer.
    // What the edge bands' scan (EntryScan) spent of the budget comes out of this one's.
    const long budget = options_.detectionWindowBudget;
    budget_ = cold_ || budget <= 0 ? 0 : std::max(1L, budget - frame.spent);
    const int detected = detect(frame, exclude);
    pass_ += detector_.windowsEvaluated();
    if (done_) {
        // A cold pass (the whole image) says nothing of what the masked passes cost.
        if (!cold_ && options_.detectionWindowBudget > 0)
            lastPass_ = pass_;
        pass_ = 0;
        coldStart_ = false;
        count_ = std::min(detected, static_cast<int>(hits_.size()));
        for (int d = 0; d < count_; ++d)
            hits_[static_cast<std::size_t>(d)] = detector_.faces()[static_cast<std::size_t>(d)];
    }
    return detector_.windowsEvaluated();
}

int FaceSearch::detect(const Frame& frame, std::span<const Rect> exclude) noexcept
{
    if (cold_) {
        // A cold start scans the whole image in its one frame: coarse to fine, which finds the
        // faces of the full scan at a fraction of its windows (§3; FaceDetector).
        // Its mask is all set (prepareMask), so no window is looked up in it.
        done_ = true;
        return detector_.detectCoarseToFine(frame.gray, nullptr, 0.f, exclude);
    }
    const bool haveMotion = frame.motion != nullptr;
    if (options_.detectionWindowBudget > 0) {
        // The scan spread over frames (a result only when a scan completes), so that no frame
        // stalls on detection.
        done_ = detector_.detectMaskedIncremental(frame.gray, haveMotion ? &maskIntegral_ : nullptr,
                                                  options_.minMaskFraction, exclude, budget_);
        return done_ ? static_cast<int>(detector_.faces().size()) : 0;
    }
    done_ = true;
    if (haveMotion)
        return detector_.detectMasked(frame.gray, maskIntegral_, options_.minMaskFraction, exclude);
    // No mask: everything scannable, but tracked faces still excluded (a minimum fraction of 0
    // accepts every window of the mask table, whatever it holds).
    if (!exclude.empty())
        return detector_.detectMasked(frame.gray, maskIntegral_, 0.f, exclude);
    return detector_.detect(frame.gray);
}

void FaceSearch::prepareMask(const Frame& frame) noexcept
{
    // 3 "Detection": scan where there is motion, or where a face was seen recently (a face that
    // stops moving for a moment must still be found again).
    const Size s = options_.imageSize;
    if (coldStart_) {
        std::memset(mask_.view().data, 255, mask_.bytes());
        maskIntegral_.compute(mask_.view());
        return;
    }
    for (int y = 0; y < s.height; ++y)
        std::memcpy(mask_.view().row(y), frame.mask.row(y), static_cast<std::size_t>(s.width));
    for (RecentArea& a : recent_) {
        if (a.expires < frame.frameIndex || a.box.width <= 0)
            continue;
        const Rect r = clipped(a.box, s.width, s.height);
        for (int y = r.y; y < r.y + r.height; ++y)
            std::memset(mask_.view().row(y) + r.x, 255, static_cast<std::size_t>(r.width));
    }
    maskIntegral_.compute(mask_.view());
}

}  // namespace vision
