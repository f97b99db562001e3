#pragma once
// Synthetic faces for the AAM fit's tests and benchmark: the model's own appearance (its mean
// plus a few modes) warped onto the CANDIDE head at a known pose and expression, over a textured
// background, drawn back to front so the far side of a turned head is hidden. Independent of the
// fitter's code: the projection is written again here from its documented convention.

#include "vision/aam_fitter.hpp"
#include "vision/aam_model.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <vector>

namespace aam_test {

struct SyntheticFaceSpec {
    vision::AamHead head;                  ///< the true pose and expression (sigma: the shape)
    std::vector<float> appearanceWeights;  ///< per appearance mode, in standard deviations
    float gain = 45.f, bias = 120.f;       ///< grey = gain * appearance + bias
    /// Light from the image's right (as IMM's photographs are lit): the head's grey is scaled by
    /// 1 - lightFromRight * (1 - u) / 2, u from -1 at the head's left edge to 1 at its right: its
    /// image-left side in shadow (0: even light).
    float lightFromRight = 0.f;
    std::uint32_t backgroundSeed = 1;
};

struct SyntheticFace {
    vision::ImageBuffer image;              ///< Gray8
    std::vector<vision::Point2f> vertices;  ///< the true 2D shape (the head's projection)

    /// The true shape's bounding box as a fit's start.
    vision::AamStart box(float rollDegrees) const;
};

/// The face of `spec` rendered into a width x height grey image.
SyntheticFace renderSyntheticFace(const vision::AamModel& model, const SyntheticFaceSpec& spec,
                                  int width, int height);

/// The model's appearance warped onto an explicit 2D shape (no depth: nothing hidden).
SyntheticFace renderShape(const vision::AamModel& model, const SyntheticFaceSpec& spec,
                          const std::vector<vision::Point2f>& shape, int width, int height);

/// The shape and animation units that put the frontal CANDIDE head closest to the model's mean
/// shape (the alternating linear fits of the builder's 5.3.1): a synthetic face made with them is a
/// face the model can represent, as a real person near the training persons' average is.
vision::AamHead meanShapeHead(const vision::AamModel& model);

/// CANDIDE units across the model's mesh (x extent of its base shape).
float meshWidthUnits(const vision::AamModel& model);

/// Root mean square distance between two shapes' vertices.
float rmsDistance(const std::vector<vision::Point2f>& a, const vision::AamFitResult& fit);

}  // namespace aam_test
