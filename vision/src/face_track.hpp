#pragma once
// Track: one face FaceTracker follows (what it reports, its corners and its motion record), and
// the constants the tracker's parts share. Private to vision/src.
#include "static_face_rule.hpp"
#include "vision/face_tracker.hpp"
#include "vision/geometry.hpp"

#include <array>

namespace vision {

constexpr int kMaxPoints = 64;  ///< corners kept per track
constexpr int kMaxTracks = 32;  ///< hard cap on options.maxFaces
/// Image-symmetry roll estimates less sure than this are not used (RollEstimate::confidence).
constexpr float kMinImageRollConfidence = 0.15f;

struct Track {
    TrackedFace face;
    std::array<Point2f, kMaxPoints> points{};
    int pointCount = 0;
    int verifiedSinceAnchor = 0;  ///< TrackVerifier's count since the last re-anchoring
    bool detectedThisFrame = false;
    bool seen = false;  ///< detected or verified this frame (step 4, for step 5)
    /// The last flow step kept most of the corners on one rigid motion: the face is still
    /// there, whatever the cascade says (a hand or another head over part of it, a turned head).
    bool heldByCorners = false;
    float seenSize = 0.f;  ///< the box's size when the face was last detected or verified
    /// The box's size when a detection or a grouped scan last placed it (its corners' fit moves
    /// it in between; TrackVerifier::recentre).
    float anchorSize = 0.f;
    /// Started with its box reaching beyond the image: found by the part of it in view, which
    /// the cascade boxes off the face's centre (TrackVerifier::recentre).
    bool cameInAtEdge = false;
    /// face.age when the image's symmetry last measured the roll (TrackVerifier::correctRoll).
    int rollMeasuredAge = 0;
    FaceMotion motion;  ///< StaticFaceRule's record of how the face moved
};

}  // namespace vision
