#include "entry_scan.hpp"

#include "vision/geometry.hpp"
#include "vision/upright_patch.hpp"

#include <algorithm>
#include <cmath>

// Beyond fig. 89 (METHOD.md §3, "Detection"): the masked scan under a window budget goes over the
// whole search mask in order (scale, row, window), so a face coming in at an edge waits for its
// turn, and it comes into view only gradually: its first frames wholly in view were missed (facegen
// seed 13's `enter-leave`: a face coming in at the left was wholly in view at frame 87 and found
// at 90). Where it enters is known, though: the band along an edge where the motion mask marks
// something no track covers. That band is scanned first, on its own, each frame, so the face is
// found as soon as the cascade answers it; the rest of the budget goes to the whole mask as
// before. The windows of the band are windows the whole scan would have spent on the same place.

namespace vision {

namespace {

/// Moving regions are looked for in cells of this many pixels.
constexpr int kCell = 8;
/// A cell is moving when this much of it is (as TiltedScan's cells: a moving face's box is about
/// 0.7 full).
constexpr float kMinCellFraction = 0.4f;
/// A tracked face's motion (its trail included) covers its box enlarged by this factor.
constexpr float kTrackMotionReach = 1.5f;
/// The band's depth, as a fraction of the image's shorter side: a face up to this size is
/// wholly in the band as it comes wholly into view (a quarter of 240 rows: 60 working pixels,
/// a face 120 px across in the camera's frame at the shipped downscale of 2).
constexpr float kBandDepth = 0.25f;
/// A hit's box may reach beyond the image by this fraction of its side (TiltedScan's slack: the
/// detector's box is larger than the face, which is in view about as soon as the box is within
/// this of the edge).
constexpr float kEdgeSlack = 0.12f;

}  // namespace

EntryScan::EntryScan(const HaarCascade& cascade, const FaceTrackerOptions& options)
    : options_(options)
{
    if (options.detectionWindowBudget <= 0 || options.mode == FaceTrackingMode::None)
        return;
    FaceDetectorOptions d = options.detector;
    d.maxFrameSize = rotatedCanvas(options.imageSize, options.tiltScanDegrees);
    detector_ = std::make_unique<FaceDetector>(cascade, d);
    if (options.tiltScanDegrees > 0.f)
        gray_ = ImageBuffer(d.maxFrameSize.width, d.maxFrameSize.height, PixelFormat::Gray8);
    mask_ = ImageBuffer(kMaskSide, kMaskSide, PixelFormat::Gray8);
    maskIntegral_ = IntegralImage({kMaskSide, kMaskSide});
    const auto perScan = static_cast<std::size_t>(std::max(1, options.detector.maxFaces));
    hits_.resize(kEdges * kLooks * perScan);
    hitRolls_.resize(hits_.size());
}

std::span<const Rect> EntryScan::hits() const noexcept
{
    return {hits_.data(), static_cast<std::size_t>(count_)};
}

std::span<const float> EntryScan::hitRolls() const noexcept
{
    return {hitRolls_.data(), static_cast<std::size_t>(count_)};
}

void EntryScan::reset() noexcept
{
    count_ = 0;
    active_ = false;
    job_ = 0;
    if (detector_)
        detector_->resetIncremental();
}

long EntryScan::run(const Frame& frame, long budget) noexcept
{
    done_ = false;
    count_ = 0;
    if (!detector_ || budget <= 0)
        return 0;
    // Each edge's band once a frame, upright then turned each way, in turn while the budget
    // lasts; a look not finished goes on next frame, and the ones after it follow.
    constexpr int kJobs = kEdges * kLooks;
    long total = 0;
    for (int k = 0; k < kJobs && budget > 0; ++k) {
        if (!active_) {
            active_ = chooseRegion(frame, job_ / kLooks) && turnRegion(job_ % kLooks);
            if (!active_) {
                job_ = (job_ + 1) % kJobs;
                continue;
            }
        }
        const long used = step(frame, budget);
        total += used;
        budget -= used;
        if (active_)
            break;  // the look's scan continues next frame
        job_ = (job_ + 1) % kJobs;
    }
    return total;
}

bool EntryScan::chooseRegion(const Frame& frame, int edge) noexcept
{
    // The bounding box of the moving cells in the edge's band whose centre lies outside every
    // tracked face's reach: where an untracked face may be coming in, when one of them is on the
    // edge itself (a face near the edge that is not coming in is the whole mask's scan's: its
    // band, cut through the face, took half the budget for nothing while two faces crossed near
    // the left edge, facegen seed 13's `two`).
    const Size s = options_.imageSize;
    const int depth =
        static_cast<int>(kBandDepth * static_cast<float>(std::min(s.width, s.height)));
    const int bx0 = edge == 1 ? s.width - depth : 0;
    const int bx1 = edge == 0 ? depth : s.width;
    const int by0 = edge == 3 ? s.height - depth : 0;
    const int by1 = edge == 2 ? depth : s.height;
    int x0 = s.width, y0 = s.height, x1 = 0, y1 = 0;
    bool onEdge = false;
    for (int cy = by0; cy < by1; cy += kCell) {
        const int cy1 = std::min(cy + kCell, by1);
        for (int cx = bx0; cx < bx1; cx += kCell) {
            const int cx1 = std::min(cx + kCell, bx1);
            if (frame.motionIntegral.maskFraction({cx, cy, cx1 - cx, cy1 - cy}) < kMinCellFraction)
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
            onEdge = onEdge || (edge == 0 && cx == 0) || (edge == 1 && cx1 == s.width) ||
                     (edge == 2 && cy == 0) || (edge == 3 && cy1 == s.height);
        }
    }
    const Size w = detector_->windowSize();
    if (!onEdge || x1 - x0 < w.width / 2 || y1 - y0 < w.height / 2)
        return false;  // nothing moving untracked of a face's size
    // Margin: the detector's box reaches beyond the moving pixels of the face.
    const int margin = 4 + static_cast<int>(0.15f * static_cast<float>(std::max(x1 - x0, y1 - y0)));
    region_ = clipped({x0 - margin, y0 - margin, x1 - x0 + 2 * margin, y1 - y0 + 2 * margin},
                      s.width, s.height);
    return region_.width >= w.width && region_.height >= w.height;
}

bool EntryScan::turnRegion(int look) noexcept
{
    // Upright: the region itself. Turned: the region about its centre, grown to hold it.
    const float tilt = options_.tiltScanDegrees;
    if (look > 0 && tilt <= 0.f)
        return false;
    angle_ = look == 0 ? 0.f : (look == 1 ? tilt : -tilt);
    turned_ = {region_.width, region_.height};
    if (look == 0)
        return true;
    const float c = std::fabs(std::cos(toRadians(angle_)));
    const float n = std::fabs(std::sin(toRadians(angle_)));
    const auto bw = static_cast<float>(region_.width);
    const auto bh = static_cast<float>(region_.height);
    const Size canvas = gray_.view().size();
    turned_ = {std::min(canvas.width, static_cast<int>(bw * c + bh * n + 0.5f)),
               std::min(canvas.height, static_cast<int>(bw * n + bh * c + 0.5f))};
    return true;
}

long EntryScan::step(const Frame& frame, long budget) noexcept
{
    // Upright, the region is a view into the frame (nothing copied); turned, a face rolled by
    // the look's angle comes out upright in the turned region (warpRotated, as TiltedScan).
    const Point2f centre{static_cast<float>(region_.x) + 0.5f * static_cast<float>(region_.width),
                         static_cast<float>(region_.y) + 0.5f * static_cast<float>(region_.height)};
    ConstImageView region{frame.gray.row(region_.y) + region_.x, region_.width, region_.height,
                          frame.gray.stride, PixelFormat::Gray8};
    if (angle_ != 0.f) {
        ImageView turned = gray_.view();
        turned.width = turned_.width;
        turned.height = turned_.height;
        warpRotated(frame.gray, centre, angle_, 1.f, 1.f, turned);
        region = turned;
    }
    warpRotated(frame.motionMask, centre, angle_, static_cast<double>(turned_.width) / kMaskSide,
                static_cast<double>(turned_.height) / kMaskSide, mask_.view());
    maskIntegral_.compute(mask_.view());
    const int excludedCount = excludeTracks(frame.tracks);
    const bool completed = detector_->detectMaskedIncremental(
        region, &maskIntegral_, options_.minMaskFraction,
        std::span<const Rect>(excluded_.data(), static_cast<std::size_t>(excludedCount)), budget);
    const long used = detector_->windowsEvaluated();
    if (!completed)
        return used;
    active_ = false;
    done_ = true;
    collectHits();
    return used;
}

int EntryScan::excludeTracks(std::span<const Track> tracks) noexcept
{
    // Tracked faces are excluded as in the upright scan: their boxes about their centres as
    // seen in the (turned) region.
    const float c = std::cos(toRadians(angle_));
    const float n = std::sin(toRadians(angle_));
    const float cx = static_cast<float>(region_.x) + 0.5f * static_cast<float>(region_.width);
    const float cy = static_cast<float>(region_.y) + 0.5f * static_cast<float>(region_.height);
    int count = 0;
    for (const Track& t : tracks) {
        const TrackedFace& f = t.face;
        const float dx = f.centre.x - cx;
        const float dy = f.centre.y - cy;
        const float u = c * dx + n * dy + 0.5f * static_cast<float>(turned_.width);
        const float v = -n * dx + c * dy + 0.5f * static_cast<float>(turned_.height);
        const float half = 0.5f * f.size;
        excluded_[static_cast<std::size_t>(count++)] = {
            static_cast<int>(u - half), static_cast<int>(v - half), static_cast<int>(f.size + 0.5f),
            static_cast<int>(f.size + 0.5f)};
    }
    return count;
}

void EntryScan::collectHits() noexcept
{
    // The detector's boxes, turned back: their centres in the image, their sides as they are;
    // a box may reach beyond the image a little (kEdgeSlack), not more (of a part of a face).
    const float c = std::cos(toRadians(angle_));
    const float n = std::sin(toRadians(angle_));
    const float cx = static_cast<float>(region_.x) + 0.5f * static_cast<float>(region_.width);
    const float cy = static_cast<float>(region_.y) + 0.5f * static_cast<float>(region_.height);
    const Size s = options_.imageSize;
    for (const Rect& b : detector_->faces()) {
        if (count_ >= static_cast<int>(hits_.size()))
            break;
        const float u = static_cast<float>(b.x) + 0.5f * static_cast<float>(b.width) -
                        0.5f * static_cast<float>(turned_.width);
        const float v = static_cast<float>(b.y) + 0.5f * static_cast<float>(b.height) -
                        0.5f * static_cast<float>(turned_.height);
        const float x = cx + c * u - n * v;
        const float y = cy + n * u + c * v;
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
