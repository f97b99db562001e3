#pragma once
// Track: one face FaceTracker follows (what it reports, its corners, its motion), and
// the constants the tracker's parts share. Private to vision/src.
#include "vision/face_tracker.hpp"
#include "vision/geometry.hpp"

#include <array>

namespace vision {

constexpr int kMaxPoints = 64;  ///< corners kept per track
constexpr int kMaxTracks = 32;  ///< hard cap on options.maxFaces
constexpr float kRadToDeg = 57.29577951308232f;
constexpr float kDegToRad = 1.f / kRadToDeg;
/// Image-symmetry roll estimates less sure than this are not used (RollEstimate::confidence).
constexpr float kMinImageRollConfidence = 0.15f;

struct Track {
    TrackedFace face;
    std::array<Point2f, kMaxPoints> points{};
    int pointCount = 0;
    int lastMotionFrame = 0;  ///< frame index of the last frame the face showed it moves
    float anchor = 0.f;       ///< `path` when the face last moved
    /// How far the image content of the face has travelled since the track began: the sum of
    /// the per-frame shifts of its centre by the motion model (tracking modes) or of the centre
    /// itself (detector only), each counted only above the noise of a still image. A person
    /// never holds perfectly still (a talking head wobbles back and forth, which a net
    /// displacement would cancel); a photo's shifts stay in the noise. Re-anchoring the box on
    /// a detection is not motion and does not count.
    float path = 0.f;
    Point2f lastCentre{};
    int verifiedSinceAnchor = 0;  ///< TrackVerifier's count since the last re-anchoring
    bool detectedThisFrame = false;
    /// The last flow step kept most of the corners on one rigid motion: the face is still
    /// there, whatever the cascade says (a hand or another head over part of it, a turned head).
    bool heldByCorners = false;
    /// Started by a tilted scan's hit: until shown, only the motion of its corners (`path`)
    /// shows it moves, not the motion mask. The turned regions offer the cascade more windows,
    /// hence more chance hits on still faces, and a changing light can fill a still face's box
    /// with foreground.
    bool tiltFound = false;
    /// How far its roll turned since it started, by flow steps that moved all of the face
    /// (movedAsOne), and (when confident) the image symmetry's roll at the start: a face turning
    /// in place shows it moves when the image agrees it turned (turnedInImage).
    float turn = 0.f;
    float imageRollAtStart = 0.f;
    bool haveImageRollAtStart = false;
    float rollChecked = 0.f;  ///< the tracked turn at the last such check
};

}  // namespace vision
