#pragma once
// The AAM fit's piecewise affine warp (§5; dissertation 5.3.2, W(x; p) composed with N(x; q), and
// the speed work of 5.3.4). Private to vision/src.

#include "aam_fit_tables.hpp"
#include "vision/image.hpp"

#include <Eigen/Core>
#include <cstdint>

namespace vision::aam {

/// One triangle's map from the mean shape's frame to the image: image = linear * x + offset.
struct TriangleAffine {
    Eigen::Matrix2f linear = Eigen::Matrix2f::Identity();
    Eigen::Vector2f offset = Eigen::Vector2f::Zero();
};

/// Every triangle's affine map onto `shape` (2V image coordinates), in closed form from the
/// frame triangle's precomputed inverse edge matrix (5.3.4: no general solver per triangle).
void triangleAffines(const Tables& t, const float* shape, TriangleAffine* out) noexcept;

/// The image sampled at every span pixel's warped place into `warped` (grey levels), along each
/// run with its triangle's map stepped in q16 fixed point. Returns the number of pixels whose
/// place fell outside the image (sampled at the nearest border pixel).
int warpImage(const Tables& t, const TriangleAffine* affines, ConstImageView grey,
              AamSampling sampling, std::int16_t* warped) noexcept;

}  // namespace vision::aam
