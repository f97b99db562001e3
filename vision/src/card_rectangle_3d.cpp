#include "card_rectangle_3d.hpp"

#include <cmath>

namespace vision {

namespace {

/// A homogeneous point, line or direction in 3D.
struct Vec3 {
    double x = 0.0, y = 0.0, z = 0.0;
};

Vec3 cross(Vec3 a, Vec3 b) noexcept
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec3 a, Vec3 b) noexcept
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3 scaled(Vec3 a, double s) noexcept
{
    return {a.x * s, a.y * s, a.z * s};
}
Vec3 plus(Vec3 a, Vec3 b) noexcept
{
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
double length(Vec3 a) noexcept
{
    return std::sqrt(dot(a, a));
}
double distance(Vec3 a, Vec3 b) noexcept
{
    return length(plus(a, scaled(b, -1.0)));
}

/// A pixel as a homogeneous point measured from the principal point, in units of `scale`.
Vec3 centred(Point2f p, Point2f principal, double scale) noexcept
{
    return {(static_cast<double>(p.x) - principal.x) / scale,
            (static_cast<double>(p.y) - principal.y) / scale, 1.0};
}

/// A line n.p = c as a homogeneous line in pixels measured from the principal point.
Vec3 centred(const Line2f& l, Point2f principal) noexcept
{
    return {
        l.nx, l.ny,
        static_cast<double>(l.nx) * principal.x + static_cast<double>(l.ny) * principal.y - l.c};
}

/// The direction in 3D of the ray through a homogeneous image point (x, y, w), centred, in pixels.
Vec3 ray(Vec3 v, double focal) noexcept
{
    return {v.x, v.y, focal * v.z};
}

/// Where a point in 3D projects, in pixels.
Point2f project(Vec3 p, const PinholeView& view) noexcept
{
    return {static_cast<float>(view.focal * p.x / p.z + view.principal.x),
            static_cast<float>(view.focal * p.y / p.z + view.principal.y)};
}

/// The quad's sides as homogeneous lines, in pixels from the principal point.
void sideLines(const Quad& q, Point2f principal, Vec3 lines[4]) noexcept
{
    for (int i = 0; i < 4; ++i)
        lines[i] = cross(centred(q[i], principal, 1.0), centred(q[(i + 1) % 4], principal, 1.0));
}

}  // namespace

FocalConstraint rectangleFocalConstraint(const Quad& q, Point2f principal, double scale) noexcept
{
    Vec3 lines[4];
    for (int i = 0; i < 4; ++i)
        lines[i] =
            cross(centred(q[i], principal, scale), centred(q[(i + 1) % 4], principal, scale));
    const Vec3 v1 = cross(lines[0], lines[2]), v2 = cross(lines[1], lines[3]);
    const double n = length(v1) * length(v2);
    if (!(n > 0.0))
        return {};
    return {v1.z * v2.z / n, -(v1.x * v2.x + v1.y * v2.y) / n};
}

double rectangleSkew(const Quad& q, const PinholeView& view) noexcept
{
    Vec3 lines[4];
    sideLines(q, view.principal, lines);
    const Vec3 d1 = ray(cross(lines[0], lines[2]), view.focal);
    const Vec3 d2 = ray(cross(lines[1], lines[3]), view.focal);
    const double n = length(d1) * length(d2);
    return n > 0.0 ? std::fabs(dot(d1, d2)) / n : 1.0;
}

double rectangleSideRatio(const Quad& q, const PinholeView& view) noexcept
{
    // The quad's plane: its normal is across the two vanishing directions; each corner's point
    // in 3D is its ray cut by that plane (through corner 0's ray at depth 1: one scale).
    Vec3 rays[4], lines[4];
    for (int i = 0; i < 4; ++i)
        rays[i] = ray(centred(q[i], view.principal, 1.0), view.focal);
    sideLines(q, view.principal, lines);
    const Vec3 normal = cross(ray(cross(lines[0], lines[2]), view.focal),
                              ray(cross(lines[1], lines[3]), view.focal));
    Vec3 corners[4];
    const double depth = dot(normal, rays[0]);
    for (int i = 0; i < 4; ++i) {
        const double along = dot(normal, rays[i]);
        if (!(std::fabs(along) > 1e-12 * length(normal) * length(rays[i])))
            return 0.0;
        corners[i] = scaled(rays[i], depth / along);
    }
    const double across = distance(corners[0], corners[3]) + distance(corners[1], corners[2]);
    if (!(across > 0.0))
        return 0.0;
    return (distance(corners[0], corners[1]) + distance(corners[3], corners[2])) / across;
}

bool diagonalsMeet(const Quad& q, Point2f& out) noexcept
{
    const Point2f origin{};
    const Vec3 meet = cross(cross(centred(q[0], origin, 1.0), centred(q[2], origin, 1.0)),
                            cross(centred(q[1], origin, 1.0), centred(q[3], origin, 1.0)));
    if (!(std::fabs(meet.z) > 1e-9))
        return false;
    out = {static_cast<float>(meet.x / meet.z), static_cast<float>(meet.y / meet.z)};
    return true;
}

bool placeHiddenRectangleEdge(const Line2f lines[4], int k, const PinholeView& view,
                              double sideRatio, Point2f inside, Point2f& p0, Point2f& p1) noexcept
{
    const double f = view.focal;
    if (!(f > 0.0) || !(sideRatio > 0.0))
        return false;
    const Vec3 next = centred(lines[(k + 1) % 4], view.principal);
    const Vec3 opposite = centred(lines[(k + 2) % 4], view.principal);
    const Vec3 previous = centred(lines[(k + 3) % 4], view.principal);
    // The measured corners k + 2 and k + 3, in the image.
    const Vec3 a = cross(next, opposite), b = cross(opposite, previous);
    if (!(std::fabs(a.z) > 1e-9) || !(std::fabs(b.z) > 1e-9))
        return false;
    // The neighbours' direction in 3D, the opposite edge's (in the plane through the camera and
    // its line, at a right angle to the neighbours), and the card's plane across both.
    const Vec3 d1 = ray(cross(next, previous), f);
    const Vec3 d2 = cross({opposite.x, opposite.y, opposite.z / f}, d1);
    const Vec3 normal = cross(d1, d2);
    const double d1Length = length(d1);
    if (!(d1Length > 0.0) || !(length(normal) > 0.0))
        return false;
    // Corners k + 2 and k + 3 in 3D: the first at depth f, the second where its ray cuts the plane.
    const Vec3 ca = ray(scaled(a, 1.0 / a.z), f);
    const Vec3 rb = ray(scaled(b, 1.0 / b.z), f);
    const double along = dot(normal, rb);
    if (!(std::fabs(along) > 1e-12 * length(normal) * length(rb)))
        return false;
    const Vec3 cb = scaled(rb, dot(normal, ca) / along);
    if (!(cb.z > 0.0))
        return false;
    // The hidden corners: both moved along d1 by the neighbours' length, toward `inside`.
    const double side = opposite.x * (static_cast<double>(inside.x) - view.principal.x) +
                        opposite.y * (static_cast<double>(inside.y) - view.principal.y) +
                        opposite.z;
    const Vec3 step = scaled(d1, sideRatio * distance(ca, cb) / d1Length);
    for (const double sign : {1.0, -1.0}) {
        const Vec3 c1 = plus(ca, scaled(step, sign)), c0 = plus(cb, scaled(step, sign));
        if (!(c1.z > 0.0) || !(c0.z > 0.0))
            continue;
        const Point2f q1 = project(c1, view);
        const double at = opposite.x * (static_cast<double>(q1.x) - view.principal.x) +
                          opposite.y * (static_cast<double>(q1.y) - view.principal.y) + opposite.z;
        if (at * side <= 0.0)
            continue;
        p1 = q1;
        p0 = project(c0, view);
        return true;
    }
    return false;
}

}  // namespace vision
