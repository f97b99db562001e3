#pragma once
// Convex hull by Andrew's monotone chain (step 4 of METHOD.md §2). The card tracker feeds it the
// leftmost and rightmost pixel of every row of the component: those contain all hull vertices.
// Sorting is in place (std::sort, no allocation); the output goes to a caller-provided array.

#include "vision/geometry.hpp"

namespace vision {

/// Hull of `points[0..n)` (sorted in place by x then y). Writes the hull vertices to `hull`
/// clockwise on screen (y down), without collinear points, starting at the smallest (x, y).
/// `hull` needs room for n + 1 points. Returns the vertex count (n when n < 3 after removing
/// duplicates).
int convexHull(Point2f* points, int n, Point2f* hull) noexcept;

/// Twice the signed area, positive for clockwise-on-screen (y down) vertex order.
double signedArea2(const Point2f* polygon, int n) noexcept;

}  // namespace vision
