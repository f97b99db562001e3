#include "vision/min_bounding_quad.hpp"

#include <array>
#include <cmath>
#include <limits>

namespace vision {

namespace {

struct P {
    double x, y;
};

double cross(P a, P b) noexcept
{
    return a.x * b.y - a.y * b.x;
}

constexpr double kInfinite = std::numeric_limits<double>::infinity();

/// Area added by replacing edge (a, b) with the intersection of lines (p, a) and (b, q); the
/// intersection goes to `out`. Infinite when the lines do not meet beyond the edge.
double removalCost(P p, P a, P b, P q, P& out) noexcept
{
    const P d1{a.x - p.x, a.y - p.y};
    const P d2{q.x - b.x, q.y - b.y};
    const P ab{b.x - a.x, b.y - a.y};
    const double den = cross(d1, d2);
    if (std::fabs(den) < 1e-12)
        return kInfinite;
    // a + s d1 = b - u d2
    const double s = cross(ab, d2) / den;
    const double u = -cross(ab, d1) / den;  // from s d1 + u d2 = ab crossed with d1
    if (s < 0.0 || u < 0.0)
        return kInfinite;
    out = {a.x + s * d1.x, a.y + s * d1.y};
    return 0.5 * std::fabs(cross({out.x - a.x, out.y - a.y}, ab));
}

struct Work {
    std::array<P, kMaxQuadInputVertices> v;
    std::array<P, kMaxQuadInputVertices> meet;
    std::array<double, kMaxQuadInputVertices> cost;
    std::array<int, kMaxQuadInputVertices> next, prev;
};

}  // namespace

bool minBoundingQuad(const Point2f* hull, int n, Quad& quad, Size frame) noexcept
{
    if (n < 3 || n > kMaxQuadInputVertices)
        return false;
    if (n == 3) {
        int longest = 0;
        double best = -1.0;
        for (int i = 0; i < 3; ++i) {
            const Point2f a = hull[i], b = hull[(i + 1) % 3];
            const double l = std::hypot(b.x - a.x, b.y - a.y);
            if (l > best) {
                best = l;
                longest = i;
            }
        }
        int k = 0;
        for (int i = 0; i < 3; ++i) {
            quad[k++] = hull[i];
            if (i == longest) {
                const Point2f b = hull[(i + 1) % 3];
                quad[k++] = {(hull[i].x + b.x) * 0.5f, (hull[i].y + b.y) * 0.5f};
            }
        }
        return true;
    }
    // Scratch on the stack (48 KiB at the maximum size): re-entrant and no heap.
    Work w;
    for (int i = 0; i < n; ++i) {
        w.v[i] = {hull[i].x, hull[i].y};
        w.next[i] = (i + 1) % n;
        w.prev[i] = (i + n - 1) % n;
    }
    const double maxX = frame.width - 1, maxY = frame.height - 1;
    const bool haveFrame = frame.width > 0 && frame.height > 0;
    auto onBorder = [&](P a, P b) {
        auto same = [](double u, double v, double line) {
            return std::fabs(u - line) <= 0.5 && std::fabs(v - line) <= 0.5;
        };
        return haveFrame && (same(a.x, b.x, 0.0) || same(a.y, b.y, 0.0) || same(a.x, b.x, maxX) ||
                             same(a.y, b.y, maxY));
    };
    auto score = [&w, &onBorder](int i) {
        const int j = w.next[i];
        w.cost[i] = removalCost(w.v[w.prev[i]], w.v[i], w.v[j], w.v[w.next[j]], w.meet[i]);
        if (w.cost[i] < kInfinite && onBorder(w.v[i], w.v[j]))
            w.cost[i] -= 1e12;  // before any real edge
    };
    for (int i = 0; i < n; ++i)
        score(i);
    int count = n, head = 0;
    while (count > 4) {
        // Linear minimum search: hulls of pixel components have tens of vertices.
        int best = -1;
        double bestCost = kInfinite;
        int i = head;
        for (int k = 0; k < count; ++k, i = w.next[i])
            if (w.cost[i] < bestCost) {
                bestCost = w.cost[i];
                best = i;
            }
        if (best < 0)
            return false;
        const int j = w.next[best];
        w.v[best] = w.meet[best];
        w.next[best] = w.next[j];
        w.prev[w.next[j]] = best;
        if (head == j)
            head = best;
        --count;
        score(w.prev[best]);
        score(best);
    }
    int i = head;
    for (int k = 0; k < 4; ++k, i = w.next[i])
        quad[k] = {static_cast<float>(w.v[i].x), static_cast<float>(w.v[i].y)};
    return true;
}

}  // namespace vision
