#include "vision/convex_hull.hpp"

#include <algorithm>

namespace vision {

namespace {

/// z of (a - o) x (b - o) in double: pixel coordinates squared exceed float's exact range.
double cross(Point2f o, Point2f a, Point2f b) noexcept
{
    return (static_cast<double>(a.x) - o.x) * (static_cast<double>(b.y) - o.y) -
           (static_cast<double>(a.y) - o.y) * (static_cast<double>(b.x) - o.x);
}

}  // namespace

int convexHull(Point2f* points, int n, Point2f* hull) noexcept
{
    if (n <= 0)
        return 0;
    std::sort(points, points + n,
              [](Point2f a, Point2f b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    n = static_cast<int>(std::unique(points, points + n) - points);
    if (n < 3) {
        std::copy(points, points + n, hull);
        return n;
    }
    // In y-down coordinates a positive cross product is a clockwise turn on screen; keep only
    // strict turns that way (drops collinear points).
    int k = 0;
    for (int i = 0; i < n; ++i) {  // upper-on-screen chain, left to right
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0)
            --k;
        hull[k++] = points[i];
    }
    for (int i = n - 2, lower = k + 1; i >= 0; --i) {  // the other chain, right to left
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0)
            --k;
        hull[k++] = points[i];
    }
    return k - 1;  // the last point repeats the first
}

double signedArea2(const Point2f* polygon, int n) noexcept
{
    double a = 0.0;
    for (int i = 0; i < n; ++i) {
        const Point2f p = polygon[i];
        const Point2f q = polygon[(i + 1) % n];
        a += static_cast<double>(p.x) * q.y - static_cast<double>(q.x) * p.y;
    }
    return a;
}

}  // namespace vision
