#pragma once
// Matching rules of the face evaluations (one place, unit tested, printed by the commands).
//
// detect (CMU/MIT): a detection is correct for a ground-truth face when its box contains both
// eyes and the mouth centre, and its side is within a factor of 2 of the face's scale, taken as
// kBoxPerEyeMouth x the eye-to-mouth distance (eye midpoint to mouth centre; the frontal-face
// cascades' boxes are about 2.2 of it). Detections and faces are paired one to one, closest
// centres first: a second detection of a face is a false positive.
//
// track: our square box against the truth box by intersection over union (IoU >= 0.5), paired
// one to one, highest IoU first. A face partly out of view is optional (matched by its box or by
// its part in view; neither a true nor a false positive, and missing it is no false negative). With
// landmark truth (FGNet) the truth box is the square a Viola-Jones detector gives on the face
// (detectorConventionBox), not the landmarks' bounding box: that one runs from the eyebrows to the
// chin while a detector's box runs from the forehead to below the mouth, so a correctly placed
// square scores only about 0.5-0.57 against it.

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

/// The detector's box in landmark terms, measured by `mirror-eval detect` on CMU/MIT set A
/// (medians over the correct detections of haarcascade_frontalface_default; set B: 2.57, -0.074):
/// side = kDetectorBoxPerEyeMouth x eye-mouth distance, centre moved from the face centre (midpoint
/// of eye midpoint and mouth centre) towards the eyes by kDetectorBoxRaise x side.
inline constexpr float kDetectorBoxPerEyeMouth = 2.5f;
inline constexpr float kDetectorBoxRaise = 0.09f;

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

/// The square a frontal-face detector gives on a face with these landmarks (see above); the
/// raise follows the face's eye -> mouth axis.
BoxF detectorConventionBox(vision::Point2f eyeMidpoint, vision::Point2f mouthCentre) noexcept;

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
