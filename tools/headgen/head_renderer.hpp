#pragma once
// Draws a textured CANDIDE head into a frame: each triangle that faces the camera, nearest last,
// sampled from the texture photograph by the affine map between its place there and its posed
// place (one bilinear remap over the head, so neighbouring triangles meet without seams). Which
// vertices the camera sees comes back with it, for the truth.

#include "head_projection.hpp"
#include "head_texture.hpp"

#include <opencv2/core.hpp>
#include <vector>

namespace headgen {

/// Blends the head into `frame` (CV_32FC3 BGR, 0..255). Returns, per mesh vertex, whether it is
/// seen: on a triangle facing the camera and not behind a nearer one. Vertices outside the frame
/// are not seen.
std::vector<bool> drawHead(cv::Mat& frame, const vision::CandideMesh& mesh,
                           const HeadTexture& texture, const ProjectedHead& head);

}  // namespace headgen
