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

/// Knobs of RollByImageSymmetry; how the defaults were chosen is in roll_by_image_symmetry.cpp.
/// Sizes and positions are fractions of the patch side unless they say otherwise.
struct RollByImageSymmetryOptions {
    int patchSize = 40;     ///< side of the comparison patch in pixels
    float boxScale = 1.1f;  ///< the face square warped into it, x the detector box's side
    int supersample = 2;    ///< sampled at up to this x patchSize, then box-averaged down
    int blurPasses = 2;     ///< [1 2 1] smoothing passes before the comparison
    SymmetryFeature feature = SymmetryFeature::Gradient;
    float minDegrees = -35.f;               ///< coarse scan of the angles from here ...
    float maxDegrees = 35.f;                ///< ... to here
    float coarseStepDegrees = 2.5f;         ///< in these steps
    float refineToleranceDegrees = 0.05f;   ///< then golden section to this (0: no refinement)
    float maxAxisOffsetFraction = 0.15f;    ///< the mirror axis may sit this far off centre
    float regionHalfWidthFraction = 0.34f;  ///< compared columns either side of the axis
    float regionTop = 0.1f;                 ///< compared rows from here ...
    float regionBottom = 0.95f;             ///< ... to here
    float gradientSaturation = 8.f;         ///< gradients g -> g / (1 + |g| / this); 0: linear
    float axisWeightSigma = 0.f;         ///< Gaussian weight by distance from the axis; 0: uniform
    float rowCoherenceWeight = 0.5f;     ///< weight of the row cue (0: symmetry only)
    float rowCueBelowConfidence = 0.3f;  ///< the row cue joins below this confidence (<= 0 never)
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
    /// prepare's steps: the supersampled warp averaged down to patch_ (s x s blocks), one
    /// [1 2 1] pass each way over patch_, and the saturated gradient planes a_, b_ from it.
    void boxAverage(const ImageView& big, int s) noexcept;
    void blur121() noexcept;
    void gradients() noexcept;
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
    bool uniformWeights_ = true;  ///< every weight_ is 1 (axisWeightSigma 0)
    char lastError_[96] = {};
};

}  // namespace vision
