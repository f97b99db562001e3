#pragma once
// FaceTracker: detection and tracking of every face, integrated as in the dissertation's fig. 89
// (METHOD.md §3, "Integration"), with the initial roll by point symmetry (§4).
//
// Give process() each frame's grey image at the working resolution (the motion stage's, e.g.
// 360x240) and its motion mask; faces() are then the tracked faces. Per frame, the five steps of
// fig. 89: 1. every track moves by the flow of its corners; 2. the detector scans where there is
// motion (or a face was seen recently) and no track is, upright and, for faces that come in
// tilted, turned by +-tiltScanDegrees, within a window budget whose first part goes to the edge
// bands where faces come into view (the first frame after construction
// or reset() is scanned whole); 3. a detection keeps the track it overlaps or starts a new one;
// 4. a track without one is verified on its face warped upright by its roll; 5. a face is shown
// after confirmFrames detections or verifications in a row and dropped after graceFrames misses
// in a row (occludedGraceFrames while its corners still hold it), or when it never moves.
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
    bool useMotionMask = true;       ///< scan only where the motion mask (or a recent face) is
    float minMaskFraction = 0.1f;    ///< a window needs this fraction of mask pixels
    int recentFaceFrames = 30;       ///< a dropped face's area stays scannable this long
    long detectionWindowBudget = 0;  ///< detector windows per frame; 0: whole scans
    int confirmFrames = 2;           ///< n: detections in a row before a face is shown
    int graceFrames = 5;             ///< m: misses in a row before a track is dropped
    int occludedGraceFrames = 30;    ///< misses while its corners still hold it (>= graceFrames)
    int maxFaces = 8;                ///< tracks at most
    int maxCornersPerFace = 40;      ///< corners found in a new box
    int minCornersPerFace = 12;      ///< replenish when fewer survive
    float cornerMinDistanceFraction = 0.05f;  ///< corner spacing as a fraction of the face size
    OpticalFlowOptions flow{};
    MotionFitOptions fit{};    ///< kind follows `mode`
    int verifyPatchSize = 48;  ///< upright verification patch side (the face ~ patch / 1.6)
    float matchIou = 0.3f;     ///< a detection is a track's face at this IoU or more
    bool initialRollBySymmetry = true;  ///< §4; otherwise new faces start at roll 0
    bool rollByImageSymmetry = true;    ///< roll by the image's symmetry, new and re-anchored faces
    // Faces that never move are dropped (StaticFaceRule, with a motion mask only):
    float minFaceMoveFraction = 0.015f;  ///< a move: the centre shifts this x its size (>= 1 px)
    float minFaceMotionFraction = 0.6f;  ///< or this much of its inner box is foreground
    bool livenessBySway = true;          ///< or its corners sway as one (LivenessCue)
    int confirmMotionFrames = 30;        ///< shown only if it moved this recently
    int staticDropFrames = 9000;         ///< a shown face still this long is dropped
    float tiltScanDegrees = 25.f;  ///< TiltedScan's angle (+- alternately); 0: upright scans only
    long tiltWindowBudget = 4000;  ///< tilted windows per frame at most (0: no limit of its own)
    int reanchorEvery = 5;         ///< verified frames between re-anchoring grouped scans
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
    /// Detector windows evaluated by the last process() (upright and tilted scans, and
    /// verification).
    long windowsEvaluated() const noexcept;

    /// Drops every track (e.g. after the camera came back).
    void reset() noexcept;
    /// Drops every track and scans the whole next frame at once, moving or not: after a scene
    /// cut (SceneCut), where everything moves and every face is new.
    void resetAfterCut() noexcept;
    const FaceTrackerOptions& options() const noexcept;
    const char* lastError() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vision
