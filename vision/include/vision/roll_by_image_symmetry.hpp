#pragma once
// Initial roll of a detected face from the dense bilateral symmetry of its IMAGE (beyond the
// dissertation: its 5.2 future work). The corner-point symmetry of METHOD.md §4 fails on small,
// noisy faces whose corner sets are not symmetric even when the face is; every pixel of the face
// takes part here instead. For each candidate angle the face square is warped upright by it into
// a small patch (warpUpright), and the patch is compared with its own mirror image about a
// vertical axis that may sit a little off the patch centre (detector boxes are not centred on the
// face's axis), and its features (brows, eyes, nostrils, mouth) should lie along the rows. The
// angle that best does both is the roll.

#include "vision/geometry.hpp"
#include "vision/image.hpp"
#include "vision/roll_estimator.hpp"

#include <vector>

namespace vision {

/// What the mirror comparison is made of.
enum class SymmetryFeature {
    /// Intensity gradients: a mirrored pixel pair should have opposite horizontal and equal
    /// vertical derivatives. Blind to a brightness offset and, through the normalisation, to
    /// contrast; one-sided lighting hurts it less than it hurts intensities.
    Gradient,
    /// Intensities minus the region mean, normalised by their mean absolute deviation.
    Intensity,
};

/// Knobs of RollByImageSymmetry. Developed on the IMM faces rotated synthetically
/// (tests/peer/roll_image_symmetry_peer_test.cpp: about 1.2 degrees mean error, every face within
/// 5). IMM does not tell the last knobs apart, so patch 40 (rather than 32), axis offset 0.15
/// (the detector's boxes sit ~0.1 of their side off the face centre) and gradient saturation 8
/// were picked on `mirror-eval roll` with seeds 7 and 11, and blurPasses 2 and
/// rowCoherenceWeight 0.5 with seeds 7, 11 and 42 (checked on 3, 99, 123, 500), never on the
/// reported 2006/2007.
struct RollByImageSymmetryOptions {
    /// Side of the comparison patch in pixels (the face square is resampled to it).
    int patchSize = 40;
    /// The face square warped into the patch, as a multiple of the detector's box side.
    float boxScale = 1.1f;
    /// The square is sampled at up to supersample x patchSize (no finer than its own pixels) and
    /// box-averaged down, so large faces do not alias into the small patch.
    int supersample = 2;
    /// Separable [1 2 1] smoothing passes over the patch before the comparison. 2 rather than 1
    /// (with the row cue): CMU/MIT set A 3.55 -> 3.27 deg mean error over seeds 7, 11, 42, 3,
    /// 99, 123, 500 (B 3.49 -> 3.50); IMM unchanged; FGNet tracking roll +0.1 deg.
    int blurPasses = 2;
    SymmetryFeature feature = SymmetryFeature::Gradient;
    /// Candidate angles: a coarse scan of [minDegrees, maxDegrees] in coarseStepDegrees, then a
    /// golden-section search around the best coarse angle down to refineToleranceDegrees (0: no
    /// refinement).
    float minDegrees = -35.f;
    float maxDegrees = 35.f;
    float coarseStepDegrees = 2.5f;
    float refineToleranceDegrees = 0.05f;
    /// The mirror axis may sit up to this fraction of the patch side left or right of the patch
    /// centre, searched in half-pixel steps, then continuously (golden section).
    float maxAxisOffsetFraction = 0.15f;
    /// Compared region: columns within this fraction of the patch side either side of the axis
    /// (the face, not the background at the corners), rows from regionTop to regionBottom (as
    /// fractions of the patch side).
    float regionHalfWidthFraction = 0.34f;
    float regionTop = 0.1f;
    float regionBottom = 0.95f;
    /// Gradient feature only: each gradient component g becomes g / (1 + |g| / saturation)
    /// (grey levels per pixel), so one strong edge (hair against a wall, a collar) cannot outweigh
    /// the eyes, nose and mouth. 0: linear.
    float gradientSaturation = 8.f;
    /// Pairs are weighted by a Gaussian of their distance from the axis with this sigma (fraction
    /// of the patch side): the middle of the face (nose, mouth, inner eyes) counts more than its
    /// outline. 0: uniform (with saturation on, 0.2 made CMU/MIT set A worse: 3.7 -> 4.3 deg).
    float axisWeightSigma = 0.f;
    /// Gradient feature only: weight of the second cue, the row coherence of the vertical
    /// derivatives (1 when, along every row of the compared region, they share their sign: the
    /// brows, eyes, nostrils and mouth lie along the rows). Each angle then scores asymmetry +
    /// weight x (1 - coherence). Symmetry alone drifts on faces whose halves differ (a turned
    /// head, one-sided light, hair); the rows do not care about left and right. 0: symmetry
    /// only. Picked on CMU/MIT seeds 7, 11, 42 among 0.3-1.0 (0.4-0.6 alike; 1.0 lets the rows
    /// win on their own).
    float rowCoherenceWeight = 0.5f;
    /// The row cue joins only when the symmetry alone is less sure than this (its confidence:
    /// 1 - best / median asymmetry of the coarse scan). On a clear face it would only add its
    /// own bias, the eye line not being square to the eye-mouth axis on every face: always on,
    /// the FGNet tracking roll error went 2.45 -> 3.08 deg; gated at 0.3, 2.57, while CMU/MIT
    /// kept its gain (0.2 lost some on set A, 0.25-0.4 alike). <= 0: never; > 1: always.
    float rowCueBelowConfidence = 0.3f;
};

/// Roll of a face by image symmetry. Construct once at start-up (the scratch patches are sized
/// there; invalid options throw std::invalid_argument with one line); estimate() does not
/// allocate or throw. Not thread-safe (one scratch per instance).
///
/// Sign convention as RollEstimate: positive roll is clockwise on screen (y down), so
/// warpUpright(gray, centre, roll, side, patch) shows the face upright.
class RollByImageSymmetry {
public:
    explicit RollByImageSymmetry(const RollByImageSymmetryOptions& options = {});

    /// Roll of the face in the detector box centred on `centre` (continuous coordinates, as
    /// warpUpright: a box's x + width / 2) with side `boxSize` pixels of `gray` (Gray8). In the
    /// result, rollDegrees is the roll, confidence 0..1 how much better the best angle scores
    /// than the median one, symmetryDistance the best score (the normalised asymmetry, 0 = a
    /// perfect mirror image, ~1 = unrelated halves, plus rowCoherenceWeight x (1 - row
    /// coherence) when the row cue joined) and points the number of pixel pairs compared. Bad
    /// input (wrong format, empty image, non-finite or non-positive size, square far outside the
    /// image) gives roll 0, confidence 0 and lastError() says why.
    RollEstimate estimate(const ConstImageView& gray, Point2f centre, float boxSize) noexcept;

    /// The score at one angle (normalised asymmetry at the best axis offset plus the weighted
    /// row term, whatever the symmetry's confidence), or a negative value on bad input. For
    /// tests and diagnostics.
    float asymmetry(const ConstImageView& gray, Point2f centre, float boxSize,
                    float rollDegrees) noexcept;

    const RollByImageSymmetryOptions& options() const noexcept { return options_; }
    /// Why the last estimate() gave confidence 0 on bad input; "" otherwise.
    const char* lastError() const noexcept { return lastError_; }

private:
    /// Warps and prepares the feature planes for one angle; false on bad input.
    bool prepare(const ConstImageView& gray, Point2f centre, float boxSize,
                 float rollDegrees) noexcept;
    /// Best asymmetry over the axis offsets of the prepared planes: half-pixel steps, and when
    /// `continuous` a golden-section search between the best step's neighbours.
    float bestOverOffsets(bool continuous) noexcept;
    /// Normalised asymmetry of the prepared planes about the axis at a2 / 2 (patch pixels).
    float asymmetryAbout(float a2) const noexcept;
    /// Gradient feature: how much the prepared vertical derivatives add up along the rows of the
    /// compared region (0..1).
    float rowCoherence() const noexcept;
    float scoreAngle(const ConstImageView& gray, Point2f centre, float boxSize, float rollDegrees,
                     bool continuous) noexcept;

    RollByImageSymmetryOptions options_;
    float rowWeight_ = 0.f;      ///< row-cue weight of the current estimate
    float lastAsymmetry_ = 0.f;  ///< scoreAngle's last terms
    float lastRowTerm_ = 0.f;
    int n_ = 0;         ///< patch side
    int maxShift_ = 0;  ///< largest |2 x axis offset| in pixels (half-pixel steps)
    ImageBuffer big_;   ///< supersampled warp
    std::vector<float> patch_, tmp_, a_, b_;  ///< patch, blur scratch, feature planes
    std::vector<float> weight_;  ///< pair weight by distance from the axis (index: |x - x'|)
    char lastError_[96] = {};
};

}  // namespace vision
