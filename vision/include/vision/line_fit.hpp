#pragma once
// Robust line fit for the card's edges (step 5 of METHOD.md §2): RANSAC on pairs of points with a
// deterministic sampler (every pair when there are few points, a fixed-seed sequence otherwise, so
// a frame always gives the same answer), then an orthogonal least-squares refit on the inliers.

#include "vision/geometry.hpp"

#include <cstdint>

namespace vision {

/// The line nx * x + ny * y = c with a unit normal (nx, ny).
struct Line2f {
    float nx = 0.f;
    float ny = 0.f;
    float c = 0.f;
    float distance(Point2f p) const noexcept { return nx * p.x + ny * p.y - c; }
};

/// Orthogonal least squares over the points whose `use` entry is non-zero (all when use is null).
/// False with fewer than two distinct points.
bool fitLineLeastSquares(const Point2f* points, int n, const std::uint8_t* use,
                         Line2f& line) noexcept;

/// RANSAC line through `points`: the pair hypothesis with the most points within `inlierDistance`
/// (ties: the smaller summed residual), refitted by least squares on its inliers (twice, with the
/// inliers recounted). `inliers` (optional, n entries) receives 1 for inliers. Returns the inlier
/// count, 0 when no line was found.
int fitLineRansac(const Point2f* points, int n, float inlierDistance, int maxIterations,
                  Line2f& line, std::uint8_t* inliers = nullptr) noexcept;

/// Intersection of two lines; false when (nearly) parallel.
bool intersectLines(const Line2f& a, const Line2f& b, Point2f& out) noexcept;

/// The line through two points; false when they coincide.
bool lineThrough(Point2f a, Point2f b, Line2f& line) noexcept;

}  // namespace vision
