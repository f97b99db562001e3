#include "track_verifier.hpp"

#include "vision/geometry.hpp"
#include "vision/upright_patch.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace vision {

namespace {

/// The verification patch shows the face box enlarged by this factor: the detector's window
/// must fit around the face at a few scales.
constexpr float kVerifyContext = 1.6f;
/// Verification retries this far either side of the tracked roll (the upright cascade finds
/// faces within about +-15 degrees).
constexpr float kVerifyRollStep = 12.f;
/// recentre(): the side of the image scanned about a track that came in at the edge, in track
/// sizes, and its patch (the face about half of it, so the cascade's window fits it at a few
/// scales from 0.75 to 1.3 of its size).
constexpr float kWideContext = 2.f;
constexpr int kWidePatch = 64;
constexpr int kWideMaxFace = 42;
/// recentre() runs for a track this young (one second at 30 fps) whose box grown by
/// kWideReach still reaches beyond the image (the face may still be partly out of view).
constexpr int kRecentreFrames = 30;
constexpr float kWideReach = 2.f;
/// recentre() also runs for a track whose box its corners have grown or shrunk by more than this
/// factor since a detection or a grouped scan last placed it (before CornerFlow's kHeldGrowth,
/// 1.25 of the size last seen, ends a missed track's occluded grace).
constexpr float kRegrowth = 1.15f;

FaceDetectorOptions wideOptions(const FaceTrackerOptions& o, Size window)
{
    FaceDetectorOptions d;
    d.maxFrameSize = {kWidePatch, kWidePatch};
    d.scaleFactor = o.detector.scaleFactor;
    d.minNeighbors = o.detector.minNeighbors;
    d.minSize = window;
    d.maxSize = {kWideMaxFace, kWideMaxFace};
    d.maxRawHits = 1024;
    d.maxFaces = 16;
    return d;
}

FaceDetectorOptions verifyOptions(const FaceTrackerOptions& o, Size window)
{
    // The face fills about 1 / kVerifyContext of the patch; scan from the smallest window up to
    // the whole patch with the scan's scale factor.
    FaceDetectorOptions d;
    d.maxFrameSize = {o.verifyPatchSize, o.verifyPatchSize};
    d.scaleFactor = o.detector.scaleFactor;
    d.minNeighbors = 1;
    d.minSize = window;
    d.maxSize = {o.verifyPatchSize, o.verifyPatchSize};
    d.maxRawHits = 1024;
    d.maxFaces = 16;
    return d;
}

/// The face's box, grown by kEdgeGrowth, reaches beyond the image.
bool atEdge(const TrackedFace& f, const ConstImageView& gray) noexcept
{
    return TrackVerifier::reachesBeyond(f, {gray.width, gray.height}, TrackVerifier::kEdgeGrowth);
}

/// Of the first `n` boxes of a grouped scan of a square patch (centre at `half`, patch pixels),
/// the one whose centre is nearest the patch's centre; `distance2`: its squared distance.
const Rect& nearestToCentre(std::span<const Rect> boxes, int n, float half,
                            float& distance2) noexcept
{
    int best = 0;
    distance2 = 1e9f;
    for (int i = 0; i < n; ++i) {
        const Rect& b = boxes[static_cast<std::size_t>(i)];
        const float dx = static_cast<float>(b.x) + static_cast<float>(b.width) * 0.5f - half;
        const float dy = static_cast<float>(b.y) + static_cast<float>(b.height) * 0.5f - half;
        const float d = dx * dx + dy * dy;
        if (d < distance2) {
            distance2 = d;
            best = i;
        }
    }
    return boxes[static_cast<std::size_t>(best)];
}

/// A box's centre from the patch's centre (at `half`), in image pixels (`unit` a patch pixel),
/// along the patch's axes.
Point2f offsetInPatch(const Rect& b, float half, float unit) noexcept
{
    return {(static_cast<float>(b.x) + static_cast<float>(b.width) * 0.5f - half) * unit,
            (static_cast<float>(b.y) + static_cast<float>(b.height) * 0.5f - half) * unit};
}

/// An offset along the axes of a patch warped upright by `rollDegrees`, turned back to the image.
Point2f turnedToImage(Point2f p, float rollDegrees) noexcept
{
    const float c = std::cos(rollDegrees / kDegreesPerRadian);
    const float s = std::sin(rollDegrees / kDegreesPerRadian);
    return {c * p.x - s * p.y, s * p.x + c * p.y};
}

/// Whether a box of side `size` whose centre is (dx, dy) from the track's shares at least half
/// (IoU) with the track's box of side `track`.
bool sameFace(float track, float size, float dx, float dy) noexcept
{
    const auto overlap = [](float a, float b, float d) {
        const float lo = std::max(-0.5f * a, d - 0.5f * b);
        const float hi = std::min(0.5f * a, d + 0.5f * b);
        return std::max(0.f, hi - lo);
    };
    const float common = overlap(track, size, dx) * overlap(track, size, dy);
    return common >= 0.5f * (track * track + size * size - common);
}

}  // namespace

TrackVerifier::TrackVerifier(const HaarCascade& cascade, const FaceTrackerOptions& options,
                             RollByImageSymmetry* imageRoll)
    : options_(options),
      detector_(cascade, verifyOptions(options, {cascade.windowWidth, cascade.windowHeight})),
      patch_(options.verifyPatchSize, options.verifyPatchSize, PixelFormat::Gray8),
      wideDetector_(cascade, wideOptions(options, {cascade.windowWidth, cascade.windowHeight})),
      widePatch_(kWidePatch, kWidePatch, PixelFormat::Gray8),
      imageRoll_(imageRoll)
{
}

bool TrackVerifier::reachesBeyond(const TrackedFace& f, Size image, float growth) noexcept
{
    const float half = f.size * 0.5f * growth;
    return f.centre.x - half < 0.f || f.centre.y - half < 0.f ||
           f.centre.x + half > static_cast<float>(image.width) ||
           f.centre.y + half > static_cast<float>(image.height);
}

bool TrackVerifier::recentre(const ConstImageView& gray, Track& t, long& windows) noexcept
{
    // A face coming into view is found by the part of it in view, and the cascade boxes that
    // part off the face's centre (facegen seed 57's `enter-leave`: 40 px inward of a 110 px face
    // coming in at the right, until it was wholly in view); the corners then carry the box as
    // found, and verify()'s patch, 1.6 times the box about the wrong centre, does not reach
    // the face's far side. So while such a track is young and near the edge, the image about it
    // (twice its size, upright by its roll) is scanned grouped (§3, "Detection") and the track
    // re-centred on the face found nearest its centre: as more of the face comes into view, the
    // box follows it out to the edge.
    //
    // The same scan finds a face again in a box its corners have grown or shrunk by more than a
    // face does between two anchorings (facegen seed 13's `two`: two faces crossing pulled one's
    // corners apart, its box grew from 103 to 153 px over a face of 87 while first-hit
    // verification still passed on part of it, a false face and a missed one for 7 frames, the
    // face unshown until the whole mask's scan found it again 6 frames after the track went):
    // the scan is then of the size the box was last placed at.
    if (t.cameInAtEdge && (t.face.age > kRecentreFrames ||
                           !reachesBeyond(t.face, {gray.width, gray.height}, kWideReach)))
        t.cameInAtEdge = false;
    const bool grown = t.anchorSize > 0.f && (t.face.size > kRegrowth * t.anchorSize ||
                                              t.face.size * kRegrowth < t.anchorSize);
    if (!t.cameInAtEdge && !grown)
        return false;
    const float side = (grown ? t.anchorSize : t.face.size) * kWideContext;
    if (!warpUpright(gray, t.face.centre, t.face.rollDegrees, side, widePatch_.view()))
        return false;
    const int n = wideDetector_.detect(widePatch_.view());
    windows += wideDetector_.windowsEvaluated();
    if (n <= 0)
        return false;
    const float half = static_cast<float>(kWidePatch) * 0.5f;
    const float unit = side / static_cast<float>(kWidePatch);
    float bestDistance = 0.f;
    const Rect& b = nearestToCentre(wideDetector_.faces(), n, half, bestDistance);
    // The face the track holds is the one about its centre: a group whose centre is more than
    // half the track's size away is another face, or a face beside this one.
    const float faceHalf = 0.5f * static_cast<float>(kWidePatch) / kWideContext;  // patch px
    if (bestDistance > faceHalf * faceHalf)
        return false;
    const Point2f move = turnedToImage(offsetInPatch(b, half, unit), t.face.rollDegrees);
    t.face.centre.x += move.x;
    t.face.centre.y += move.y;
    t.face.size = static_cast<float>(b.width) * unit;
    t.anchorSize = t.face.size;
    t.verifiedSinceAnchor = 0;
    correctRoll(gray, t, grown);
    return true;
}

bool TrackVerifier::verify(const ConstImageView& gray, Track& t, long& windows) noexcept
{
    // Fig. 89: a track with no detection is verified by warping its face upright by the tracked
    // roll into a small patch and running first-hit detection on it.
    if (options_.mode == FaceTrackingMode::Translation)
        return verifyAt(gray, t, 0.f, windows);
    if (verifyAt(gray, t, t.face.rollDegrees, windows))
        return true;
    // The tracked roll drifts (corners on hair and outline): a shown face the cascade no longer
    // finds at it is tried once either side, within the cascade's reach, and the roll moves
    // towards where it was found. Not a Tentative one: those get no grace (a still photo that
    // lingers as a track would in time be confirmed by the light changing on it).
    if (t.face.state == FaceState::Tentative)
        return false;
    for (const float d : {-kVerifyRollStep, kVerifyRollStep}) {
        if (verifyAt(gray, t, t.face.rollDegrees + d, windows)) {
            t.face.rollDegrees += 0.5f * d;
            return true;
        }
    }
    return false;
}

bool TrackVerifier::verifyAt(const ConstImageView& gray, Track& t, float roll,
                             long& windows) noexcept
{
    const float side = t.face.size * kVerifyContext;
    if (!warpUpright(gray, t.face.centre, roll, side, patch_.view()))
        return false;
    // Every reanchorEvery verified frames a grouped scan of the patch instead of first hit
    // re-centres and re-sizes the track from it: the corners alone let its scale drift. A face
    // at the image's edge every frame: it was found by the part of it in view, which grows as
    // it comes in, while its corners keep the size it was found at.
    // One track's periodic re-anchoring a frame: a track due while another re-anchors is
    // verified first-hit and re-anchors on a later frame (§3: the dissertation alternates
    // detection and fitting between frames rather than doing all of it in one).
    const bool edge = atEdge(t.face, gray);
    const bool due = t.verifiedSinceAnchor + 1 >= options_.reanchorEvery &&
                     (anchoring_ == nullptr || anchoring_ == &t);
    const bool reanchoring = options_.reanchorEvery > 0 && (due || edge);
    if (reanchoring && !edge)
        anchoring_ = &t;  // its retries at other rolls re-anchor too
    if (!reanchoring) {
        Rect hit;
        const bool ok = detector_.detectFirst(patch_.view(), hit);
        windows += detector_.windowsEvaluated();
        if (ok)
            ++t.verifiedSinceAnchor;
        return ok;
    }
    // Grouped scan of the patch: the best group near the patch centre re-centres and re-sizes
    // the track (first hits say only "a face is here", not where exactly).
    const int n = detector_.detect(patch_.view());
    windows += detector_.windowsEvaluated();
    if (n <= 0)
        return false;
    float distance = 0.f;
    const float half = static_cast<float>(options_.verifyPatchSize) * 0.5f;
    reanchor(gray, t, nearestToCentre(detector_.faces(), n, half, distance), roll, side);
    return true;
}

void TrackVerifier::reanchor(const ConstImageView& gray, Track& t, const Rect& b, float roll,
                             float side) noexcept
{
    const float half = static_cast<float>(options_.verifyPatchSize) * 0.5f;
    const float unit = side / static_cast<float>(options_.verifyPatchSize);
    const float size = static_cast<float>(b.width) * unit;
    if (size < t.face.size * 0.6f || size > t.face.size * 1.6f)
        return;  // a face is there, but this box is not a sensible measure of it
    const Point2f offset = offsetInPatch(b, half, unit);
    // A track drifts by a few percent of its size between re-anchorings: a box that shares less
    // than half with it is another grouping of windows (facegen seed 42's `four`: one over the
    // chin and neck, a quarter of the face below it, moved the box off the face), not a measure
    // of this face.
    if (!sameFace(t.face.size, size, offset.x, offset.y))
        return;
    // Patch offset back to the image: rotated by the roll used for warping.
    const Point2f move = turnedToImage(offset, roll);
    t.face.centre.x += 0.8f * move.x;
    t.face.centre.y += 0.8f * move.y;
    t.face.size += 0.8f * (size - t.face.size);
    t.anchorSize = t.face.size;
    t.verifiedSinceAnchor = 0;
    correctRoll(gray, t, false);
}

void TrackVerifier::correctRoll(const ConstImageView& gray, Track& t, bool force) noexcept
{
    // Tracking accumulates small rotation errors (corners on hair and outline pull the fit
    // towards no rotation): when a face is re-anchored, its roll is measured again from the
    // image and the track moves halfway towards it. Not more often than a re-anchoring comes
    // due: a face at the image's edge (or one coming in) is re-anchored every frame, but its roll
    // does not drift faster there, and the measurement costs more than the grouped scan.
    if (!imageRoll_ || options_.mode == FaceTrackingMode::Translation)
        return;
    if (!force && t.face.age - t.rollMeasuredAge < std::max(options_.reanchorEvery, 1))
        return;
    t.rollMeasuredAge = t.face.age;
    const RollEstimate r = imageRoll_->estimate(gray, t.face.centre, t.face.size);
    if (r.confidence < kMinImageRollConfidence ||
        std::fabs(r.rollDegrees - t.face.rollDegrees) > 20.f)
        return;
    t.face.rollDegrees += 0.5f * (r.rollDegrees - t.face.rollDegrees);
}

}  // namespace vision
