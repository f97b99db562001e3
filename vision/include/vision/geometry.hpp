#pragma once
// Small geometry types of the vision core, in image coordinates: pixels, origin at the top-left
// pixel's centre, x to the right, y down. Fixed-size, never allocate.

#include <array>

namespace vision {

struct Point2f {
    float x = 0.0f;
    float y = 0.0f;
    friend constexpr bool operator==(Point2f, Point2f) = default;
};

/// A quadrilateral's corners, clockwise on screen (y down) starting from the top-left corner.
using Quad = std::array<Point2f, 4>;

/// An axis-aligned rectangle of whole pixels: [x, x + width) x [y, y + height).
struct Rect {
    int x = 0;
    int y = 0;
    int width = 0;
    int height = 0;
    friend constexpr bool operator==(Rect, Rect) = default;
};

}  // namespace vision
