#include "vision/min_bounding_quad.hpp"

#include "vision/convex_hull.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using vision::Point2f;
using vision::Quad;

namespace {

double cross(Point2f o, Point2f a, Point2f b)
{
    return (double(a.x) - o.x) * (double(b.y) - o.y) - (double(a.y) - o.y) * (double(b.x) - o.x);
}

bool contains(const Quad& q, Point2f p, double tol)
{
    for (int i = 0; i < 4; ++i) {
        const Point2f a = q[i], b = q[(i + 1) % 4];
        const double len = std::hypot(b.x - a.x, b.y - a.y);
        if (cross(a, b, p) / len < -tol)
            return false;
    }
    return true;
}

/// Hull of the pixel centres of a filled polygon given by its corners (rasterised by a point-in-
/// polygon test), as the tracker feeds it.
std::vector<Point2f> rasterHull(const Quad& shape, int w, int h)
{
    std::vector<Point2f> pts;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (contains(shape, {float(x), float(y)}, 0.0))
                pts.push_back({float(x), float(y)});
    std::vector<Point2f> hull(pts.size() + 1);
    hull.resize(vision::convexHull(pts.data(), int(pts.size()), hull.data()));
    return hull;
}

double minCornerDistance(const Quad& q, Point2f p)
{
    double best = 1e9;
    for (const Point2f& c : q)
        best = std::min(best, double(std::hypot(c.x - p.x, c.y - p.y)));
    return best;
}

}  // namespace

TEST(MinBoundingQuad, AxisAlignedRectangleIsExact)
{
    const Quad rect = {{{10, 20}, {70, 20}, {70, 60}, {10, 60}}};
    std::vector<Point2f> hull = rasterHull(rect, 100, 100);
    ASSERT_EQ(hull.size(), 4u);
    Quad q;
    ASSERT_TRUE(vision::minBoundingQuad(hull.data(), int(hull.size()), q));
    for (const Point2f& c : rect)
        EXPECT_LT(minCornerDistance(q, c), 1e-4);
}

TEST(MinBoundingQuad, RotatedRectangleHullGivesItsCorners)
{
    // A rotated rectangle's raster hull has many vertices; the greedy quad recovers the rectangle
    // within about a pixel (pixel centres lie up to ~0.7 px inside the true edges).
    const double a = 0.35, cx = 100, cy = 90, hw = 60, hh = 35;
    Quad rect;
    const double dx[4] = {-hw, hw, hw, -hw}, dy[4] = {-hh, -hh, hh, hh};
    for (int i = 0; i < 4; ++i)
        rect[i] = {float(cx + dx[i] * std::cos(a) - dy[i] * std::sin(a)),
                   float(cy + dx[i] * std::sin(a) + dy[i] * std::cos(a))};
    std::vector<Point2f> hull = rasterHull(rect, 200, 200);
    ASSERT_GT(hull.size(), 8u);
    Quad q;
    ASSERT_TRUE(vision::minBoundingQuad(hull.data(), int(hull.size()), q));
    for (const Point2f& c : rect)
        EXPECT_LT(minCornerDistance(q, c), 1.5);
    for (const Point2f& p : hull)
        EXPECT_TRUE(contains(q, p, 1e-3));
}

TEST(MinBoundingQuad, ContainsTheHullOfRandomPolygons)
{
    std::uint32_t seed = 7;
    auto next = [&seed] {
        seed = seed * 1664525u + 1013904223u;
        return float((seed >> 16) % 500) / 5.f;
    };
    for (int trial = 0; trial < 40; ++trial) {
        std::vector<Point2f> pts(30);
        for (Point2f& p : pts)
            p = {next(), next()};
        std::vector<Point2f> hull(pts.size() + 1);
        hull.resize(vision::convexHull(pts.data(), int(pts.size()), hull.data()));
        Quad q;
        ASSERT_TRUE(vision::minBoundingQuad(hull.data(), int(hull.size()), q));
        double area = 0;
        for (int i = 0; i < 4; ++i)
            area += double(q[i].x) * q[(i + 1) % 4].y - double(q[(i + 1) % 4].x) * q[i].y;
        EXPECT_GT(area, 0.0);
        for (const Point2f& p : hull)
            EXPECT_TRUE(contains(q, p, 1e-2)) << "trial " << trial;
    }
}

TEST(MinBoundingQuad, RejectsTooFewVertices)
{
    const Point2f two[2] = {{0, 0}, {1, 1}};
    Quad q;
    EXPECT_FALSE(vision::minBoundingQuad(two, 2, q));
    const Point2f tri[3] = {{0, 0}, {10, 0}, {0, 10}};
    EXPECT_TRUE(vision::minBoundingQuad(tri, 3, q));
}
