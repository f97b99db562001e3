#pragma once
// The whole of §5's model building (dissertation 5.3.1), its steps in the text's order: each
// training image's CANDIDE fit, the synthesized shapes, their alignment and shape modes, the
// appearance frame of the mean shape, every training image warped into it, the appearance modes;
// and the model as the runtime's file holds it (vision::AamModel).
//
// The training images are the ones whose marks fit CANDIDE (one frontal image per person in the
// text); each contributes its synthesized shapes to the shape model and its own warped image to
// the appearance model.

#include "annotation_schemes.hpp"
#include "appearance_frame.hpp"
#include "appearance_modes.hpp"
#include "candide_fit.hpp"
#include "shape_alignment.hpp"
#include "shape_modes.hpp"
#include "vision/aam_model.hpp"
#include "vision/candide_mesh.hpp"

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace aam {

struct ModelOptions {
    int resolution = 96;          ///< the appearance frame's width (docs/aam-model-format.md: why)
    double shapeVariance = 0.98;  ///< shape_modes.hpp
    double appearanceVariance = 0.95;  ///< docs/aam-model-format.md: why
    /// Each training image also mirrored in the appearance model (mirrored_training.hpp; off:
    /// docs/aam-model-format.md).
    bool mirroredAppearance = false;
    SynthesisOptions synthesis;
};

/// One annotated image fitted: its file, its person, the fit and every vertex projected.
struct FittedImage {
    std::string annotationPath, imagePath, person;
    CandideFit fit;
    Shape2d shape;
    cv::Mat grey;
};

/// Reads the annotation and its image and fits `face` to the marks (5.3.1, eq. 44).
FittedImage fitAnnotatedImage(const vision::CandideMesh& face, const AnnotationScheme& scheme,
                              const std::string& path);

/// Every fit's synthesized shapes (each its own seed from `synthesis.seed` on), aligned in the
/// frame of the first fit's frontal neutral shape (shape_alignment.hpp: so the mean is upright).
AlignedShapes alignedTrainingShapes(const vision::CandideMesh& face,
                                    const std::vector<CandideFit>& fits,
                                    SynthesisOptions synthesis);

struct BuiltModel {
    vision::CandideMesh face;
    std::vector<std::string> persons;  ///< whom it was built from, for the leave-persons-out check
    AlignedShapes aligned;             ///< its weights align new shapes as the training ones were
    ShapeModes shape;
    AppearanceFrame frame;
    AppearanceModes appearance;
};

/// The model of the training images (at least two); one-line std::exceptions for bad input.
BuiltModel buildModel(const vision::CandideMesh& face, const std::vector<FittedImage>& training,
                      const ModelOptions& options);

/// The model as the file holds it: the mean shape and modes in frame pixels.
vision::AamModel modelForFile(const BuiltModel& built);

}  // namespace aam
