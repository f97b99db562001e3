#pragma once
// The card as a rectangle in 3D seen through a pinhole camera, beyond the dissertation (§2 step 5
// fits the quad in the image only; §2 future work, recovery from the shape model): what one quad
// fitted on all four edges tells about the camera's focal length and the card's aspect, and where
// an edge without image evidence lies when the other three are fitted. Private to vision/src.
//
// A rectangle's two pairs of opposite sides meet in two vanishing points v1, v2 whose rays through
// the camera are perpendicular: with image coordinates taken from the principal point,
// v1.x v2.x + v1.y v2.y + f^2 v1.w v2.w = 0 (the standard rectangle constraint). With the focal
// length known, the quad's plane, and so its sides' lengths in 3D up to one scale, follow.

#include "vision/geometry.hpp"
#include "vision/line_fit.hpp"

namespace vision {

/// A pinhole camera: focal length and principal point in pixels.
struct PinholeView {
    double focal = 0.0;
    Point2f principal{};
};

/// One quad's constraint a f^2 = b on the focal length f (in units of `scale` pixels), from the
/// perpendicular vanishing directions of its two pairs of sides. Each vanishing point is scaled to
/// unit length, so a and b are bounded and a is near 0 when a pair of sides is near parallel in
/// the image (that quad tells nothing of f).
struct FocalConstraint {
    double a = 0.0;
    double b = 0.0;
};
FocalConstraint rectangleFocalConstraint(const Quad& q, Point2f principal, double scale) noexcept;

/// |cos| of the angle in 3D between the directions of the quad's two pairs of sides (their
/// vanishing points' rays), seen through `view`: 0 for the image of a rectangle, 1 when
/// degenerate.
double rectangleSkew(const Quad& q, const PinholeView& view) noexcept;
/// The length in 3D of the quad's edges 0 and 2 over that of edges 1 and 3 (each pair averaged),
/// the quad taken as a rectangle seen through `view`. 0 when degenerate.
double rectangleSideRatio(const Quad& q, const PinholeView& view) noexcept;

/// Where the diagonals of `q` meet: the image of the rectangle's centre. false when degenerate.
bool diagonalsMeet(const Quad& q, Point2f& out) noexcept;

/// With edge k's line unknown and the other three of `lines` fitted (edge i runs from corner i to
/// corner i + 1), the corners p0 (corner k) and p1 (corner k + 1) that make the quad the image
/// through `view` of a rectangle whose neighbour edges (k + 1, k + 3) are `sideRatio` times as long
/// in 3D as the opposite edge k + 2. The neighbours' lines fix their vanishing direction d1, the
/// opposite edge's line and the right angle fix its direction d2 = m x d1 (m: the normal of the
/// plane through the camera and that line), so the card's plane and its corners k + 2, k + 3 in
/// 3D follow up to one scale; the hidden corners are those two moved by sideRatio |k+2 k+3| along
/// d1, on the side of edge k + 2 where `inside` lies. False when degenerate or behind the camera.
bool placeHiddenRectangleEdge(const Line2f lines[4], int k, const PinholeView& view,
                              double sideRatio, Point2f inside, Point2f& p0, Point2f& p1) noexcept;

}  // namespace vision
