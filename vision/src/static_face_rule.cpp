#include "static_face_rule.hpp"

#include "face_track.hpp"
#include "vision/geometry.hpp"

#include <algorithm>
#include <cmath>

// The dissertation keeps still regions out of the detector's search mask (5.1.3: "prevents the
// possibility of static regions of the background being falsely detected as faces"). A face on
// the wall beside a moving person is inside the mask all the same (the person's motion, a
// recently seen face, the light changing), so the tracker also asks each track to show it moves:
// its centre leaving the place it last moved from by a few percent of its size (only flow steps
// that moved nearly all of its corners count), a box full of motion while its corners move, (not
// yet shown) a turn in place by a few degrees that the image's symmetry agrees with, or, for a
// person standing still, its corners swaying together by a fraction of a pixel (LivenessCue). A
// photo does none of these: its mask fraction stays at a few percent (a change of light can fill
// it, hence the high threshold and the corners that must move with it: facegen seed 23's `one`
// showed a photo for 247 frames on the mask alone), and a passer-by drags only the corners
// nearest to it. A Tentative face is confirmed only if it moved within the last
// confirmMotionFrames frames (and dropped if it has not after twice that); a shown face still for
// staticDropFrames frames is dropped.

namespace vision {

namespace {

/// Per-frame shifts of a face's centre (working-image pixels) below this are the noise of a
/// still image (sensor noise, light changing), not motion.
constexpr float kStillShift = 0.25f;
/// The first frames of a track settle its box (detections move it a few pixels).
constexpr int kSettleFrames = 5;
/// Fraction of a young track's corners that must follow its motion fit for the motion to count.
constexpr float kCoherentFraction = 0.85f;
/// Fraction of a track's corners that must each move along its shift (by half of it at least)
/// for the shift to count as the face moving.
constexpr float kMovedAsOneFraction = 0.75f;
/// The fraction of the view's motion (BackgroundMotion) that a face's own shift may be in error
/// by far from the corners that measured it (facegen --shake 3: up to about a quarter).
constexpr float kViewError = 0.5f;
/// A Tentative face whose tracked roll turned this far since it started is checked for turning
/// in the image (and again after each further step as far): each check is one estimate of the
/// image's roll, and a face turning in place a degree a frame waited four frames for the first
/// at 4 degrees (facegen seed 42's `rotate`: shown at frame 6 of a cold start).
constexpr float kTurnCheckDegrees = 2.f;
/// The image's roll must have turned the same way by this much for the turn to count: what it
/// was asked when the checks came every 4 degrees (a photo's tracked turn is the corners' noise,
/// and the image must not agree with it more easily for being asked more often).
constexpr float kTurnSeenDegrees = 2.f;

}  // namespace

StaticFaceRule::StaticFaceRule(const FaceTrackerOptions& options,
                               RollByImageSymmetry* imageRoll) noexcept
    : options_(options), imageRoll_(imageRoll)
{
}

void StaticFaceRule::beginFrame(const ConstImageView& gray, const IntegralImage* motion, int frame,
                                float viewMoved) noexcept
{
    gray_ = gray;
    motion_ = motion;
    frame_ = frame;
    if (viewMoved > kStillShift)
        viewMovedFrame_ = frame;
}

float StaticFaceRule::motionFraction(Rect box) const noexcept
{
    if (motion_ == nullptr)
        return 1.f;
    // The inner half of the box: a head moving past a still face (a poster, a photo on the wall)
    // sweeps the edges of its box far more than its middle.
    return motion_->maskFraction(
        {box.x + box.width / 4, box.y + box.height / 4, box.width / 2, box.height / 2});
}

bool StaticFaceRule::start(FaceMotion& m, Rect box, bool tiltFound) const noexcept
{
    // A face found still is not shown until it moves; it is dropped if it never does.
    // A tilted scan's hit must show motion of its own: the turned regions offer the cascade more
    // windows, hence more chance hits on still faces, and a changing light can fill a still
    // face's box with foreground.
    m.tiltFound = tiltFound;
    // With corners to follow, a box full of foreground counts only once they moved too
    // (observe()): a change of light fills a photo's box as well.
    const bool maskAlone = options_.mode == FaceTrackingMode::None;
    m.lastMotionFrame =
        maskAlone && !m.tiltFound && motionFraction(box) >= options_.minFaceMotionFraction
            ? frame_
            : frame_ - options_.confirmMotionFrames - 1;
    return m.lastMotionFrame == frame_;
}

void StaticFaceRule::addFlowStep(FaceMotion& m, const FlowStep& step) noexcept
{
    // A person never holds perfectly still (a talking head wobbles back and forth, which a net
    // displacement would cancel); a photo's shifts stay in the noise. Re-anchoring the box on a
    // detection is not motion and does not count. A young track's box may hold some background
    // or a passing head, whose motion the fit can follow: its shifts count only when nearly all
    // of its corners agree with them.
    const bool coherent = step.age >= kSettleFrames || step.survived >= kCoherentFraction;
    const bool asOne = coherent && movedAsOne(step);
    // The view's motion is known to a fraction of itself: a shift within that fraction of it is
    // the error of the view's motion (a print beside a shaking view), not the face's own.
    if (step.shift > kStillShift + kViewError * step.viewShift && asOne)
        m.path += step.shift;
    if (options_.mode != FaceTrackingMode::Translation && asOne)
        m.turn += toDegrees(step.model.roll());
    // A sway is a fraction of a pixel: against a view the camera moved by more, measured to a
    // few hundredths at best, it cannot be told (a print's own flow then sways as much as a calm
    // head's, by the errors of the view's motion). Such steps say nothing about liveness.
    if (frame_ != viewMovedFrame_)
        liveness_.addFlowStep(m.sway, step.from, step.to, step.inliers, step.model, step.view);
}

bool StaticFaceRule::movedAsOne(const FlowStep& step) noexcept
{
    // A still face beside a moving one (a photo on the wall as someone passes it) has its fit
    // pulled along by the corners nearest the passer-by, whose flow windows hold part of them:
    // a robust fit keeps them all as inliers, yet only those few moved. A face that moves (or
    // turns) moves all its corners as the fit says (measured: 93-100% of them, against 25-36%
    // for a photo beside a passing head). Corners the fit hardly moves (near the centre of a
    // turn) say nothing.
    int along = 0, counted = 0;
    for (std::size_t i = 0; i < step.from.size(); ++i) {
        if (!step.inliers[i])
            continue;
        const Point2f a = step.from[i];
        const Point2f b = step.to[i];
        const Point2f p = step.model.apply(a);
        const float dx = p.x - a.x;
        const float dy = p.y - a.y;
        const float d2 = dx * dx + dy * dy;
        if (d2 < kStillShift * kStillShift * 0.25f)
            continue;
        // (b - a) . d >= |d|^2 / 2: moved along the fit by at least half of it.
        along += (b.x - a.x) * dx + (b.y - a.y) * dy >= 0.5f * d2;
        ++counted;
    }
    return counted > 0 &&
           static_cast<float>(along) >= kMovedAsOneFraction * static_cast<float>(counted);
}

bool StaticFaceRule::turnedInImage(FaceMotion& m, const TrackedFace& face) noexcept
{
    // A face turning about its own centre (a head tilting from side to side) hardly moves its
    // centre, so `path` misses it. Its tracked roll does turn, but corners near a face moving past
    // a still one can turn that one's fit too (the edge of the passer-by uncovers and covers it):
    // the turn counts only when the image's symmetry, measured afresh, turned the same way, and
    // only while no other face is in its box (observe()): the symmetry of a box that holds part
    // of a passer-by turns with the passer-by (facegen seed 23's `one`: a photo below a head
    // passing over it was shown for 23 frames).
    if (!imageRoll_ || !m.haveImageRollAtStart || options_.mode == FaceTrackingMode::Translation)
        return false;
    if (std::fabs(m.turn) < std::fabs(m.rollChecked) + kTurnCheckDegrees)
        return false;
    m.rollChecked = m.turn;
    const RollEstimate r = imageRoll_->estimate(gray_, face.centre, face.size);
    if (r.confidence < kMinImageRollConfidence)
        return false;
    const float seen = r.rollDegrees - m.imageRollAtStart;
    return seen * m.turn > 0.f && std::fabs(seen) >= kTurnSeenDegrees;
}

StaticFaceRule::Verdict StaticFaceRule::observe(FaceMotion& m, const TrackedFace& face, bool seen,
                                                bool alone) noexcept
{
    // Detector only: the first frames of a track settle its box (detections move it a few
    // pixels): they are no evidence either way. Tracking measures the motion of the face's
    // corners, which re-anchoring does not add to, so it counts from the first frame.
    if (options_.mode == FaceTrackingMode::None) {
        // Detections jitter by a pixel or so from frame to frame.
        const float jump =
            std::hypot(face.centre.x - m.lastCentre.x, face.centre.y - m.lastCentre.y);
        if (face.age > 0 && jump > 1.5f)
            m.path += jump;
        m.lastCentre = face.centre;
    }
    if (options_.mode == FaceTrackingMode::None && face.age < kSettleFrames)
        m.anchor = m.path;
    const bool haveMotion = motion_ != nullptr;
    const float step = std::max(1.0f, options_.minFaceMoveFraction * face.size);
    // The mixture of Gaussians takes a still camera (METHOD.md §3, "Motion"): once the camera
    // moved the view, every edge is foreground until the mixture has learnt the view again, a
    // print's box as much as a head's.
    const bool maskCounts =
        !(m.tiltFound && face.state == FaceState::Tentative) &&
        frame_ - viewMovedFrame_ > options_.confirmMotionFrames &&
        (options_.mode == FaceTrackingMode::None || LivenessCue::stirred(m.sway));
    const bool sways = options_.livenessBySway && LivenessCue::swayed(m.sway);
    if (m.path - m.anchor > step || sways ||
        (maskCounts && motionFraction(face.box()) >= options_.minFaceMotionFraction) ||
        (haveMotion && face.state == FaceState::Tentative && seen && alone &&
         turnedInImage(m, face))) {
        m.lastMotionFrame = frame_;
        m.anchor = m.path;
    }
    return {!haveMotion || frame_ - m.lastMotionFrame <= options_.staticDropFrames,
            !haveMotion || frame_ - m.lastMotionFrame <= options_.confirmMotionFrames};
}

bool StaticFaceRule::keeps(const Verdict& v, const TrackedFace& face) const noexcept
{
    // A face found still (a photo on the wall, detected while someone moved nearby) is never
    // shown and is let go; a shown face that stops moving stays until it has been still for a
    // long time: staticDropFrames catches a photo that slipped through, while a person standing
    // still in front of the mirror keeps their hat much longer.
    if (face.state == FaceState::Tentative && !v.movedLately &&
        face.age > 2 * options_.confirmMotionFrames)
        return false;
    return v.moved;
}

}  // namespace vision
