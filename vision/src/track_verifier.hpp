#pragma once
// TrackVerifier: fig. 89's test of a track no detection confirmed (METHOD.md §3, "Integration"):
// the face is warped upright by its tracked roll into a small patch and the patch is scanned in
// first-hit mode. Every few verifications it scans the patch grouped instead and re-anchors the
// track on the face it finds (position, size, and roll from the image). Private to vision/src.
//
// Use: construct once with the tracker's options; beginFrame() once a frame, then verify() a
// track each frame it was not detected. At most one track re-anchors in a frame (faces at the
// image's edge aside): the others due wait a frame, so that no frame pays for every track's
// grouped scan and roll measurement at once (tracks started together fall due together).
#include "face_track.hpp"
#include "vision/face_detector.hpp"
#include "vision/face_tracker.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/image.hpp"
#include "vision/roll_by_image_symmetry.hpp"

namespace vision {

class TrackVerifier {
public:
    /// Allocates the patch and the patch detector. `imageRoll` (null: none) measures the roll
    /// at re-anchoring; it must outlive the verifier.
    TrackVerifier(const HaarCascade& cascade, const FaceTrackerOptions& options,
                  RollByImageSymmetry* imageRoll);

    /// A new frame: its one re-anchoring is free again.
    void beginFrame() noexcept { anchoring_ = nullptr; }

    /// True when a face is at `t` in `gray` (the working image). May move `t.face` (re-anchoring,
    /// and its roll towards where the face was found). Adds the windows it evaluated to `windows`.
    bool verify(const ConstImageView& gray, Track& t, long& windows) noexcept;

private:
    bool verifyAt(const ConstImageView& gray, Track& t, float roll, long& windows) noexcept;
    void reanchor(const ConstImageView& gray, Track& t, const Rect& hit, float roll,
                  float side) noexcept;
    void correctRoll(const ConstImageView& gray, Track& t) noexcept;

    FaceTrackerOptions options_;
    FaceDetector detector_;
    ImageBuffer patch_;
    RollByImageSymmetry* imageRoll_;
    const Track* anchoring_ = nullptr;  ///< the track (not at the edge) re-anchoring this frame
};

}  // namespace vision
