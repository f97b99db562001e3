#pragma once
// Small geometry types of the vision core, in image coordinates: pixels, origin at the top-left
// pixel's centre, x to the right, y down. Fixed-size, never allocate.

#include <algorithm>
#include <array>
#include <numbers>

namespace vision {

/// Angles: the method, the config and the tracks speak degrees, the trigonometry radians. In
/// float, both conversions multiply by the float nearest the factor (pi/180 and 180/pi); in
/// double, degrees -> radians is (d * pi) / 180.
inline constexpr float kRadiansPerDegree = std::numbers::pi_v<float> / 180.f;
inline constexpr float kDegreesPerRadian = static_cast<float>(180.0 / std::numbers::pi);
constexpr float toRadians(float degrees) noexcept
{
    return degrees * kRadiansPerDegree;
}
constexpr float toDegrees(float radians) noexcept
{
    return radians * kDegreesPerRadian;
}
constexpr double toRadians(double degrees) noexcept
{
    return degrees * std::numbers::pi / 180.0;
}
constexpr double toDegrees(double radians) noexcept
{
    return radians * (180.0 / std::numbers::pi);
}

struct Point2f {
    float x = 0.0f;
    float y = 0.0f;
    friend constexpr bool operator==(Point2f, Point2f) = default;
};

/// A quadrilateral's corners, clockwise on screen (y down) starting from the top-left corner.
using Quad = std::array<Point2f, 4>;

/// The axis-aligned extent of a quad's corners, in (unrounded) pixels.
struct QuadExtent {
    float x0, y0, x1, y1;
};

constexpr QuadExtent extentOf(const Quad& q) noexcept
{
    QuadExtent e{q[0].x, q[0].y, q[0].x, q[0].y};
    for (const Point2f& p : q) {
        e.x0 = std::min(e.x0, p.x);
        e.x1 = std::max(e.x1, p.x);
        e.y0 = std::min(e.y0, p.y);
        e.y1 = std::max(e.y1, p.y);
    }
    return e;
}

/// An axis-aligned rectangle of whole pixels: [x, x + width) x [y, y + height).
struct Rect {
    int x = 0;
    int y = 0;
    int width = 0;
    int height = 0;
    friend constexpr bool operator==(Rect, Rect) = default;
};

/// The part of `r` inside [0, width) x [0, height); an empty Rect ({}) when none is.
constexpr Rect clipped(Rect r, int width, int height) noexcept
{
    const int x0 = std::max(r.x, 0);
    const int y0 = std::max(r.y, 0);
    const int x1 = std::min(r.x + r.width, width);
    const int y1 = std::min(r.y + r.height, height);
    if (x1 <= x0 || y1 <= y0)
        return {};
    return {x0, y0, x1 - x0, y1 - y0};
}

/// Intersection over union of two rectangles, 0 when they do not overlap.
constexpr float iou(Rect a, Rect b) noexcept
{
    const int x0 = std::max(a.x, b.x);
    const int y0 = std::max(a.y, b.y);
    const int x1 = std::min(a.x + a.width, b.x + b.width);
    const int y1 = std::min(a.y + a.height, b.y + b.height);
    if (x1 <= x0 || y1 <= y0)
        return 0.f;
    const float inter = static_cast<float>(x1 - x0) * static_cast<float>(y1 - y0);
    const float uni = static_cast<float>(a.width) * static_cast<float>(a.height) +
                      static_cast<float>(b.width) * static_cast<float>(b.height) - inter;
    return uni > 0.f ? inter / uni : 0.f;
}

}  // namespace vision
