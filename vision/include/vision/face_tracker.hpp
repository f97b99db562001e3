#pragma once
// FaceTracker: detection and tracking of every face, integrated as in the dissertation's fig. 89
// (METHOD.md §3, "Integration"), with the initial roll by point symmetry (§4).
//
// Each frame, on a grey image at the working resolution (the motion stage's, e.g. 360x240):
//  1. every live track moves by the motion model fitted to its corners, tracked by pyramidal
//     Lucas-Kanade with a forward-backward check (translation / similarity / affine, RANSAC);
//     corners are replenished inside the box when too few survive;
//  2. the detector scans where there is motion (or a face was seen recently) and no track is,
//     within a per-frame window budget (a scan may take several frames); the moving regions no
//     track covers are also scanned turned by +-tiltScanDegrees, for faces that enter tilted
//     beyond the upright cascade's reach. The first frame (after construction or reset(),
//     before the motion mask marks anything) is scanned whole, upright and turned, whatever the
//     budget: the faces in view at start are all found at once, and step 5 sorts them;
//  3. a track overlapping a detection is confirmed by it; a detection overlapping no track starts a
//     new track (initial roll by symmetry, near a tilted scan's angle for its hits), unless its
//     box holds a tracked face's centre (a grouping over two heads);
//  4. a track without a detection is verified by warping its face upright by its roll into a small
//     patch and running first-hit detection there (again at the roll +-12 degrees if that fails:
//     the tracked roll drifts); a failed verification is a miss;
//  5. a track becomes Confirmed (shown) after `confirmFrames` detections or verifications in a
//     row, and is dropped after `graceFrames` misses in a row (`occludedGraceFrames` while its
//     corners still hold it).
// Ids are stable for the life of a track and never reused while the tracker lives.
// Everything is allocated by the constructor; process() never allocates and never throws.
#include "vision/face_detector.hpp"
#include "vision/geometry.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/image.hpp"
#include "vision/integral_image.hpp"
#include "vision/motion_model.hpp"
#include "vision/optical_flow.hpp"

#include <cstdint>
#include <memory>
#include <span>

namespace vision {

/// How tracks move between detections (the rows of the dissertation's Table 6).
enum class FaceTrackingMode : std::uint8_t {
    None,         ///< detector only: a track lives only while it is detected
    Translation,  ///< corners move the box; no roll
    Similarity,   ///< translation, scale and roll, with roll-warped verification
    Affine,       ///< like Similarity with a full affine fit (roll/scale from its similarity part)
};

enum class FaceState : std::uint8_t {
    Tentative,  ///< seen, not yet confirmed: not shown
    Confirmed,  ///< shown
    Missing,    ///< was confirmed, missed by the last detection/verification, within grace
};

/// One face as the tracker reports it. Coordinates are in the tracker's working image (the
/// caller scales them to the frame; FaceStage reports frame coordinates).
struct TrackedFace {
    int id = 0;               ///< stable, > 0
    Point2f centre{};         ///< centre of the face box
    float size = 0.f;         ///< side of the (square) face box in pixels
    float rollDegrees = 0.f;  ///< clockwise on screen (y down), see RollEstimate
    /// 0..1: the fraction of the last `confirmFrames` frames in which it was detected or
    /// verified, scaled by the fraction of its corners that survived the last flow step.
    float confidence = 0.f;
    int age = 0;     ///< frames since the track started
    int hits = 0;    ///< detections or verifications in a row
    int misses = 0;  ///< failed verifications in a row
    FaceState state = FaceState::Tentative;
    /// The corners tracked last frame (inliers of the motion fit), valid until the next process().
    const Point2f* points = nullptr;
    int pointCount = 0;

    /// The axis-aligned box of side `size` about `centre`, rounded.
    Rect box() const noexcept
    {
        const float half = size * 0.5f;
        return {static_cast<int>(centre.x - half + 0.5f), static_cast<int>(centre.y - half + 0.5f),
                static_cast<int>(size + 0.5f), static_cast<int>(size + 0.5f)};
    }
    bool shown() const noexcept { return state != FaceState::Tentative; }
};

struct FaceTrackerOptions {
    Size imageSize{360, 240};        ///< working image (grey) the tracker is given every frame
    FaceDetectorOptions detector{};  ///< maxFrameSize is set to imageSize by the tracker
    FaceTrackingMode mode = FaceTrackingMode::Similarity;
    bool useMotionMask = true;     ///< scan only where the motion mask (or a recent face) is
    float minMaskFraction = 0.1f;  ///< a window needs this fraction of mask pixels
    int recentFaceFrames = 30;     ///< a dropped face's area stays scannable this long
    /// Detector windows per frame (0 = whole scan every frame). A bigger scan continues on the
    /// next frames, so no frame stalls on detection.
    long detectionWindowBudget = 0;
    int confirmFrames = 2;  ///< n: detections in a row before a face is shown
    int graceFrames = 5;    ///< m: misses in a row before a track is dropped
    /// Beyond fig. 89: a shown face the detector misses while its corners still move together
    /// (most survive each flow step) is covered, not gone: a hand or another head in front of
    /// part of it, or the head turned. It keeps its place for this many misses in a row
    /// (at least graceFrames) before it is dropped.
    int occludedGraceFrames = 30;
    int maxFaces = 8;                         ///< tracks at most
    int maxCornersPerFace = 40;               ///< corners found in a new box
    int minCornersPerFace = 12;               ///< replenish when fewer survive
    float cornerMinDistanceFraction = 0.05f;  ///< corner spacing as a fraction of the face size
    OpticalFlowOptions flow{};
    MotionFitOptions fit{};  ///< kind follows `mode`
    /// Upright patch side for verification (the face is warped to ~patch / 1.6).
    int verifyPatchSize = 48;
    /// A detection and a track are the same face when their boxes overlap by at least this IoU.
    float matchIou = 0.3f;
    bool initialRollBySymmetry = true;  ///< §4; otherwise new faces start at roll 0
    /// Roll from the dense symmetry of the face image (RollByImageSymmetry) for new faces and,
    /// at each re-anchoring, to correct the tracked roll; false: corner point symmetry only.
    bool rollByImageSymmetry = true;
    /// Static regions are ignored (the dissertation's motion rule; with a motion mask only): a
    /// face shows it moves when its centre leaves the place it last moved from by
    /// minFaceMoveFraction of its size (at least 1 px; only flow steps that moved nearly all of
    /// its corners count), or when this fraction of the inner half of its box is foreground, or
    /// (not yet shown) when it turned in place by a few degrees and its image's symmetry agrees.
    /// A photo on the wall beside a moving person does none of these (its mask fraction stays
    /// at a few percent, but lighting changes can raise it, hence the high threshold; the
    /// passer-by drags only the corners nearest to it). A Tentative track is confirmed only if it
    /// moved within the last confirmMotionFrames frames (and a Tentative one that has not, after
    /// twice that, is dropped), and a shown track that has not moved for staticDropFrames frames is
    /// dropped (a photo that slipped through; a person standing still keeps their hat much longer).
    float minFaceMoveFraction = 0.015f;
    float minFaceMotionFraction = 0.6f;
    int confirmMotionFrames = 30;
    int staticDropFrames = 9000;
    /// Faces that enter tilted beyond the upright cascade's reach (about +-15 degrees): the
    /// moving regions no track covers are also scanned turned by +tiltScanDegrees and
    /// -tiltScanDegrees (one angle per scan, alternating), within what the upright scan left of
    /// the window budget; a hit there starts a track with that roll (refined from the image).
    /// 0: upright scans only.
    float tiltScanDegrees = 25.f;
    /// Tilted-scan windows per frame at most (0 = no limit of its own); a longer tilted scan
    /// continues on the next frames. Tilted scans share detectionWindowBudget too: they get only
    /// what the upright scan left of it.
    long tiltWindowBudget = 4000;
    /// Every this many verified frames, verification runs a grouped scan of the upright patch
    /// instead of first hit and re-centres / re-sizes the track from it (stops scale drift).
    int reanchorEvery = 5;
};

class FaceTracker {
public:
    /// Builds the detectors (scan and verification) from `cascade` and allocates every buffer.
    /// Throws std::runtime_error on bad options.
    FaceTracker(const HaarCascade& cascade, const FaceTrackerOptions& options);
    ~FaceTracker();
    FaceTracker(FaceTracker&&) noexcept;
    FaceTracker& operator=(FaceTracker&&) noexcept;

    /// One frame: `gray` is the working image (Gray8, imageSize); `motionMask` the foreground
    /// mask (Gray8, 255 = moving) at imageSize, or an empty view (no mask: everything is
    /// scannable, and motion is not required of a face). Returns false (tracks unchanged,
    /// lastError() set) on a wrong image.
    bool process(const ConstImageView& gray, const ConstImageView& motionMask) noexcept;
    /// The same with the mask's integral image already computed (MotionStage keeps one): saves
    /// recomputing it. `maskIntegral` must be that of `motionMask`; null: computed here.
    bool process(const ConstImageView& gray, const ConstImageView& motionMask,
                 const IntegralImage* maskIntegral) noexcept;

    /// Live tracks, Tentative ones included (check shown()), oldest first.
    std::span<const TrackedFace> faces() const noexcept;
    /// Detections of the last completed scans (working-image boxes, upright and tilted; a
    /// tilted hit as the axis-aligned box of its size about its centre), for the HUD and
    /// evaluation.
    std::span<const Rect> detections() const noexcept;
    /// True when the last process() completed a detector scan.
    bool scanCompleted() const noexcept;
    /// Detector windows evaluated by the last process() (upright and tilted scans, and
    /// verification).
    long windowsEvaluated() const noexcept;

    /// Drops every track (e.g. after the camera came back).
    void reset() noexcept;
    const FaceTrackerOptions& options() const noexcept;
    const char* lastError() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vision
