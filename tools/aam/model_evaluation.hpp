#pragma once
// Leave-persons-out evaluation of a built model (§5; the protocol, beyond the text, which
// shows its model only on the persons it was built from): how well its shape and appearance modes
// reconstruct the faces of persons it never saw.
//  - shape: the held-out image's fitted CANDIDE vertices aligned to the mean (eq. 47 with the
//    model's weights), less their projection on the shape modes; rms per vertex, in the image's
//    pixels (the alignment's scale undone);
//  - appearance: the image warped to the mean shape, matched to the mean (eq. 59), less its
//    projection on the appearance modes; rms per pixel in the image's grey levels; and the same
//    reconstruction compared at the reference resolution (256 px, the text's) with the image
//    warped there, which also counts the detail the model's resolution cannot hold; and that
//    detail alone (the image warped at the model's resolution against its warp at 256 px).
// A held-out image of a person the model was built from is refused unless the evaluation is
// labelled person-specific.

#include "model_building.hpp"

#include <string>
#include <vector>

namespace aam {

inline constexpr int kReferenceResolution = 256;

struct HeldOutResult {
    std::string annotationPath;
    double shapeRmsPx = 0, shapeMeanOnlyRmsPx = 0;
    double appearanceRms = 0, appearanceMeanOnlyRms = 0;  ///< grey levels
    double appearanceRmsAtReference = 0;                  ///< grey levels, at 256 px
    double resolutionLoss =
        0;  ///< grey levels at 256 px: the image's own warp at the model's resolution, shown at 256
};

/// Throws std::invalid_argument (one line) naming the first of `heldOutPaths` whose person
/// (personOf) is one of `trainingPersons`: checked before a model is built, and again by
/// evaluateHeldOut.
void refuseSeenPersons(const std::vector<std::string>& trainingPersons,
                       const std::vector<std::string>& heldOutPaths);

/// Each image of `heldOut` reconstructed by `model`. Throws std::invalid_argument (one line)
/// naming the first image whose person the model saw, unless `personSpecific`.
std::vector<HeldOutResult> evaluateHeldOut(const BuiltModel& model,
                                           const std::vector<FittedImage>& heldOut,
                                           bool personSpecific);

}  // namespace aam
