#pragma once
// CornerFlow: how FaceTracker moves a face between detections (METHOD.md §3, "Tracking"):
// Shi-Tomasi corners in the face box, followed by pyramidal Lucas-Kanade from the last frame to
// this one, a robust motion model fitted to the pairs, and the face moved by it. It keeps this
// frame's grey copy and pyramid and the last frame's. Private to vision/src.
//
// Use: newFrame() once a frame, then follow() each track (when hasPrevious()) and find() corners
// in new or re-anchored boxes; image() is this frame's grey copy.
#include "face_track.hpp"
#include "static_face_rule.hpp"
#include "vision/background_motion.hpp"
#include "vision/corner_detector.hpp"
#include "vision/face_tracker.hpp"
#include "vision/image.hpp"
#include "vision/image_pyramid.hpp"
#include "vision/optical_flow.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace vision {

class CornerFlow {
public:
    /// Allocates the images, pyramids and scratch. `options.fit.kind` must follow its mode.
    explicit CornerFlow(const FaceTrackerOptions& options);

    /// Copies this frame's grey image (the caller's buffer changes under us) and builds its
    /// pyramid.
    void newFrame(const ConstImageView& gray) noexcept;
    /// True when a frame came before this one (since construction or reset()).
    bool hasPrevious() const noexcept { return hasPrevious_; }
    ConstImageView image() const noexcept { return grays_[current_].view(); }

    /// Measures how the view moved since the last frame (BackgroundMotion), away from the
    /// `tracks`' faces; once a frame, before follow().
    void followBackground(std::span<const Track> tracks) noexcept;
    const BackgroundMotion& background() const noexcept { return background_; }
    /// Moves `t` by its corners' flow from the last frame (position, and with roll: scale and
    /// roll); keeps the corners that fit; tells `rule` how the face moved against the view.
    void follow(Track& t, StaticFaceRule& rule) noexcept;
    /// Finds corners in `t`'s box, added to those it has (`replenish`) or instead of them.
    void find(Track& t, bool replenish) noexcept;
    /// Forgets the last frame.
    void reset() noexcept;

private:
    void move(Track& t, const MotionModel& model, int pairs) noexcept;
    void tellRule(Track& t, StaticFaceRule& rule, const MotionModel& model, int pairs,
                  float survived) noexcept;

    FaceTrackerOptions options_;
    CornerDetector corners_;
    PyramidalLucasKanade flow_;
    ImagePyramid pyramids_[2];
    ImageBuffer grays_[2];
    int current_ = 0;  ///< index of this frame's gray / pyramid
    bool hasCurrent_ = false;
    bool hasPrevious_ = false;
    // Per-track flow scratch.
    std::array<Point2f, kMaxPoints> next_{};
    std::array<FlowStatus, kMaxPoints> status_{};
    std::array<Point2f, kMaxPoints> from_{};
    std::array<Point2f, kMaxPoints> to_{};
    std::array<std::uint8_t, kMaxPoints> inliers_{};
    std::array<Corner, kMaxPoints> found_{};
    BackgroundMotion background_;
    std::array<Rect, kMaxTracks> faces_{};     ///< followBackground()'s scratch
    std::array<Point2f, kMaxPoints> ownTo_{};  ///< to_ less the view's motion
};

}  // namespace vision
