#include "vision/convex_hull.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

using vision::Point2f;

namespace {

double cross(Point2f o, Point2f a, Point2f b)
{
    return (double(a.x) - o.x) * (double(b.y) - o.y) - (double(a.y) - o.y) * (double(b.x) - o.x);
}

/// Brute force: gift wrapping (Jarvis march), taking the farthest point among collinear ones.
std::vector<Point2f> jarvis(const std::vector<Point2f>& pts)
{
    Point2f start = pts[0];
    for (const Point2f& p : pts)
        if (p.x < start.x || (p.x == start.x && p.y < start.y))
            start = p;
    std::vector<Point2f> hull;
    Point2f p = start;
    do {
        hull.push_back(p);
        Point2f q = p;
        for (const Point2f& r : pts) {
            if (r == p)
                continue;
            if (q == p) {
                q = r;
                continue;
            }
            const double c = cross(p, q, r);
            const double dq = double(q.x - p.x) * (q.x - p.x) + double(q.y - p.y) * (q.y - p.y);
            const double dr = double(r.x - p.x) * (r.x - p.x) + double(r.y - p.y) * (r.y - p.y);
            if (c < 0 || (c == 0 && dr > dq))
                q = r;
        }
        p = q;
    } while (!(p == start) && hull.size() <= pts.size());
    return hull;
}

}  // namespace

TEST(ConvexHull, MatchesBruteForceOnRandomPoints)
{
    std::uint32_t seed = 12345;
    auto next = [&seed] {
        seed = seed * 1664525u + 1013904223u;
        return static_cast<int>((seed >> 16) % 60);  // small range: many duplicates, collinears
    };
    for (int trial = 0; trial < 60; ++trial) {
        const int n = 3 + trial * 3;
        std::vector<Point2f> pts(n);
        for (Point2f& p : pts)
            p = {static_cast<float>(next()), static_cast<float>(next())};
        std::vector<Point2f> work = pts, hull(n + 1);
        const int h = vision::convexHull(work.data(), n, hull.data());
        const std::vector<Point2f> expected = jarvis(pts);
        ASSERT_EQ(h, static_cast<int>(expected.size())) << "trial " << trial;
        for (int i = 0; i < h; ++i)
            EXPECT_EQ(hull[i], expected[i]) << "trial " << trial << " vertex " << i;
        EXPECT_GT(vision::signedArea2(hull.data(), h), 0.0);
    }
}

TEST(ConvexHull, DropsCollinearAndDuplicatePoints)
{
    std::vector<Point2f> pts = {{0, 0},  {5, 0}, {10, 0}, {10, 10},
                                {0, 10}, {5, 5}, {0, 0},  {10, 5}};
    std::vector<Point2f> hull(pts.size() + 1);
    const int h = vision::convexHull(pts.data(), static_cast<int>(pts.size()), hull.data());
    ASSERT_EQ(h, 4);
    // Clockwise on screen from the smallest (x, y): (0,0), (10,0), (10,10), (0,10)... Andrew's
    // order starts at the leftmost-lowest point and runs the y-down clockwise way.
    EXPECT_EQ(hull[0], (Point2f{0, 0}));
    EXPECT_GT(vision::signedArea2(hull.data(), h), 0.0);
}
