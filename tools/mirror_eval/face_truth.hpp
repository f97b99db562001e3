#pragma once
// Ground truth of faces for `mirror-eval detect`, `roll` and `track`:
//  - CMU/MIT frontal sets (landmarks_test_set_a.txt / _b.txt): one face per line,
//      filename lx ly rx ry nx ny mlx mly mcx mcy mrx mry
//    (eye on the image's left, the other eye, nose, mouth left / centre / right; pixels);
//  - FGNet talking face: one .pts file per frame ("version: 1", "n_points: 68", "{", 68 "x y"
//    lines, "}"), the FGNet/Cootes 68-point markup (NOT the iBUG order: jaw 0-14, eyebrows
//    15-26, eyes 27-31 and 32-36 with their centres at 31 and 36, nose 37-47, outer lip 48-59,
//    inner lip 60-66, nose tip 67; read off franck_00000.pts);
//  - composed multi-face sequences (tools/facegen): one .txt per frame, one line per face
//      id cx cy size roll_deg moving
//    (moving 0: a static face of the background that must not be tracked).
// Blank lines and '#' comment lines are skipped in the line formats. Errors are one line,
// "NAME:LINE: what".

#include "vision/geometry.hpp"

#include <array>
#include <istream>
#include <string>
#include <vector>

namespace mirror_eval {

/// One face of a CMU/MIT landmark file.
struct LandmarkFace {
    std::string image;  ///< file name relative to the image folder
    int line = 0;       ///< line in the truth file (for reports)
    vision::Point2f leftEye{};
    vision::Point2f rightEye{};
    vision::Point2f nose{};
    vision::Point2f mouthLeft{};
    vision::Point2f mouthCentre{};
    vision::Point2f mouthRight{};

    vision::Point2f eyeMidpoint() const noexcept;
    /// Midpoint of the eye midpoint and the mouth centre: the face centre used by the crops.
    vision::Point2f centre() const noexcept;
    /// Eye midpoint to mouth centre, pixels.
    float eyeMouthDistance() const noexcept;
};

std::vector<LandmarkFace> parseLandmarkFaces(std::istream& in, const std::string& name);
/// "truth PATH: cannot open (missing or unreadable)"; "PATH: no faces" when empty.
std::vector<LandmarkFace> loadLandmarkFaces(const std::string& path);

/// The 68 points of a .pts file.
std::vector<vision::Point2f> parsePts(std::istream& in, const std::string& name);
std::vector<vision::Point2f> loadPts(const std::string& path);

/// One face of a composed frame's truth.
struct ComposedFace {
    int id = 0;
    vision::Point2f centre{};
    float size = 0.f;  ///< side of the face's square box, pixels
    float rollDegrees = 0.f;
    bool moving = true;
};

std::vector<ComposedFace> parseComposedTruth(std::istream& in, const std::string& name);
std::vector<ComposedFace> loadComposedTruth(const std::string& path);

/// Ground-truth roll (RollEstimate's sign: clockwise on screen positive) of the best orthogonal
/// least-squares line through the eye midpoint, the nose and the mouth centre, as an angle from
/// vertical. Falls back to the eye-to-mouth direction when the fit is degenerate (> 45 degrees
/// from it).
double axisRollDegrees(vision::Point2f eyeMidpoint, vision::Point2f nose,
                       vision::Point2f mouthCentre) noexcept;

/// Mean of points[first..last] (inclusive): a landmark group's centre (an eye, the outer lip).
vision::Point2f meanOf(const std::vector<vision::Point2f>& points, int first, int last);

/// The axis points of the FGNet 68-point markup: eye midpoint (of the eye centres 31 and 36),
/// nose tip (67), mouth centre (mean of the outer lip 48-59). Requires 68 points.
std::array<vision::Point2f, 3> axisPoints68(const std::vector<vision::Point2f>& points);

}  // namespace mirror_eval
