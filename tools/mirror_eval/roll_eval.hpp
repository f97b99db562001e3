#pragma once
// mirror-eval roll: initial roll by dense image symmetry (RollByImageSymmetry, the primary result)
// and by point symmetry (METHOD.md §4, the dissertation's method) on rotated CMU/MIT faces, the
// protocol of the product's roll targets: for each ground-truth face a square crop of 3x its eye-to-mouth distance
// about the face centre (border replicated) is rotated about that centre by a seeded uniform
// angle in [-rotate, rotate]; the landmarks go with it. Our FaceDetector runs on the crop; for the
// detection holding the (rotated) eye midpoint and mouth centre, Shi-Tomasi corners in its box
// (CornerDetector, min distance a fraction of the box side) give the roll by corner symmetry, and
// the box's image its roll by image symmetry. Truth: the
// best line through eye midpoint, nose and mouth centre. Also the line-fit baseline, and an
// estimate of the truth's own noise (three-cornered hat, with CascadeResponseRoll as a second
// image measurement independent of symmetry): what an exact estimator could score against it.

#include "vision/roll_by_image_symmetry.hpp"

#include <cstdio>
#include <string>

namespace mirror_eval {

struct RollEvalOptions {
    std::string images;
    std::string truth;
    std::string cascade;  ///< empty: detect_eval.hpp's default
    double rotateDegrees = 30.0;
    unsigned seed = 2006;
    int corners = 60;                      ///< most corners per face
    float cornerDistanceFraction = 0.05f;  ///< min distance between corners / box side
    /// Crops smaller than this are resampled up to it (the rotation and scale in one warp), so
    /// small faces give the detector and the corner detector enough pixels; 0: native size.
    int minCropSide = 150;
    /// Corners are found on the crop smoothed by a Gaussian of this sigma x the box side (0: none).
    float cornerBlurFraction = 0.02f;
    /// RollByImageSymmetry's options (the primary method); defaults are the class's.
    int imagePatch = vision::RollByImageSymmetryOptions{}.patchSize;
    float imageBoxScale = vision::RollByImageSymmetryOptions{}.boxScale;
    float imageAxisOffset = vision::RollByImageSymmetryOptions{}.maxAxisOffsetFraction;
    float imageHalfWidth = vision::RollByImageSymmetryOptions{}.regionHalfWidthFraction;
    float imageTop = vision::RollByImageSymmetryOptions{}.regionTop;
    float imageBottom = vision::RollByImageSymmetryOptions{}.regionBottom;
    int imageBlur = vision::RollByImageSymmetryOptions{}.blurPasses;
    float imageStep = vision::RollByImageSymmetryOptions{}.coarseStepDegrees;
    bool imageIntensity = false;
    float imageSaturation = vision::RollByImageSymmetryOptions{}.gradientSaturation;
    float imageAxisSigma = vision::RollByImageSymmetryOptions{}.axisWeightSigma;
    int maxFaces = 0;  ///< 0: every face of the truth file; else the first N (tests)
    bool perFace = false;
};

/// Runs, prints the table and the final line `roll: faces=.. mean_err_deg=.. within1=..
/// within5=..` to `out`. Returns the exit code; errors go to `err` as one line.
int runRollEval(const RollEvalOptions& options, std::FILE* out, std::FILE* err);

}  // namespace mirror_eval
