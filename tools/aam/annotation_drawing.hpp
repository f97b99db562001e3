#pragma once
// Pictures for checking the annotation tables and the CANDIDE fits by eye: an annotated image
// with its points numbered, the CANDIDE vertices they map to, and a fitted mesh.

#include "vision/candide_mesh.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace aam {

/// The part of `image` around `points` (a tenth of their extent as margin) enlarged to `height`
/// pixels, and `points` moved into it: the picture the labels are legible in.
cv::Mat closeUp(const cv::Mat& image, std::vector<std::vector<Eigen::Vector2d>*> points,
                int height = 900);

/// Each point as a dot with its number beside it (yellow), and when `labels` is given its text
/// instead (e.g. "c31": the CANDIDE vertex the point maps to).
void drawNumberedPoints(cv::Mat& image, const std::vector<Eigen::Vector2d>& points,
                        const std::vector<std::string>& labels = {});

/// A mesh projected into the image (`projected`: one 2D point per mesh vertex), its triangles in
/// green, vertices in red.
void drawMesh(cv::Mat& image, const vision::CandideMesh& mesh,
              const std::vector<Eigen::Vector2d>& projected);

}  // namespace aam
