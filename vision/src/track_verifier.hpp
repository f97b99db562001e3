#pragma once
// TrackVerifier: fig. 89's test of a track no detection confirmed (METHOD.md §3, "Integration"):
// the face is warped upright by its tracked roll into a small patch and the patch is scanned in
// first-hit mode. Every few verifications it scans the patch grouped instead and re-anchors the
// track on the face it finds (position, size, and roll from the image). Private to vision/src.
//
// A track that came in at the image's edge is first re-centred, while young and near the edge,
// by a grouped scan of the image about it (recentre()): the cascade boxes a face partly out of
// view off its centre. So is a track whose box its corners grew or shrank (faces crossing).
//
// Use: construct once with the tracker's options; beginFrame() once a frame, then recentre() or
// else verify() a track each frame it was not detected. At most one track re-anchors in a frame
// (faces at the image's edge aside): the others due wait a frame, so that no frame pays for every
// track's grouped scan and roll measurement at once (tracks started together fall due together).
#include "face_track.hpp"
#include "vision/face_detector.hpp"
#include "vision/face_tracker.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/image.hpp"
#include "vision/roll_by_image_symmetry.hpp"

namespace vision {

class TrackVerifier {
public:
    /// A face box grown by this factor that reaches beyond the image is a face at its edge: one
    /// found by the part in view may be this much larger.
    static constexpr float kEdgeGrowth = 1.5f;

    /// Allocates the patch and the patch detector. `imageRoll` (null: none) measures the roll
    /// at re-anchoring; it must outlive the verifier.
    TrackVerifier(const HaarCascade& cascade, const FaceTrackerOptions& options,
                  RollByImageSymmetry* imageRoll);

    /// A new frame: its one re-anchoring is free again.
    void beginFrame() noexcept { anchoring_ = nullptr; }

    /// True when a face is at `t` in `gray` (the working image). May move `t.face` (re-anchoring,
    /// and its roll towards where the face was found). Adds the windows it evaluated to `windows`.
    bool verify(const ConstImageView& gray, Track& t, long& windows) noexcept;

    /// A track that came in at the image's edge (Track::cameInAtEdge), while young and within
    /// its size of the edge, or one whose box its corners grew or shrank by more than 15% since
    /// it was last placed (Track::anchorSize): a grouped scan of the image about it, twice its
    /// size (its placed size), re-centres and re-sizes it on the face found there. True when it
    /// did (the face is there; its corners are then the caller's to find afresh); false when the
    /// track is not such a one (any more) or nothing was found: verify() then as usual.
    bool recentre(const ConstImageView& gray, Track& t, long& windows) noexcept;

    /// Whether the face's box grown by `growth` reaches beyond the image of size `image`.
    static bool reachesBeyond(const TrackedFace& f, Size image, float growth) noexcept;

private:
    bool verifyAt(const ConstImageView& gray, Track& t, float roll, long& windows) noexcept;
    void reanchor(const ConstImageView& gray, Track& t, const Rect& hit, float roll,
                  float side) noexcept;
    // The roll measured from the image again (at most every reanchorEvery frames unless `force`).
    void correctRoll(const ConstImageView& gray, Track& t, bool force) noexcept;

    FaceTrackerOptions options_;
    FaceDetector detector_;
    ImageBuffer patch_;
    FaceDetector wideDetector_;  ///< recentre()'s grouped scan
    ImageBuffer widePatch_;      ///< recentre()'s view of the image about the track
    RollByImageSymmetry* imageRoll_;
    const Track* anchoring_ = nullptr;  ///< the track (not at the edge) re-anchoring this frame
};

}  // namespace vision
