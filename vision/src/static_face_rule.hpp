#pragma once
// StaticFaceRule: FaceTracker drops faces that never move (posters and photos on the wall), the
// dissertation's rule that static regions are not faces (METHOD.md §3, "Detection"; 5.1.3),
// taken from the search mask to the tracks. A face shows it moves by its corners carrying its
// centre away as one, by a box full of motion, by turning in place as its image agrees, or (a
// person standing still) by its corners swaying together as only a living face's do (LivenessCue),
// all measured against the background: a print moves with it when the camera shakes.
// Private to vision/src.
//
// Use: each track keeps a FaceMotion. Per frame: beginFrame(); start() for a new track;
// addFlowStep() after each flow step; in step 5 observe() before the track's state is decided
// (movedLately gates confirmation) and keeps() after.
#include "vision/face_tracker.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"
#include "vision/integral_image.hpp"
#include "vision/liveness_cue.hpp"
#include "vision/motion_model.hpp"
#include "vision/roll_by_image_symmetry.hpp"

#include <cstdint>
#include <span>

namespace vision {

/// What the rule keeps of one track.
struct FaceMotion {
    int lastMotionFrame = 0;  ///< frame index of the last frame the face showed it moves
    float anchor = 0.f;       ///< `path` when the face last moved
    /// How far the image content of the face has travelled since the track began: the sum of
    /// the per-frame shifts of its centre by the motion model (tracking modes) or of the centre
    /// itself (detector only), each counted only above the noise of a still image.
    float path = 0.f;
    Point2f lastCentre{};  ///< detector only: the centre last frame
    /// Started by a tilted scan's hit: until shown, only `path` shows it moves, not the mask.
    bool tiltFound = false;
    /// How far its roll turned since it started, by flow steps that moved all of the face, and
    /// (when confident) the image symmetry's roll at the start (set by whoever measured it).
    float turn = 0.f;
    float imageRollAtStart = 0.f;
    bool haveImageRollAtStart = false;
    float rollChecked = 0.f;  ///< the tracked turn at the last check in the image
    SwayHistory sway;         ///< its last flow steps, for LivenessCue
};

class StaticFaceRule {
public:
    /// `imageRoll` (null: none) measures a turn in the image; it must outlive the rule.
    StaticFaceRule(const FaceTrackerOptions& options, RollByImageSymmetry* imageRoll) noexcept;

    /// This frame: the working image, the motion mask's integral image (null: no mask, and then
    /// no face needs to move), the frame's index, and how far the camera moved the view since
    /// the last frame (BackgroundMotion::largestDisplacement()).
    void beginFrame(const ConstImageView& gray, const IntegralImage* motion, int frame,
                    float viewMoved) noexcept;
    /// A new track found at `box` (by a tilted scan: `tiltFound`). True when it counts as
    /// moving already (its box full of motion).
    bool start(FaceMotion& m, Rect box, bool tiltFound) const noexcept;

    /// One flow step of a track: the corner pairs the motion fit saw (`inliers` marks its
    /// inliers), the fit, the track's age, the fraction of its corners that survived and the
    /// shift of its centre (all less the view's motion), and the view's shift at the face.
    struct FlowStep {
        std::span<const Point2f> from, to;
        std::span<const std::uint8_t> inliers;
        const MotionModel& model;
        int age;
        float survived;
        float shift;
        float viewShift;  ///< how far the camera moved the view at the face (BackgroundMotion)
        Point2f view{};   ///< the same as a vector (taken off the flow)
    };
    void addFlowStep(FaceMotion& m, const FlowStep& step) noexcept;

    /// Whether a face moved within the last staticDropFrames (`moved`) and confirmMotionFrames
    /// (`movedLately`) frames.
    struct Verdict {
        bool moved;
        bool movedLately;
    };
    /// Step 5, before the track's state is decided: `seen` is this frame's detection or
    /// verification; `alone`: no other track's box overlaps the face's.
    Verdict observe(FaceMotion& m, const TrackedFace& face, bool seen, bool alone) noexcept;
    /// Step 5, after: false when the face is to be dropped for never moving.
    bool keeps(const Verdict& v, const TrackedFace& face) const noexcept;

private:
    static bool movedAsOne(const FlowStep& step) noexcept;
    bool turnedInImage(FaceMotion& m, const TrackedFace& face) noexcept;
    float motionFraction(Rect box) const noexcept;

    FaceTrackerOptions options_;
    RollByImageSymmetry* imageRoll_;
    LivenessCue liveness_;
    ConstImageView gray_{};
    const IntegralImage* motion_ = nullptr;
    int frame_ = 0;
    int viewMovedFrame_ = -1000000;  ///< the last frame the camera moved the view
};

}  // namespace vision
