#include "vision/face_tracker.hpp"

#include "corner_flow.hpp"
#include "entry_scan.hpp"
#include "face_search.hpp"
#include "face_track.hpp"
#include "static_face_rule.hpp"
#include "tilted_scan.hpp"
#include "track_verifier.hpp"
#include "vision/roll_by_image_symmetry.hpp"
#include "vision/roll_estimator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

// The dissertation's fig. 89 (5.1.3; METHOD.md §3, "Integration"), one frame:
//   motion detection                  -> MotionStage, before the tracker (its mask comes in)
//   update face poses                 -> step 1, updateFacePoses()
//   create face search mask,
//   face detection on masked area     -> step 2, detectInSearchMask() (EntryScan, FaceSearch,
//                                        TiltedScan)
//   overlap? keep face / add face     -> step 3, keepOrAddDetected()
//   warp face to frontal pose,
//   face detection on warped image    -> step 4, verifyUndetected() (TrackVerifier)
//   keep face / discard face          -> step 5, confirmOrDiscard(), with the text's n detections
//                                        before a face is shown and m failures before it is
//                                        dropped, and StaticFaceRule for faces that never move.

namespace vision {

namespace {

/// A detection re-anchors the track it matches only when they share this much (IoU).
constexpr float kReanchorIou = 0.5f;
/// A turned scan's hit whose centre is within this fraction of a tracked face's size of that
/// face's centre (both ways) is of part of that head: the reach of its motion, which the turned
/// scans look into (TiltedScan's and EntryScan's regions stop at it, their windows do not).
constexpr float kTiltedHitReach = 0.75f;
/// EntryScan gets what leaves the whole mask's scan the budget to complete a pass as large as
/// its last one within this many frames (a quarter of a second at 30 fps; with two faces
/// moving, facegen seed 13's `enter-leave`, a pass was up to 17400 windows, 7 frames at half
/// the shipped budget).
constexpr long kWholePassFrames = 8;

Point2f centreOf(Rect box) noexcept
{
    return {static_cast<float>(box.x) + static_cast<float>(box.width) * 0.5f,
            static_cast<float>(box.y) + static_cast<float>(box.height) * 0.5f};
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

/// The options as the tracker runs them (and reports them).
FaceTrackerOptions effective(FaceTrackerOptions o) noexcept
{
    o.detector.maxFrameSize = o.imageSize;
    o.fit.kind = fitKind(o.mode);
    return o;
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
        : options(effective(o)),
          cornerFlow(options),
          search(cascade, options),
          motionIntegral(o.imageSize),
          imageRoll(o.rollByImageSymmetry ? std::make_unique<RollByImageSymmetry>() : nullptr),
          verifier(cascade, options, imageRoll.get()),
          staticRule(options, imageRoll.get()),
          tilted(cascade, options),
          entry(cascade, options)
    {
        tracks.resize(static_cast<std::size_t>(o.maxFaces));
        outFaces.resize(static_cast<std::size_t>(o.maxFaces));
    }

    bool process(const ConstImageView& gray, const ConstImageView& mask,
                 const IntegralImage* maskIntegral) noexcept;
    bool accept(const ConstImageView& gray, const ConstImageView& mask) noexcept;
    void beginFrame(const ConstImageView& gray, const ConstImageView& mask,
                    const IntegralImage* maskIntegral) noexcept;
    void updateFacePoses() noexcept;
    void detectInSearchMask(const ConstImageView& mask) noexcept;
    void keepOrAddDetected() noexcept;
    void verifyUndetected() noexcept;
    void confirmOrDiscard() noexcept;
    void publish() noexcept;

    void dropLostTracks() noexcept;
    long entryBudget() const noexcept;
    long tiltBudget() const noexcept;
    void match(Rect box, float rollHint) noexcept;
    void startTrack(Rect box, float rollHint) noexcept;
    float initialRoll(Track& t, float rollHint) noexcept;
    bool keeps(Track& t) noexcept;
    bool alone(const Track& t) const noexcept;
    void drop(int index) noexcept;
    std::span<const Track> live() const noexcept
    {
        return {tracks.data(), static_cast<std::size_t>(trackCount)};
    }
    ConstImageView image() const noexcept { return cornerFlow.image(); }

    FaceTrackerOptions options;
    CornerFlow cornerFlow;  ///< step 1: the images, and the tracks' corners and their flow
    FaceSearch search;      ///< step 2: the upright scan of the search mask
    IntegralImage motionIntegral;
    const IntegralImage* motion = nullptr;           ///< this frame's mask integral; null: no mask
    std::unique_ptr<RollByImageSymmetry> imageRoll;  ///< null: corner symmetry only
    TrackVerifier verifier;                          ///< step 4: fig. 89's upright-warped check
    StaticFaceRule staticRule;  ///< step 5: faces that never move (photos on the wall) go
    TiltedScan tilted;          ///< step 2: the moving regions no track covers, turned
    EntryScan entry;            ///< step 2: first, the edge bands where faces come in
    std::vector<Track> tracks;  ///< [0, trackCount) live, oldest first
    int trackCount = 0;
    int nextId = 1;
    int frameIndex = 0;

    std::vector<TrackedFace> outFaces;
    long windows = 0;

    std::array<Point2f, kMaxPoints> rollPoints{};  ///< initialRoll's scratch
    char error[96] = "";
};

bool FaceTracker::Impl::process(const ConstImageView& gray, const ConstImageView& mask,
                                const IntegralImage* maskIntegral) noexcept
{
    if (!accept(gray, mask))
        return false;
    beginFrame(gray, mask, maskIntegral);
    updateFacePoses();         // 1. tracks follow their corners
    detectInSearchMask(mask);  // 2. detection where there is motion and no track is
    keepOrAddDetected();       // 3. a detection keeps the track it overlaps, or adds one
    verifyUndetected();        // 4. the other tracks, warped upright, are scanned again
    confirmOrDiscard();        // 5. n in a row to be shown, m misses to be dropped
    publish();
    return true;
}

bool FaceTracker::Impl::accept(const ConstImageView& gray, const ConstImageView& mask) noexcept
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
    return true;
}

void FaceTracker::Impl::beginFrame(const ConstImageView& gray, const ConstImageView& mask,
                                   const IntegralImage* maskIntegral) noexcept
{
    const Size s = options.imageSize;
    ++frameIndex;
    windows = 0;
    cornerFlow.newFrame(gray);
    motion = nullptr;
    if (mask.data != nullptr && mask.width > 0 && options.useMotionMask) {
        motion = &motionIntegral;
        if (maskIntegral != nullptr && maskIntegral->size() == s)
            motion = maskIntegral;
        else
            motionIntegral.compute(mask);
    }
    if (options.mode != FaceTrackingMode::None)
        cornerFlow.followBackground(live());
    staticRule.beginFrame(image(), motion, frameIndex,
                          cornerFlow.background().largestDisplacement());
}

void FaceTracker::Impl::updateFacePoses() noexcept
{
    for (int i = 0; i < trackCount; ++i) {
        Track& t = tracks[static_cast<std::size_t>(i)];
        t.detectedThisFrame = false;
        t.heldByCorners = false;
        ++t.face.age;
        if (options.mode != FaceTrackingMode::None && cornerFlow.hasPrevious())
            cornerFlow.follow(t, staticRule);
    }
    dropLostTracks();
}

void FaceTracker::Impl::dropLostTracks() noexcept
{
    // Tracks that left the image or merged into another face end here.
    const Size s = options.imageSize;
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
}

void FaceTracker::Impl::detectInSearchMask(const ConstImageView& mask) noexcept
{
    // Beyond fig. 89: first the edge bands where something moves untracked (a face coming in),
    // with what the whole mask's scan can spare (entryBudget()); the whole mask's scan gets the
    // rest.
    long spent = 0;
    if (entry.enabled() && motion != nullptr && !search.wasCold())
        spent = entry.run({image(), mask, *motion, live()}, entryBudget());
    windows += spent;
    windows += search.scan({image(), mask, motion, live(), frameIndex, spent});
    // Beyond fig. 89: the moving regions no track covers, turned, with what the budget left.
    windows += tilted.run({image(), search.mask(), search.maskIntegral(), live(), search.wasCold()},
                          tiltBudget());
}

long FaceTracker::Impl::entryBudget() const noexcept
{
    // The edge bands take only what the whole mask's scan can spare, at most half the budget:
    // the budget less what lets a pass of the whole mask, as large as the last one, complete
    // within kWholePassFrames frames. Nothing until a masked pass has completed since the cold
    // start (its cost is not known yet). A face coming in while little moves is found first in
    // its band; when much moves (a panning view: on the demo film the left band moved over its
    // whole height, one turned look over it took 13 frames of half the budget, and the whole
    // mask's scan, left the other half, completed a pass of 30000 windows at frame 12 and the
    // next, of about 90000, not by frame 48, so no face was shown in its first 2 s) the whole
    // mask's scan, which covers the bands too, keeps the budget (§3, "Detection").
    const long budget = options.detectionWindowBudget;
    const long pass = search.lastPassWindows();
    if (pass <= 0)
        return 0;
    return std::clamp(budget - pass / kWholePassFrames, 0L, budget / 2);
}

long FaceTracker::Impl::tiltBudget() const noexcept
{
    if (motion == nullptr || options.mode == FaceTrackingMode::None)
        return 0;
    // A cold start's tilted scans cover the whole image once, as its upright scan does, in its
    // frame.
    const long own = options.tiltWindowBudget > 0 && !search.wasCold() ? options.tiltWindowBudget
                                                                       : TiltedScan::kUnlimited;
    return std::min(own, search.windowsLeft());
}

void FaceTracker::Impl::keepOrAddDetected() noexcept
{
    // Detections of the scans completed this frame; a tilted scan's carry its angle as the
    // first guess of the roll.
    if (entry.completed())
        for (std::size_t d = 0; d < entry.hits().size(); ++d)
            match(entry.hits()[d], entry.hitRolls()[d]);
    if (search.completed())
        for (const Rect& box : search.hits())
            match(box, 0.f);
    if (tilted.completed())
        for (std::size_t d = 0; d < tilted.hits().size(); ++d)
            match(tilted.hits()[d], tilted.hitRolls()[d]);
}

void FaceTracker::Impl::match(Rect box, float rollHint) noexcept
{
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
        // A box around a tracked face's centre is that face with its surroundings (a grouping
        // of windows over two heads), not a new face: faces do not overlap so.
        bool holdsTrack = false;
        for (int i = 0; i < trackCount && !holdsTrack; ++i) {
            const Point2f c = tracks[static_cast<std::size_t>(i)].face.centre;
            holdsTrack = c.x >= static_cast<float>(box.x) && c.y >= static_cast<float>(box.y) &&
                         c.x < static_cast<float>(box.x + box.width) &&
                         c.y < static_cast<float>(box.y + box.height);
        }
        // A turned scan's hit beside a tracked head is a turned window over part of it and what
        // is beside it (facegen seed 13's `two`: a -25 degree hit on the lower part of a head
        // and below it, 0.7 of its size from its centre, moved with the head and was shown for
        // 24 frames). An upright hit there is still taken: faces that cross come so close. Only
        // shown faces count: a track not yet shown may be a chance hit itself (facegen seed 42's
        // `four`: a 224 px tilted hit at a cold start, gone the next frame, kept a face beside it
        // from being started for two frames).
        // An upright hit within that reach of two shown heads at once is a grouping of windows
        // over parts of both (facegen seed 57's `three`: a 52 px hit between two 82 px heads,
        // its centre 0.70 and 0.66 of their size from theirs, verified on what the two show of
        // a face, moved by their corners, shown and held for 34 frames): a face uncovered by a
        // crossing is beside the one head that covered it.
        int beside = 0;
        for (int i = 0; i < trackCount; ++i) {
            const TrackedFace& f = tracks[static_cast<std::size_t>(i)].face;
            const Point2f c = centreOf(box);
            beside += f.shown() && std::fabs(c.x - f.centre.x) < kTiltedHitReach * f.size &&
                      std::fabs(c.y - f.centre.y) < kTiltedHitReach * f.size;
        }
        const bool besideTrack = beside >= (rollHint != 0.f ? 1 : 2);
        if (!holdsTrack && !besideTrack)
            startTrack(box, rollHint);
        return;
    }
    Track& t = tracks[static_cast<std::size_t>(best)];
    if (t.detectedThisFrame)
        return;
    t.detectedThisFrame = true;
    // A detection re-anchors position and size (tracking drifts, detections do not), if it
    // shares half with the track, as TrackVerifier's re-anchoring does: the corners hold a face
    // to within a few percent of its size, and a box that shares less is a grouping beside it
    // (facegen seed 5's `three`: one 54 px to the left took a track off its face for 155 frames).
    if (bestIou < kReanchorIou)
        return;
    t.face.centre = centreOf(box);
    t.face.size = static_cast<float>(std::max(box.width, box.height));
    t.anchorSize = t.face.size;
    if (options.mode != FaceTrackingMode::None && t.pointCount < options.minCornersPerFace)
        cornerFlow.find(t, true);
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
    t.face.centre = centreOf(box);
    t.face.size = static_cast<float>(std::max(box.width, box.height));
    t.face.hits = 1;
    t.anchorSize = t.face.size;
    t.cameInAtEdge =
        TrackVerifier::reachesBeyond(t.face, options.imageSize, TrackVerifier::kEdgeGrowth);
    t.face.state = options.confirmFrames <= 1 ? FaceState::Confirmed : FaceState::Tentative;
    t.face.confidence = 1.f / static_cast<float>(options.confirmFrames);
    // A face found still is not shown until it moves; it is dropped if it never does.
    const bool moving = staticRule.start(t.motion, box, rollHint != 0.f);
    if (t.face.state == FaceState::Confirmed && !moving)
        t.face.state = FaceState::Tentative;
    t.detectedThisFrame = true;
    if (options.mode != FaceTrackingMode::None)
        cornerFlow.find(t, false);
    if (options.initialRollBySymmetry && (options.mode == FaceTrackingMode::Similarity ||
                                          options.mode == FaceTrackingMode::Affine)) {
        t.face.rollDegrees = initialRoll(t, rollHint);
    }
    ++trackCount;
}

float FaceTracker::Impl::initialRoll(Track& t, float rollHint) noexcept
{
    // Beyond §4: the dense symmetry of the face image, which holds on small faces whose corner
    // sets are not symmetric; the corners' point symmetry (§4, 5.2) when it has no answer.
    if (imageRoll) {
        const RollEstimate r = imageRoll->estimate(image(), t.face.centre, t.face.size);
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

void FaceTracker::Impl::verifyUndetected() noexcept
{
    verifier.beginFrame();
    for (int i = 0; i < trackCount; ++i) {
        Track& t = tracks[static_cast<std::size_t>(i)];
        t.seen = t.detectedThisFrame;
        if (!t.seen && options.mode != FaceTrackingMode::None &&
            verifier.recentre(image(), t, windows)) {
            t.seen = true;
            cornerFlow.find(t, false);  // the corners that carried the box off the face go
        }
        if (!t.seen && options.mode != FaceTrackingMode::None)
            t.seen = verifier.verify(image(), t, windows);
    }
}

void FaceTracker::Impl::confirmOrDiscard() noexcept
{
    for (int i = 0; i < trackCount;) {
        if (keeps(tracks[static_cast<std::size_t>(i)]))
            ++i;
        else
            drop(i);
    }
}

bool FaceTracker::Impl::keeps(Track& t) noexcept
{
    const bool seen = t.seen;
    if (seen)
        t.seenSize = t.face.size;
    if (t.face.age > 0) {  // a new track's detection is its first hit already
        if (seen) {
            ++t.face.hits;
            t.face.misses = 0;
        } else {
            t.face.hits = 0;
            ++t.face.misses;
        }
    }
    const StaticFaceRule::Verdict still = staticRule.observe(t.motion, t.face, seen, alone(t));
    bool keep = true;
    if (t.face.state == FaceState::Tentative) {
        if (!seen)
            keep = false;  // a face not yet shown gets no grace: phantoms die at once
        else if (t.face.hits >= options.confirmFrames && still.movedLately)
            t.face.state = FaceState::Confirmed;
    } else if (seen) {
        t.face.state = FaceState::Confirmed;
    } else if (t.face.misses > options.graceFrames &&
               (!t.heldByCorners || t.face.misses > options.occludedGraceFrames)) {
        // Beyond fig. 89: a shown face the detector misses while its corners still move together
        // is covered, not gone (a hand or another head in front of it, the head turned): it
        // keeps its place for occludedGraceFrames misses.
        keep = false;
    } else {
        t.face.state = FaceState::Missing;
    }
    keep = staticRule.keeps(still, t.face) && keep;
    if (keep && options.mode != FaceTrackingMode::None && seen &&
        t.pointCount < options.minCornersPerFace)
        cornerFlow.find(t, true);
    // Confidence: recent detection record, scaled by the corners that survived the flow.
    const float record =
        std::min(1.f, static_cast<float>(t.face.hits) / static_cast<float>(options.confirmFrames));
    t.face.confidence = seen ? std::max(record * t.face.confidence, record * 0.5f) : 0.f;
    return keep;
}

bool FaceTracker::Impl::alone(const Track& t) const noexcept
{
    // No other track's box overlaps this one's.
    const Rect b = t.face.box();
    for (const Track& o : live()) {
        if (&o == &t)
            continue;
        const Rect a = o.face.box();
        if (a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height &&
            b.y < a.y + a.height)
            return false;
    }
    return true;
}

void FaceTracker::Impl::drop(int index) noexcept
{
    const Track& t = tracks[static_cast<std::size_t>(index)];
    // Remember where a face was, so it is scanned for again even if it stands still.
    if (t.face.state != FaceState::Tentative)
        search.remember(t.face.box(), frameIndex);
    for (int i = index; i + 1 < trackCount; ++i)
        tracks[static_cast<std::size_t>(i)] = tracks[static_cast<std::size_t>(i + 1)];
    --trackCount;
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

long FaceTracker::windowsEvaluated() const noexcept
{
    return impl_->windows;
}

void FaceTracker::reset() noexcept
{
    impl_->trackCount = 0;
    impl_->cornerFlow.reset();
    impl_->tilted.reset();
    impl_->entry.reset();
    impl_->search.reset();
}

void FaceTracker::resetAfterCut() noexcept
{
    reset();
    impl_->search.reset(true);
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
