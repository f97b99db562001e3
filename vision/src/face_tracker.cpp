#include "vision/face_tracker.hpp"

#include "face_track.hpp"
#include "tilted_scan.hpp"
#include "track_verifier.hpp"
#include "vision/corner_detector.hpp"
#include "vision/image_pyramid.hpp"
#include "vision/roll_by_image_symmetry.hpp"
#include "vision/roll_estimator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

namespace vision {

namespace {

constexpr int kMaxRecent = 16;  ///< dropped-face areas remembered for the scan mask
/// Fraction of a track's corners that must survive a flow step for the face to count as held
/// by them (the longer grace of FaceTrackerOptions::occludedGraceFrames).
constexpr float kHeldFraction = 0.8f;

struct RecentArea {
    Rect box;
    int expires = 0;  ///< frame index after which the area is forgotten
};

float iou(Rect a, Rect b) noexcept
{
    const int x0 = std::max(a.x, b.x);
    const int y0 = std::max(a.y, b.y);
    const int x1 = std::min(a.x + a.width, b.x + b.width);
    const int y1 = std::min(a.y + a.height, b.y + b.height);
    if (x1 <= x0 || y1 <= y0)
        return 0.f;
    const float inter = static_cast<float>(x1 - x0) * static_cast<float>(y1 - y0);
    const float uni = static_cast<float>(a.width) * static_cast<float>(a.height) +
                      static_cast<float>(b.width) * static_cast<float>(b.height) - inter;
    return uni > 0.f ? inter / uni : 0.f;
}

Rect clip(Rect r, Size s) noexcept
{
    const int x0 = std::clamp(r.x, 0, s.width);
    const int y0 = std::clamp(r.y, 0, s.height);
    const int x1 = std::clamp(r.x + r.width, 0, s.width);
    const int y1 = std::clamp(r.y + r.height, 0, s.height);
    return {x0, y0, x1 - x0, y1 - y0};
}

MotionKind fitKind(FaceTrackingMode mode) noexcept
{
    switch (mode) {
        case FaceTrackingMode::Affine:
            return MotionKind::Affine;
        case FaceTrackingMode::Similarity:
            return MotionKind::Similarity;
        default:
            return MotionKind::Translation;
    }
}

FaceDetectorOptions scanOptions(const FaceTrackerOptions& o)
{
    FaceDetectorOptions d = o.detector;
    d.maxFrameSize = o.imageSize;
    return d;
}

void validate(const FaceTrackerOptions& o)
{
    if (o.imageSize.width < 24 || o.imageSize.height < 24)
        throw std::runtime_error("FaceTracker: working image must be at least 24x24");
    if (o.maxFaces < 1 || o.maxFaces > kMaxTracks)
        throw std::runtime_error("FaceTracker: maxFaces must be 1..32");
    if (o.confirmFrames < 1 || o.graceFrames < 0)
        throw std::runtime_error("FaceTracker: confirmFrames must be >= 1 and graceFrames >= 0");
    if (o.occludedGraceFrames < 0)
        throw std::runtime_error("FaceTracker: occludedGraceFrames must be >= 0");
    if (o.maxCornersPerFace < 4 || o.maxCornersPerFace > kMaxPoints)
        throw std::runtime_error("FaceTracker: maxCornersPerFace must be 4..64");
    if (o.minCornersPerFace < 3 || o.minCornersPerFace > o.maxCornersPerFace)
        throw std::runtime_error("FaceTracker: minCornersPerFace must be 3..maxCornersPerFace");
    if (o.verifyPatchSize < 32 || o.verifyPatchSize > 256)
        throw std::runtime_error("FaceTracker: verifyPatchSize must be 32..256");
    if (!(o.minMaskFraction >= 0.f && o.minMaskFraction <= 1.f))
        throw std::runtime_error("FaceTracker: minMaskFraction must be 0..1");
    if (!(o.tiltScanDegrees >= 0.f && o.tiltScanDegrees <= 60.f))
        throw std::runtime_error("FaceTracker: tiltScanDegrees must be 0..60");
    if (o.tiltWindowBudget < 0)
        throw std::runtime_error("FaceTracker: tiltWindowBudget must be >= 0");
}

}  // namespace

struct FaceTracker::Impl {
    explicit Impl(const HaarCascade& cascade, const FaceTrackerOptions& o)
        : options(o),
          scan(cascade, scanOptions(o)),
          corners(o.imageSize, CornerDetectorOptions{kMaxPoints, 0.01f, 5.f, 3}),
          flow(o.flow),
          pyramids{ImagePyramid(o.imageSize, o.flow.maxLevel + 1),
                   ImagePyramid(o.imageSize, o.flow.maxLevel + 1)},
          grays{ImageBuffer(o.imageSize.width, o.imageSize.height, PixelFormat::Gray8),
                ImageBuffer(o.imageSize.width, o.imageSize.height, PixelFormat::Gray8)},
          scanMask(o.imageSize.width, o.imageSize.height, PixelFormat::Gray8),
          scanMaskIntegral(o.imageSize),
          motionIntegral(o.imageSize),
          imageRoll(o.rollByImageSymmetry ? std::make_unique<RollByImageSymmetry>() : nullptr),
          verifier(cascade, o, imageRoll.get()),
          staticRule(o, imageRoll.get()),
          tilted(cascade, o)
    {
        options.detector.maxFrameSize = o.imageSize;
        options.fit.kind = fitKind(o.mode);
        tracks.resize(static_cast<std::size_t>(o.maxFaces));
        outFaces.resize(static_cast<std::size_t>(o.maxFaces));
        const auto capacity = static_cast<std::size_t>(std::max(1, o.detector.maxFaces));
        uprightHits.resize(capacity);
        outDetections.resize(uprightHits.size() + tilted.capacity());
        excluded.resize(static_cast<std::size_t>(o.maxFaces));
        std::memset(scanMask.view().data, 0, scanMask.bytes());
        scanMaskIntegral.compute(scanMask.view());
    }

    bool process(const ConstImageView& gray, const ConstImageView& mask,
                 const IntegralImage* maskIntegral) noexcept;
    void trackPoints(Track& t) noexcept;
    void findCorners(Track& t, bool replenish) noexcept;
    void startTrack(Rect box, float rollHint) noexcept;
    float initialRoll(Track& t, float rollHint) noexcept;
    void prepareScanMask(const ConstImageView& mask) noexcept;
    void drop(int index) noexcept;
    void publish() noexcept;

    FaceTrackerOptions options;
    FaceDetector scan;
    CornerDetector corners;
    PyramidalLucasKanade flow;
    ImagePyramid pyramids[2];
    ImageBuffer grays[2];
    int current = 0;  ///< index of this frame's gray / pyramid
    bool havePrevious = false;
    ImageBuffer scanMask;
    IntegralImage scanMaskIntegral;
    IntegralImage motionIntegral;
    const IntegralImage* motion = nullptr;  ///< this frame's mask integral (ours or the caller's)
    bool haveMotion = false;
    std::unique_ptr<RollByImageSymmetry> imageRoll;  ///< null: corner symmetry only
    TrackVerifier verifier;  ///< fig. 89's upright-warped check of undetected tracks
    StaticFaceRule staticRule;  ///< faces that never move (photos on the wall) are dropped
    std::vector<Track> tracks;                       ///< [0, trackCount) live, oldest first
    int trackCount = 0;
    int nextId = 1;
    int frameIndex = 0;
    /// Until the first scan after construction or reset() completes, or the motion mask first
    /// marks something, the whole image is scanned: nothing is known yet of what moves (a motion
    /// model that has seen one frame marks nothing), so every face is found and the static rule
    /// (step 5) tells still from moving. A scan spread over frames by the window budget goes on
    /// masked once there is motion (a whole-image scan would keep a moving face waiting).
    bool coldStart = true;
    std::array<RecentArea, kMaxRecent> recent{};

    std::vector<TrackedFace> outFaces;
    std::vector<Rect> outDetections;
    int detectionCount = 0;
    std::vector<Rect> uprightHits;  ///< the last completed upright scan's faces
    int uprightCount = 0;

    TiltedScan tilted;  ///< the moving regions no track covers, turned

    std::vector<Rect> excluded;
    bool scanDone = false;
    long windows = 0;

    // Per-track flow scratch.
    std::array<Point2f, kMaxPoints> next{};
    std::array<FlowStatus, kMaxPoints> status{};
    std::array<Point2f, kMaxPoints> from{};
    std::array<Point2f, kMaxPoints> to{};
    std::array<std::uint8_t, kMaxPoints> inliers{};
    std::array<Corner, kMaxPoints> found{};
    std::array<Point2f, kMaxPoints> rollPoints{};
    char error[96] = "";
};

void FaceTracker::Impl::prepareScanMask(const ConstImageView& mask) noexcept
{
    // 3 "Detection": scan where there is motion, or where a face was seen recently (a face that
    // stops moving for a moment must still be found again).
    const Size s = options.imageSize;
    if (coldStart) {
        std::memset(scanMask.view().data, 255, scanMask.bytes());
        scanMaskIntegral.compute(scanMask.view());
        return;
    }
    for (int y = 0; y < s.height; ++y)
        std::memcpy(scanMask.view().row(y), mask.row(y), static_cast<std::size_t>(s.width));
    for (RecentArea& a : recent) {
        if (a.expires < frameIndex || a.box.width <= 0)
            continue;
        const Rect r = clip(a.box, s);
        for (int y = r.y; y < r.y + r.height; ++y)
            std::memset(scanMask.view().row(y) + r.x, 255, static_cast<std::size_t>(r.width));
    }
    scanMaskIntegral.compute(scanMask.view());
}

void FaceTracker::Impl::findCorners(Track& t, bool replenish) noexcept
{
    // 3 "Tracking": Shi-Tomasi corners in the face box, spaced in proportion to the face size.
    const float minDistance = std::max(2.f, t.face.size * options.cornerMinDistanceFraction);
    corners.setMinDistance(minDistance);
    corners.setMaxCorners(options.maxCornersPerFace);
    // The inner part of the box: the box corners are often background or hair, which do not
    // move with the face.
    const float inner = t.face.size * 0.7f;
    const Rect area{static_cast<int>(t.face.centre.x - inner * 0.5f),
                    static_cast<int>(t.face.centre.y - inner * 0.5f), static_cast<int>(inner),
                    static_cast<int>(inner)};
    const int n = corners.detect(grays[current].view(), area, found.data(), kMaxPoints);
    if (!replenish)
        t.pointCount = 0;
    const float minSq = minDistance * minDistance;
    for (int i = 0; i < n && t.pointCount < options.maxCornersPerFace; ++i) {
        const Point2f p = found[static_cast<std::size_t>(i)].position;
        bool nearExisting = false;
        for (int k = 0; k < t.pointCount && !nearExisting; ++k) {
            const float dx = t.points[static_cast<std::size_t>(k)].x - p.x;
            const float dy = t.points[static_cast<std::size_t>(k)].y - p.y;
            nearExisting = dx * dx + dy * dy < minSq;
        }
        if (!nearExisting)
            t.points[static_cast<std::size_t>(t.pointCount++)] = p;
    }
}

void FaceTracker::Impl::trackPoints(Track& t) noexcept
{
    const ImagePyramid& prev = pyramids[1 - current];
    const ImagePyramid& cur = pyramids[current];
    const int n = t.pointCount;
    if (n == 0)
        return;
    flow.track(prev, cur, t.points.data(), next.data(), status.data(), n);
    int m = 0;
    for (int i = 0; i < n; ++i) {
        if (status[static_cast<std::size_t>(i)] != FlowStatus::Tracked)
            continue;
        from[static_cast<std::size_t>(m)] = t.points[static_cast<std::size_t>(i)];
        to[static_cast<std::size_t>(m)] = next[static_cast<std::size_t>(i)];
        ++m;
    }
    const int minimum = options.mode == FaceTrackingMode::Affine ? 4 : 3;
    MotionModel model;
    const int in = m >= minimum ? fitMotionRobust(from.data(), to.data(), m, t.face.centre,
                                                  options.fit, model, inliers.data())
                                : 0;
    const float survived = n > 0 ? static_cast<float>(in) / static_cast<float>(n) : 0.f;
    t.heldByCorners =
        in >= std::max(minimum, options.minCornersPerFace / 2) && survived >= kHeldFraction;
    if (in < minimum) {
        // Nothing reliable moved: keep the box where it was, start the corners afresh.
        t.pointCount = 0;
        t.face.confidence *= 0.5f;
        return;
    }
    const Point2f moved = model.apply(t.face.centre);
    const float shift = std::hypot(moved.x - t.face.centre.x, moved.y - t.face.centre.y);
    const auto pairs = static_cast<std::size_t>(m);
    staticRule.addFlowStep(t.motion, {{from.data(), pairs}, {to.data(), pairs},
                                      {inliers.data(), pairs}, model, t.face.age, survived, shift});
    t.face.centre = moved;
    if (options.mode != FaceTrackingMode::Translation) {
        // Scale and roll of the similarity part (METHOD §3: th = atan2(a2, a1)).
        // A face does not change size by more than a few percent between frames; larger fitted
        // scales come from corners on the background or hair.
        const float s = std::clamp(model.scale(), 0.95f, 1.05f);
        t.face.size *= s;
        t.face.rollDegrees += model.roll() * kRadToDeg;
        t.face.rollDegrees = std::clamp(t.face.rollDegrees, -60.f, 60.f);
    }
    int k = 0;
    for (int i = 0; i < m; ++i)
        if (inliers[static_cast<std::size_t>(i)])
            t.points[static_cast<std::size_t>(k++)] = to[static_cast<std::size_t>(i)];
    t.pointCount = k;
    t.face.confidence = std::min(1.f, survived);
}

float FaceTracker::Impl::initialRoll(Track& t, float rollHint) noexcept
{
    // Beyond 5.2: the dense symmetry of the face image, which holds on small faces whose corner
    // sets are not symmetric; the corners' point symmetry (5.2) when it has no answer.
    if (imageRoll) {
        const RollEstimate r =
            imageRoll->estimate(grays[current].view(), t.face.centre, t.face.size);
        if (r.confidence >= kMinImageRollConfidence &&
            (rollHint == 0.f || std::fabs(r.rollDegrees - rollHint) <= 20.f)) {
            t.motion.imageRollAtStart = r.rollDegrees;
            t.motion.haveImageRollAtStart = true;
            return r.rollDegrees;
        }
    }
    // A tilted scan's hit: the face is within the cascade's reach of the scan's angle.
    if (rollHint != 0.f)
        return rollHint;
    const int n = std::min(t.pointCount, kMaxPoints);
    for (int i = 0; i < n; ++i)
        rollPoints[static_cast<std::size_t>(i)] = t.points[static_cast<std::size_t>(i)];
    const RollEstimate r = estimateRollBySymmetry(
        std::span<const Point2f>(rollPoints.data(), static_cast<std::size_t>(n)), t.face.centre,
        t.face.size);
    return r.confidence > 0.f ? r.rollDegrees : 0.f;
}

void FaceTracker::Impl::startTrack(Rect box, float rollHint) noexcept
{
    if (trackCount >= options.maxFaces)
        return;
    Track& t = tracks[static_cast<std::size_t>(trackCount)];
    t = Track{};
    t.face.id = nextId++;
    if (nextId <= 0)  // wrapped after 2^31 faces
        nextId = 1;
    t.face.centre = {static_cast<float>(box.x) + static_cast<float>(box.width) * 0.5f,
                     static_cast<float>(box.y) + static_cast<float>(box.height) * 0.5f};
    t.face.size = static_cast<float>(std::max(box.width, box.height));
    t.face.hits = 1;
    t.face.state = options.confirmFrames <= 1 ? FaceState::Confirmed : FaceState::Tentative;
    t.face.confidence = 1.f / static_cast<float>(options.confirmFrames);
    // A face found still is not shown until it moves; it is dropped if it never does.
    const bool moving = staticRule.start(t.motion, box, rollHint != 0.f);
    if (t.face.state == FaceState::Confirmed && !moving)
        t.face.state = FaceState::Tentative;
    t.detectedThisFrame = true;
    if (options.mode != FaceTrackingMode::None)
        findCorners(t, false);
    if (options.initialRollBySymmetry && (options.mode == FaceTrackingMode::Similarity ||
                                          options.mode == FaceTrackingMode::Affine)) {
        t.face.rollDegrees = initialRoll(t, rollHint);
    }
    ++trackCount;
}

void FaceTracker::Impl::drop(int index) noexcept
{
    const Track& t = tracks[static_cast<std::size_t>(index)];
    if (t.face.state != FaceState::Tentative) {
        // Remember where a face was, so it is scanned for again even if it stands still.
        RecentArea* slot = &recent[0];
        for (RecentArea& a : recent)
            if (a.expires < slot->expires)
                slot = &a;
        slot->box = t.face.box();
        slot->expires = frameIndex + options.recentFaceFrames;
    }
    for (int i = index; i + 1 < trackCount; ++i)
        tracks[static_cast<std::size_t>(i)] = tracks[static_cast<std::size_t>(i + 1)];
    --trackCount;
}

bool FaceTracker::Impl::process(const ConstImageView& gray, const ConstImageView& mask,
                                const IntegralImage* maskIntegral) noexcept
{
    const Size s = options.imageSize;
    if (gray.format != PixelFormat::Gray8 || gray.width != s.width || gray.height != s.height ||
        gray.data == nullptr) {
        std::snprintf(error, sizeof error, "faces: expected a %dx%d Gray8 image, got %dx%d %s",
                      s.width, s.height, gray.width, gray.height, pixelFormatName(gray.format));
        return false;
    }
    const bool maskGiven = mask.data != nullptr && mask.width > 0;
    if (maskGiven &&
        (mask.format != PixelFormat::Gray8 || mask.width != s.width || mask.height != s.height)) {
        std::snprintf(error, sizeof error, "faces: expected a %dx%d Gray8 mask, got %dx%d %s",
                      s.width, s.height, mask.width, mask.height, pixelFormatName(mask.format));
        return false;
    }
    error[0] = '\0';
    ++frameIndex;
    windows = 0;
    scanDone = false;

    // This frame's grey copy (the caller's buffer changes under us) and pyramid.
    current = 1 - current;
    for (int y = 0; y < s.height; ++y)
        std::memcpy(grays[current].view().row(y), gray.row(y), static_cast<std::size_t>(s.width));
    pyramids[current].build(grays[current].view());
    haveMotion = maskGiven && options.useMotionMask;
    motion = &motionIntegral;
    if (haveMotion) {
        if (maskIntegral != nullptr && maskIntegral->size() == s)
            motion = maskIntegral;
        else
            motionIntegral.compute(mask);
    }
    staticRule.beginFrame(grays[current].view(), haveMotion ? motion : nullptr, frameIndex);

    // 1. Existing tracks follow their corners.
    for (int i = 0; i < trackCount; ++i) {
        Track& t = tracks[static_cast<std::size_t>(i)];
        t.detectedThisFrame = false;
        t.heldByCorners = false;
        ++t.face.age;
        if (options.mode != FaceTrackingMode::None && havePrevious)
            trackPoints(t);
    }
    havePrevious = true;
    // Tracks that left the image or merged into another face end here.
    for (int i = 0; i < trackCount;) {
        const TrackedFace& f = tracks[static_cast<std::size_t>(i)].face;
        const bool outside = f.centre.x < 0.f || f.centre.y < 0.f ||
                             f.centre.x >= static_cast<float>(s.width) ||
                             f.centre.y >= static_cast<float>(s.height) || f.size < 8.f;
        bool duplicate = false;
        for (int k = 0; k < i && !duplicate; ++k)
            duplicate = iou(tracks[static_cast<std::size_t>(k)].face.box(), f.box()) > 0.5f;
        if (outside || duplicate)
            drop(i);
        else
            ++i;
    }

    // 2. Detection where there is motion (or a face was recently) and no track is.
    int excludedCount = 0;
    if (options.mode != FaceTrackingMode::None)
        for (int i = 0; i < trackCount; ++i)
            excluded[static_cast<std::size_t>(excludedCount++)] =
                tracks[static_cast<std::size_t>(i)].face.box();
    const std::span<const Rect> exclude(excluded.data(), static_cast<std::size_t>(excludedCount));
    int detected = 0;
    if (coldStart && haveMotion && motion->sum(0, 0, s.width, s.height) > 0)
        coldStart = false;
    const bool cold = coldStart;
    if (haveMotion)
        prepareScanMask(mask);
    // A cold start's scan is not spread over frames: the faces in view when the mirror starts
    // (or its camera comes back) are all found in that one frame, which may take longer.
    const long budget = cold ? 0 : options.detectionWindowBudget;
    if (options.detectionWindowBudget > 0) {
        // The scan spread over frames: faces() holds a result only when a scan completes.
        scanDone = scan.detectMaskedIncremental(grays[current].view(),
                                                haveMotion ? &scanMaskIntegral : nullptr,
                                                options.minMaskFraction, exclude, budget);
        detected = scanDone ? static_cast<int>(scan.faces().size()) : 0;
    } else if (haveMotion) {
        detected = scan.detectMasked(grays[current].view(), scanMaskIntegral,
                                     options.minMaskFraction, exclude);
        scanDone = true;
    } else if (excludedCount > 0) {
        // No mask: everything scannable, but tracked faces still excluded (a minimum fraction
        // of 0 accepts every window of the all-zero mask table).
        detected = scan.detectMasked(grays[current].view(), scanMaskIntegral, 0.f, exclude);
        scanDone = true;
    } else {
        detected = scan.detect(grays[current].view());
        scanDone = true;
    }
    windows += scan.windowsEvaluated();
    if (scanDone) {
        coldStart = false;
        uprightCount = std::min(detected, static_cast<int>(uprightHits.size()));
        for (int d = 0; d < uprightCount; ++d)
            uprightHits[static_cast<std::size_t>(d)] = scan.faces()[static_cast<std::size_t>(d)];
    }
    // Tilted scans of the moving regions no track covers, with what the budget left.
    long left = 0;
    if (haveMotion && options.mode != FaceTrackingMode::None) {
        // A cold start's tilted scans cover the whole image once, as its upright scan does, in
        // its frame.
        left = options.tiltWindowBudget > 0 && !cold ? options.tiltWindowBudget
                                                     : TiltedScan::kUnlimited;
        if (budget > 0)
            left = std::min(left, budget - scan.windowsEvaluated());
    }
    windows += tilted.run({grays[current].view(), scanMask.view(), scanMaskIntegral,
                           {tracks.data(), static_cast<std::size_t>(trackCount)}},
                          left);
    detectionCount = 0;
    for (int d = 0; d < uprightCount; ++d)
        outDetections[static_cast<std::size_t>(detectionCount++)] =
            uprightHits[static_cast<std::size_t>(d)];
    for (const Rect& b : tilted.hits())
        outDetections[static_cast<std::size_t>(detectionCount++)] = b;

    // 3. Detections (of the scans completed this frame) confirm the tracks they overlap; the
    // others start new tracks, a tilted scan's with its angle as the first guess of the roll.
    const int newUpright = scanDone ? uprightCount : 0;
    const int newTilted = tilted.completed() ? static_cast<int>(tilted.hits().size()) : 0;
    for (int d = 0; d < newUpright + newTilted; ++d) {
        const bool isTilted = d >= newUpright;
        const Rect box = isTilted ? tilted.hits()[static_cast<std::size_t>(d - newUpright)]
                                  : uprightHits[static_cast<std::size_t>(d)];
        int best = -1;
        float bestIou = options.matchIou;
        for (int i = 0; i < trackCount; ++i) {
            const float v = iou(tracks[static_cast<std::size_t>(i)].face.box(), box);
            if (v >= bestIou) {
                bestIou = v;
                best = i;
            }
        }
        if (best < 0) {
            // A box around a tracked face's centre is that face with its surroundings (a
            // grouping of windows over two heads), not a new face: faces do not overlap so.
            bool holdsTrack = false;
            for (int i = 0; i < trackCount && !holdsTrack; ++i) {
                const Point2f c = tracks[static_cast<std::size_t>(i)].face.centre;
                holdsTrack = c.x >= static_cast<float>(box.x) && c.y >= static_cast<float>(box.y) &&
                             c.x < static_cast<float>(box.x + box.width) &&
                             c.y < static_cast<float>(box.y + box.height);
            }
            if (!holdsTrack)
                startTrack(box, isTilted
                                    ? tilted.hitRolls()[static_cast<std::size_t>(d - newUpright)]
                                    : 0.f);
            continue;
        }
        Track& t = tracks[static_cast<std::size_t>(best)];
        if (t.detectedThisFrame)
            continue;
        t.detectedThisFrame = true;
        // A detection re-anchors position and size (tracking drifts, detections do not).
        t.face.centre = {static_cast<float>(box.x) + static_cast<float>(box.width) * 0.5f,
                         static_cast<float>(box.y) + static_cast<float>(box.height) * 0.5f};
        t.face.size = static_cast<float>(std::max(box.width, box.height));
        if (options.mode != FaceTrackingMode::None && t.pointCount < options.minCornersPerFace)
            findCorners(t, true);
    }

    // 4. Tracks without a detection are verified; 5. confirmation and grace.
    for (int i = 0; i < trackCount;) {
        Track& t = tracks[static_cast<std::size_t>(i)];
        bool seen = t.detectedThisFrame;
        const bool isNew = t.face.age == 0;
        if (!seen && options.mode != FaceTrackingMode::None)
            seen = verifier.verify(grays[current].view(), t, windows);
        if (!isNew) {
            if (seen) {
                ++t.face.hits;
                t.face.misses = 0;
            } else {
                t.face.hits = 0;
                ++t.face.misses;
            }
        }
        // Static regions are ignored (StaticFaceRule): a face shows it is a person by moving.
        const StaticFaceRule::Verdict still = staticRule.observe(t.motion, t.face, seen);
        const bool movedLately = still.movedLately;
        bool keep = true;
        if (t.face.state == FaceState::Tentative) {
            if (!seen)
                keep = false;  // a face not yet shown gets no grace: phantoms die at once
            else if (t.face.hits >= options.confirmFrames && movedLately)
                t.face.state = FaceState::Confirmed;
        } else if (seen) {
            t.face.state = FaceState::Confirmed;
        } else if (t.face.misses > options.graceFrames &&
                   (!t.heldByCorners || t.face.misses > options.occludedGraceFrames)) {
            keep = false;
        } else {
            t.face.state = FaceState::Missing;
        }
        if (!staticRule.keeps(still, t.face))
            keep = false;
        if (keep && options.mode != FaceTrackingMode::None && seen &&
            t.pointCount < options.minCornersPerFace)
            findCorners(t, true);
        // Confidence: recent detection record, scaled by the corners that survived the flow.
        const float record = std::min(
            1.f, static_cast<float>(t.face.hits) / static_cast<float>(options.confirmFrames));
        t.face.confidence = seen ? std::max(record * t.face.confidence, record * 0.5f) : 0.f;
        if (keep)
            ++i;
        else
            drop(i);
    }
    publish();
    return true;
}

void FaceTracker::Impl::publish() noexcept
{
    for (int i = 0; i < trackCount; ++i) {
        const Track& t = tracks[static_cast<std::size_t>(i)];
        TrackedFace& f = outFaces[static_cast<std::size_t>(i)];
        f = t.face;
        f.points = t.points.data();
        f.pointCount = t.pointCount;
    }
}

FaceTracker::FaceTracker(const HaarCascade& cascade, const FaceTrackerOptions& options)
{
    validate(options);
    impl_ = std::make_unique<Impl>(cascade, options);
}

FaceTracker::~FaceTracker() = default;
FaceTracker::FaceTracker(FaceTracker&&) noexcept = default;
FaceTracker& FaceTracker::operator=(FaceTracker&&) noexcept = default;

bool FaceTracker::process(const ConstImageView& gray, const ConstImageView& motionMask) noexcept
{
    return impl_->process(gray, motionMask, nullptr);
}

bool FaceTracker::process(const ConstImageView& gray, const ConstImageView& motionMask,
                          const IntegralImage* maskIntegral) noexcept
{
    return impl_->process(gray, motionMask, maskIntegral);
}

std::span<const TrackedFace> FaceTracker::faces() const noexcept
{
    return {impl_->outFaces.data(), static_cast<std::size_t>(impl_->trackCount)};
}

std::span<const Rect> FaceTracker::detections() const noexcept
{
    return {impl_->outDetections.data(), static_cast<std::size_t>(impl_->detectionCount)};
}

bool FaceTracker::scanCompleted() const noexcept
{
    return impl_->scanDone;
}
long FaceTracker::windowsEvaluated() const noexcept
{
    return impl_->windows;
}

void FaceTracker::reset() noexcept
{
    impl_->trackCount = 0;
    impl_->havePrevious = false;
    impl_->detectionCount = 0;
    impl_->uprightCount = 0;
    impl_->tilted.reset();
    impl_->scan.resetIncremental();
    impl_->recent.fill(RecentArea{});
    impl_->coldStart = true;
}

const FaceTrackerOptions& FaceTracker::options() const noexcept
{
    return impl_->options;
}
const char* FaceTracker::lastError() const noexcept
{
    return impl_->error;
}

}  // namespace vision
