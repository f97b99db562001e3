#pragma once
// Matching rules of the face evaluations (one place, unit tested, printed by the commands).
//
// detect (CMU/MIT): a detection is correct for a ground-truth face when its box contains both
// eyes and the mouth centre, and its side is within a factor of 2 of the face's scale, taken as
// kBoxPerEyeMouth x the eye-to-mouth distance (eye midpoint to mouth centre; the frontal-face
// cascades' boxes are about 2.2 of it). Detections and faces are paired one to one, closest
// centres first: a second detection of a face is a false positive.
//
// track: our box against the truth box by intersection over union (IoU >= 0.5), paired one to
// one, highest IoU first. A face partly out of view is optional (matched by its box or by its part
// in view; neither a true nor a false positive, and missing it is no false negative). With
// landmark truth (FGNet) the truth box is the landmarks' bounding box, as the product's targets say; our face
// box is a Viola-Jones square, which runs from the forehead to below the mouth while the landmarks
// run from the eyebrows to the chin (a correctly placed square scores only about 0.5 against
// them), so it is first turned into the box its face's landmarks would have
// (landmarkConventionBox), by factors measured on other faces than the ones scored.

#include "face_truth.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <span>
#include <string>
#include <vector>

namespace mirror_eval {

/// Box side of a frontal face per unit of eye-to-mouth distance.
inline constexpr float kBoxPerEyeMouth = 2.2f;
/// A detection's side may be this factor above or below the face's scale.
inline constexpr float kScaleTolerance = 2.f;

/// The bounding box of a face's 68 landmarks (iBUG 300-W scheme) in terms of the square box
/// haarcascade_frontalface_default gives on it: a square of kLandmarkBoxPerSide x its side, centred
/// kLandmarkBoxDrop x its side below the square's centre (towards the chin). Medians over dlib's
/// example faces (68 machine-placed landmarks each; our detector finds 40 of the 43), which
/// landmark_box_convention_test measures again. Not fitted to FGNet, whose own markup sits a
/// little narrower and lower (0.72 x 0.85 of the side, 0.175 below: IoU ~0.8 with this map).
inline constexpr float kLandmarkBoxPerSide = 0.805f;
inline constexpr float kLandmarkBoxDrop = 0.125f;

/// Axis-aligned box in float pixels (truth boxes are not integral).
struct BoxF {
    float x = 0.f;
    float y = 0.f;
    float width = 0.f;
    float height = 0.f;
};

BoxF toBoxF(const vision::Rect& r) noexcept;
/// The square of side `size` centred at `centre`.
BoxF squareAbout(vision::Point2f centre, float size) noexcept;
/// Bounding box of points (empty box for none).
BoxF boundingBox(std::span<const vision::Point2f> points) noexcept;
float iou(const BoxF& a, const BoxF& b) noexcept;
/// True when the box lies wholly inside a frame of this size (edges included).
bool wholeInFrame(const BoxF& box, vision::Size frame) noexcept;
/// The part of a box inside a frame of this size (an empty box when none is).
BoxF partInView(const BoxF& box, vision::Size frame) noexcept;
/// Inclusive of the box edges.
bool contains(const BoxF& box, vision::Point2f p) noexcept;

/// The landmarks' bounding box of the face in the detector-convention square of side `side` about
/// `centre`, rolled by `rollDegrees` (RollEstimate's sense: the drop follows the face's own down
/// direction; the box is not widened for the roll, which FGNet's faces hardly have).
BoxF landmarkConventionBox(vision::Point2f centre, float side, float rollDegrees) noexcept;
/// landmarkConventionBox in words, as mirror-eval track prints it.
std::string landmarkBoxText();

/// The detect rule above, for one detection and one face.
bool detectionMatchesFace(const vision::Rect& box, const LandmarkFace& face) noexcept;
/// The rule in one line, as the commands print it.
std::string detectRuleText();

/// A one-to-one pairing: pairs[i] = index of the truth matched to candidate i, or -1.
struct Pairing {
    std::vector<int> truthOfCandidate;
    std::vector<int> candidateOfTruth;
    int matches = 0;
};

/// Pairs detections with faces by the detect rule, closest centres (box centre to face centre)
/// first.
Pairing pairDetections(std::span<const vision::Rect> boxes,
                       std::span<const LandmarkFace* const> faces);

/// Pairs candidate boxes with truth boxes whose IoU reaches `minIou`, highest IoU first.
Pairing pairByIou(std::span<const BoxF> candidates, std::span<const BoxF> truths, float minIou);

}  // namespace mirror_eval
