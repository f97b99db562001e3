#include "vision/line_fit.hpp"

#include <cmath>

namespace vision {

namespace {

constexpr int kMaxPoints = 256;  // the tracker samples at most a few dozen points per edge

int countInliers(const Point2f* points, int n, const Line2f& line, float dist, double& residual,
                 std::uint8_t* mask) noexcept
{
    int count = 0;
    residual = 0.0;
    for (int i = 0; i < n; ++i) {
        const float d = std::fabs(line.distance(points[i]));
        const bool in = d <= dist;
        if (in) {
            ++count;
            residual += d;
        }
        if (mask)
            mask[i] = static_cast<std::uint8_t>(in);
    }
    return count;
}

}  // namespace

bool lineThrough(Point2f a, Point2f b, Line2f& line) noexcept
{
    const float dx = b.x - a.x, dy = b.y - a.y;
    const float len = std::hypot(dx, dy);
    if (!(len > 1e-6f))
        return false;
    line.nx = -dy / len;
    line.ny = dx / len;
    line.c = line.nx * a.x + line.ny * a.y;
    return true;
}

bool fitLineLeastSquares(const Point2f* points, int n, const std::uint8_t* use,
                         Line2f& line) noexcept
{
    double sx = 0, sy = 0;
    int m = 0;
    for (int i = 0; i < n; ++i)
        if (!use || use[i]) {
            sx += points[i].x;
            sy += points[i].y;
            ++m;
        }
    if (m < 2)
        return false;
    const double mx = sx / m, my = sy / m;
    double sxx = 0, sxy = 0, syy = 0;
    for (int i = 0; i < n; ++i)
        if (!use || use[i]) {
            const double dx = points[i].x - mx, dy = points[i].y - my;
            sxx += dx * dx;
            sxy += dx * dy;
            syy += dy * dy;
        }
    if (sxx + syy < 1e-12)
        return false;
    // Direction = principal axis of the scatter; the normal is perpendicular to it.
    const double theta = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
    const double nx = -std::sin(theta), ny = std::cos(theta);
    line.nx = static_cast<float>(nx);
    line.ny = static_cast<float>(ny);
    line.c = static_cast<float>(nx * mx + ny * my);
    return true;
}

int fitLineRansac(const Point2f* points, int n, float inlierDistance, int maxIterations,
                  Line2f& line, std::uint8_t* inliers) noexcept
{
    if (n < 2)
        return 0;
    if (n > kMaxPoints)
        n = kMaxPoints;
    const long pairs = static_cast<long>(n) * (n - 1) / 2;
    const bool exhaustive = pairs <= maxIterations;
    const int iterations = exhaustive ? static_cast<int>(pairs) : maxIterations;
    std::uint32_t seed = 0x9e3779b9u;  // fixed: the same frame always gives the same line
    int bestCount = 0;
    double bestResidual = 0.0;
    Line2f best;
    int i = 0, j = 1;
    for (int it = 0; it < iterations; ++it) {
        int a, b;
        if (exhaustive) {
            a = i;
            b = j;
            if (++j == n) {
                ++i;
                j = i + 1;
            }
        } else {
            seed = seed * 1664525u + 1013904223u;
            a = static_cast<int>((seed >> 8) % static_cast<std::uint32_t>(n));
            seed = seed * 1664525u + 1013904223u;
            b = static_cast<int>((seed >> 8) % static_cast<std::uint32_t>(n - 1));
            if (b >= a)
                ++b;
        }
        Line2f h;
        if (!lineThrough(points[a], points[b], h))
            continue;
        double residual;
        const int count = countInliers(points, n, h, inlierDistance, residual, nullptr);
        if (count > bestCount || (count == bestCount && residual < bestResidual)) {
            bestCount = count;
            bestResidual = residual;
            best = h;
        }
    }
    if (bestCount < 2)
        return 0;
    std::uint8_t mask[kMaxPoints];
    double residual;
    int count = countInliers(points, n, best, inlierDistance, residual, mask);
    for (int round = 0; round < 2; ++round) {
        Line2f refit;
        if (!fitLineLeastSquares(points, n, mask, refit))
            break;
        std::uint8_t mask2[kMaxPoints];
        const int c2 = countInliers(points, n, refit, inlierDistance, residual, mask2);
        if (c2 < count)
            break;
        best = refit;
        count = c2;
        for (int k = 0; k < n; ++k)
            mask[k] = mask2[k];
    }
    line = best;
    if (inliers)
        for (int k = 0; k < n; ++k)
            inliers[k] = mask[k];
    return count;
}

bool intersectLines(const Line2f& a, const Line2f& b, Point2f& out) noexcept
{
    const double det = static_cast<double>(a.nx) * b.ny - static_cast<double>(a.ny) * b.nx;
    if (std::fabs(det) < 1e-6)
        return false;
    out.x = static_cast<float>((static_cast<double>(a.c) * b.ny - static_cast<double>(a.ny) * b.c) /
                               det);
    out.y = static_cast<float>((static_cast<double>(a.nx) * b.c - static_cast<double>(a.c) * b.nx) /
                               det);
    return true;
}

}  // namespace vision
