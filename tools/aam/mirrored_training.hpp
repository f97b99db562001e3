#pragma once
// Mirrored training images for the appearance model (§5, dissertation 5.3.1, where the text is
// silent; `aam-build model --mirrored-appearance`). The training photographs of one studio share
// its light: IMM's come from the image's right, and a mean appearance of them alone is darker on
// its left half by about two thirds of its standard deviation. Each training image also used
// mirrored (the photograph flipped, its mesh flipped with every vertex taking its mirror partner's
// place) makes the mean appearance symmetric and the light from either side one of the modes,
// which the fit projects out. Not the default: docs/aam-model-format.md has what it gained and
// lost.

#include "shape_synthesis.hpp"
#include "vision/candide_mesh.hpp"

#include <opencv2/core.hpp>
#include <vector>

namespace aam {

/// Each vertex's mirror partner: of the vertices at (-x, y, z), the one the units move most nearly
/// as its mirror image (so the inner lips, which share a place at rest, pair upper with upper).
/// Throws std::invalid_argument (one line) when a vertex has none: the mesh is not symmetric.
std::vector<int> mirrorPartners(const vision::CandideMesh& face);

/// `shape` (the vertices in an image `width` pixels wide) as it lies in the mirrored image.
Shape2d mirroredShape(const Shape2d& shape, const std::vector<int>& partners, int width);

/// `grey` flipped left to right.
cv::Mat mirroredImage(const cv::Mat& grey);

}  // namespace aam
