#pragma once
// The piecewise affine warp of §5 (dissertation 5.3.1, "an affine warp to map pixels in each
// triangle from the old image into the new image"): an image whose face has shape s sampled at
// every pixel of the appearance frame. Offline, so bilinear sampling; the runtime fit samples
// nearest-neighbour (5.3.4) and will show its convergence against this.

#include "appearance_frame.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace aam {

/// `grey` (8-bit) sampled at each frame pixel's place in `shape` (the face's vertices in `grey`,
/// pixels); a place outside the image takes the nearest border pixel. One value per frame pixel.
Eigen::VectorXd warpToFrame(const cv::Mat& grey, const Shape2d& shape,
                            const vision::CandideMesh& face, const AppearanceFrame& frame);

/// `values` (one per frame pixel) as a frame-sized CV_64F image, 0 outside the face.
cv::Mat frameImage(const AppearanceFrame& frame, const Eigen::VectorXd& values);

/// `values` of frame `from` resampled at the pixels of `to` (the same mean shape at another
/// resolution), bilinearly over the pixels of `from` only: what a model of `from`'s resolution
/// can show at `to`'s. NaN where no pixel of `from` lies within one pixel (the outline's edge).
Eigen::VectorXd resampledTo(const AppearanceFrame& from, const Eigen::VectorXd& values,
                            const AppearanceFrame& to);

}  // namespace aam
