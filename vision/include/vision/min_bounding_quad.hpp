#pragma once
// Minimum bounding quadrilateral of a convex polygon by the greedy method of Low & Ilie (step 4
// of METHOD.md §2): repeatedly remove the edge (v_i, v_i+1) whose replacement by the intersection
// of the lines (v_i-1, v_i) and (v_i+1, v_i+2) adds the least area, until four vertices remain.
// Removing an edge changes the scores of its two neighbours only, so only those are re-scored.

#include "vision/geometry.hpp"
#include "vision/image.hpp"

namespace vision {

/// Largest hull accepted; more vertices are rejected (a pixel component's hull has far fewer).
inline constexpr int kMaxQuadInputVertices = 1024;

/// `hull`: a convex polygon, clockwise on screen, without collinear vertices (convexHull()).
/// Writes the quad (clockwise on screen, starting at an arbitrary vertex). A triangle becomes a
/// quad by splitting its longest edge. False for fewer than 3 or more than the maximum vertices,
/// or when no edge can be removed (cannot happen for a proper convex polygon of > 4 vertices).
///
/// With a `frame` size, hull edges lying along the frame's border (both ends on the same border
/// line, within half a pixel) are removed first: they are where the image cut the object off, not
/// its outline (a card with a corner out of view then keeps that corner, extrapolated).
bool minBoundingQuad(const Point2f* hull, int n, Quad& quad, Size frame = {}) noexcept;

}  // namespace vision
