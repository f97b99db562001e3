#pragma once
// The inverse compositional update of the AAM's 2D shape (§5; dissertation 5.3.2, eqs. 68, 75-78,
// after Matthews & Baker): the shape from (q, p), and (q, p) composed with the inverse of an
// increment. Private to vision/src.

#include "aam_fit_tables.hpp"
#include "aam_warp.hpp"

#include <Eigen/Core>

namespace vision::aam {

/// N(x; q) = centre + linear (x - centre) + translation (eq. 75 about s0's centroid).
struct Similarity {
    Eigen::Matrix2f linear = Eigen::Matrix2f::Identity();
    Eigen::Vector2f translation = Eigen::Vector2f::Zero();

    float scale() const noexcept { return std::hypot(linear(0, 0), linear(1, 0)); }
};

Similarity similarityOf(const Tables& t, const float* q) noexcept;
void parametersOf(const Tables& t, const Similarity& n, float* q) noexcept;

/// N(s0 + sum p_i s_i; q) into `shape` (2V image points).
void shapeFromParameters(const Tables& t, const float* q, const float* p, float* shape) noexcept;

/// Each vertex's map: the mean of the maps of the triangles it is in (5.3.4's vertex -> triangles
/// table), as the composition applies them.
void vertexAffines(const Tables& t, const TriangleAffine* triangles,
                   TriangleAffine* vertices) noexcept;

/// q, p composed with the inverse of the increment (dq, dp): every vertex of s0 moved by
/// -(S* dq + S dp), mapped by its vertex map into the image, and that shape decomposed into q
/// (its projection on the similarity basis) and p (the modes' projection of N^-1 of it), p then
/// kept within the modes' limits. `shape` is scratch (2V) and ends as the new N(s0 + S p; q).
void composeInverse(const Tables& t, const TriangleAffine* vertexMaps, const float* dq,
                    const float* dp, float* q, float* p, float* shape) noexcept;

/// An image shape (2V points in `shape`) as q (its projection on the similarity basis) and p (the
/// modes' projection of N^-1 of it, within the modes' limits); `shape` ends as N(s0 + S p; q).
void decomposeShape(const Tables& t, float* q, float* p, float* shape) noexcept;

}  // namespace vision::aam
