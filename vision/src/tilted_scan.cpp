#include "tilted_scan.hpp"

#include "vision/geometry.hpp"
#include "vision/upright_patch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

// Beyond fig. 89 (METHOD.md §3, "Detection"; dissertation 5.1.3): the upright cascade finds faces
// within about +-15 degrees of upright, and a tracked face keeps its roll by its corners, but a
// face that comes into view tilted further is never detected. The moving regions no track covers
// are therefore also scanned turned by the tilt angle, as the dissertation's verification turns a
// tracked face upright by its roll. The two angles (+-tiltScanDegrees) alternate, one per
// scan; a tilted scan gets only what the upright scan left of detectionWindowBudget (and at
// most tiltWindowBudget of it) and continues on the next frames; a hit there starts a track with
// that roll, refined from the image.

namespace vision {

namespace {

/// Moving regions are looked for in cells of this many pixels.
constexpr int kTiltCell = 8;
/// A tracked face's motion (its trail included) covers its box enlarged by this factor.
constexpr float kTrackMotionReach = 1.5f;
/// Tilted scans cost as much as upright ones per window and there are two angles: only
/// windows (and cells) this full of motion, as a moving face's box is (about 0.7 on average).
constexpr float kTiltMinMaskFraction = 0.4f;
/// A cold start's scans (the whole image, once) also turn by +- this angle, the upright
/// cascade's reach, between upright and tiltScanDegrees: the cascade answers a face at some
/// angles and not at others near them, and a face it misses in all three looks of a cold start
/// waits until its own roll brings it into one (facegen seed 7's `four`: an upright face found
/// only at about 15 degrees, unshown for its first 15 frames).
constexpr float kColdMidDegrees = 15.f;
/// A hit's box may reach beyond the image by this fraction of its side: facegen's face boxes
/// are the detector's box, and the face it holds is in view about as soon as the box is within
/// this of the edge (facegen seed 7's `enter-leave`: a face tilted -19 degrees coming in at the
/// top was in view, unshown, for three frames while its box still reached 3-7 px above it).
constexpr float kEdgeSlack = 0.12f;

FaceDetectorOptions tiltOptions(const FaceTrackerOptions& o)
{
    FaceDetectorOptions d = o.detector;
    d.maxFrameSize = rotatedCanvas(o.imageSize, o.tiltScanDegrees);
    return d;
}

}  // namespace

TiltedScan::TiltedScan(const HaarCascade& cascade, const FaceTrackerOptions& options)
    : options_(options)
{
    if (options.tiltScanDegrees <= 0.f)
        return;
    const FaceDetectorOptions t = tiltOptions(options);
    detector_ = std::make_unique<FaceDetector>(cascade, t);
    gray_ = ImageBuffer(t.maxFrameSize.width, t.maxFrameSize.height, PixelFormat::Gray8);
    mask_ = ImageBuffer(kMaskSide, kMaskSide, PixelFormat::Gray8);
    maskIntegral_ = IntegralImage({kMaskSide, kMaskSide});
    // Both angles may complete in one frame.
    const auto perScan = static_cast<std::size_t>(std::max(1, options.detector.maxFaces));
    hits_.resize(4 * perScan);  // a cold start's four angles
    hitRolls_.resize(hits_.size());
}

std::span<const Rect> TiltedScan::hits() const noexcept
{
    return {hits_.data(), static_cast<std::size_t>(count_)};
}

std::span<const float> TiltedScan::hitRolls() const noexcept
{
    return {hitRolls_.data(), static_cast<std::size_t>(count_)};
}

void TiltedScan::reset() noexcept
{
    count_ = 0;
    active_ = false;
    if (detector_)
        detector_->resetIncremental();
}

long TiltedScan::run(const Frame& frame, long budget) noexcept
{
    done_ = false;
    if (!detector_)
        return 0;
    // One angle after the other while the budget lasts (both in a frame when it allows; a cold
    // start's whole-image scans also at +-kColdMidDegrees).
    long total = 0;
    whole_ = frame.coldStart;
    const int scans = frame.coldStart && options_.tiltScanDegrees > kColdMidDegrees + 5.f ? 4 : 2;
    for (int k = 0; k < scans && budget > 0; ++k) {
        const bool unlimited = budget == kUnlimited;
        magnitude_ = k < 2 ? options_.tiltScanDegrees : kColdMidDegrees;
        const long used = step(frame, unlimited ? 0 : budget);
        total += used;
        if (active_ || used == 0)
            break;  // the scan continues next frame, or there was nothing to scan
        if (!unlimited)
            budget -= used;
    }
    return total;
}

bool TiltedScan::chooseRegion(const Frame& frame) noexcept
{
    // The bounding box of the cells with motion (the scan mask's fraction) whose centre lies
    // outside every tracked face's reach: where an untracked face may be.
    const Size s = options_.imageSize;
    int x0 = s.width, y0 = s.height, x1 = 0, y1 = 0;
    for (int cy = 0; cy < s.height; cy += kTiltCell) {
        const int cy1 = std::min(cy + kTiltCell, s.height);
        for (int cx = 0; cx < s.width; cx += kTiltCell) {
            const int cx1 = std::min(cx + kTiltCell, s.width);
            if (frame.scanMaskIntegral.maskFraction({cx, cy, cx1 - cx, cy1 - cy}) <
                kTiltMinMaskFraction)
                continue;
            const float mx = 0.5f * static_cast<float>(cx + cx1);
            const float my = 0.5f * static_cast<float>(cy + cy1);
            bool tracked = false;
            for (const Track& t : frame.tracks) {
                const float reach = 0.5f * kTrackMotionReach * t.face.size;
                tracked = std::fabs(mx - t.face.centre.x) < reach &&
                          std::fabs(my - t.face.centre.y) < reach;
                if (tracked)
                    break;
            }
            if (tracked)
                continue;
            x0 = std::min(x0, cx);
            y0 = std::min(y0, cy);
            x1 = std::max(x1, cx1);
            y1 = std::max(y1, cy1);
        }
    }
    // The same cascade as the upright scan's, hence the same window.
    const int window = std::max(detector_->windowSize().width, detector_->windowSize().height);
    if (x1 - x0 < window / 2 || y1 - y0 < window / 2)
        return false;  // nothing moving untracked of a face's size
    // Margin: the detector's box reaches beyond the moving pixels of the face.
    const float margin = 4.f + 0.15f * static_cast<float>(std::max(x1 - x0, y1 - y0));
    const float bw = static_cast<float>(x1 - x0) + 2.f * margin;
    const float bh = static_cast<float>(y1 - y0) + 2.f * margin;
    angle_ = nextSign_ * magnitude_;
    nextSign_ = -nextSign_;
    const float c = std::fabs(std::cos(toRadians(angle_)));
    const float n = std::fabs(std::sin(toRadians(angle_)));
    const Size canvas = gray_.view().size();
    size_ = {std::min(canvas.width, static_cast<int>(bw * c + bh * n + 0.5f)),
             std::min(canvas.height, static_cast<int>(bw * n + bh * c + 0.5f))};
    if (size_.width < window || size_.height < window)
        return false;
    centre_ = {0.5f * static_cast<float>(x0 + x1), 0.5f * static_cast<float>(y0 + y1)};
    return true;
}

long TiltedScan::step(const Frame& frame, long budget) noexcept
{
    // A face rolled by the scan's angle comes out upright in the turned region (warpRotated:
    // region offset (u, v) from its centre shows the image at centre_ + R(angle) (u, v)).
    if (!active_) {
        active_ = chooseRegion(frame);
        if (!active_) {
            if (!done_)
                count_ = 0;  // nothing untracked moves: no tilted detections to report
            return 0;
        }
    }
    ImageView region = gray_.view();
    region.width = size_.width;
    region.height = size_.height;
    warpRotated(frame.gray, centre_, angle_, 1.f, 1.f, region);
    if (whole_)
        markImageInRegion();
    else
        warpRotated(frame.scanMask, centre_, angle_, static_cast<float>(size_.width) / kMaskSide,
                    static_cast<float>(size_.height) / kMaskSide, mask_.view());
    maskIntegral_.compute(mask_.view());
    const int excludedCount = excludeTracks(frame.tracks);
    const std::span<const Rect> excluded(excluded_.data(), static_cast<std::size_t>(excludedCount));
    const float minFraction = std::max(options_.minMaskFraction, kTiltMinMaskFraction);
    // A cold start's scans (the whole image, in its frame) go coarse to fine, as its upright
    // scan does (FaceSearch).
    const bool completed =
        whole_ ? detector_->detectCoarseToFine(region, &maskIntegral_, minFraction, excluded) >= 0
               : detector_->detectMaskedIncremental(region, &maskIntegral_, minFraction, excluded,
                                                    budget);
    const long used = detector_->windowsEvaluated();
    if (!completed)
        return used;
    active_ = false;
    if (!done_)
        count_ = 0;  // the first tilted scan completed this frame replaces the last ones
    done_ = true;
    collectHits();
    return used;
}

void TiltedScan::markImageInRegion() noexcept
{
    // A cold start's mask: the part of the turned region that shows the image. The region is
    // larger than the turned image (its corners, and a margin) and shows the image's border
    // pixels repeated there; a window mostly there holds no face in view (collectHits keeps
    // only faces nearly wholly in view). (The cold frame's scan mask is all set, and turned it
    // would mark the whole region.)
    const Turn r = turn();
    const Size s = options_.imageSize;
    const float su = static_cast<float>(size_.width) / kMaskSide;
    const float sv = static_cast<float>(size_.height) / kMaskSide;
    ImageView m = mask_.view();
    for (int j = 0; j < kMaskSide; ++j) {
        const float v = (static_cast<float>(j) + 0.5f) * sv - r.hh;
        std::uint8_t* row = m.row(j);
        for (int i = 0; i < kMaskSide; ++i) {
            const float u = (static_cast<float>(i) + 0.5f) * su - r.hw;
            const float x = centre_.x + r.c * u - r.n * v;
            const float y = centre_.y + r.n * u + r.c * v;
            row[i] = x >= 0.f && y >= 0.f && x < static_cast<float>(s.width) &&
                             y < static_cast<float>(s.height)
                         ? 255
                         : 0;
        }
    }
}

TiltedScan::Turn TiltedScan::turn() const noexcept
{
    return {std::cos(toRadians(angle_)), std::sin(toRadians(angle_)),
            0.5f * static_cast<float>(size_.width), 0.5f * static_cast<float>(size_.height)};
}

int TiltedScan::excludeTracks(std::span<const Track> tracks) noexcept
{
    // Tracked faces are excluded as in the upright scan: their boxes about their centres as
    // seen in the turned region. (Tilted scans run only with tracking on, so every track is.)
    const Turn r = turn();
    int count = 0;
    for (const Track& t : tracks) {
        const TrackedFace& f = t.face;
        const float dx = f.centre.x - centre_.x;
        const float dy = f.centre.y - centre_.y;
        const float u = r.c * dx + r.n * dy + r.hw;
        const float v = -r.n * dx + r.c * dy + r.hh;
        const float half = 0.5f * f.size;
        excluded_[static_cast<std::size_t>(count++)] = {
            static_cast<int>(u - half), static_cast<int>(v - half), static_cast<int>(f.size + 0.5f),
            static_cast<int>(f.size + 0.5f)};
    }
    return count;
}

void TiltedScan::collectHits() noexcept
{
    // The detector's boxes, turned back: their centres in the image, their sides as they are.
    const Turn r = turn();
    const Size s = options_.imageSize;
    for (const Rect& b : detector_->faces()) {
        if (count_ >= static_cast<int>(hits_.size()))
            break;
        const float u = static_cast<float>(b.x) + 0.5f * static_cast<float>(b.width) - r.hw;
        const float v = static_cast<float>(b.y) + 0.5f * static_cast<float>(b.height) - r.hh;
        const float x = centre_.x + r.c * u - r.n * v;
        const float y = centre_.y + r.n * u + r.c * v;
        // Only faces (nearly) wholly in view: the turned region repeats the image's border
        // pixels, and a box mostly beyond them is of a part of a face (its box and roll poor).
        // A face coming in tilted is taken while the detector's box still reaches a little
        // beyond the edge (the box is larger than the face, which is then in view or nearly):
        // waiting until the whole box is in lets the face be in view unshown for frames.
        const int side = std::max(b.width, b.height);
        const float half = 0.5f * static_cast<float>(side);
        const float out = kEdgeSlack * static_cast<float>(side);
        if (x - half < -out || y - half < -out || x + half > static_cast<float>(s.width) + out ||
            y + half > static_cast<float>(s.height) + out)
            continue;
        hitRolls_[static_cast<std::size_t>(count_)] = angle_;
        hits_[static_cast<std::size_t>(count_++)] = {static_cast<int>(x - half + 0.5f),
                                                     static_cast<int>(y - half + 0.5f), side, side};
    }
}

}  // namespace vision
