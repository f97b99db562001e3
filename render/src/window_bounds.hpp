#pragma once
// Window-pixel bounds of what a mesh can cover: FaceOverlayLayer scissors its depth clears and
// draws to them, so each face costs the pixels near it and not the whole screen.

#include <GLES2/gl2.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <vector>

namespace render::detail {

// A rectangle of window pixels, x0 <= x < x1, y0 <= y < y1, y up (glScissor's).
struct PixelRect {
    int x0 = 0;
    int y0 = 0;
    int x1 = 0;
    int y1 = 0;
    long area() const noexcept { return static_cast<long>(x1 - x0) * (y1 - y0); }
    bool intersects(const PixelRect& o) const noexcept
    {
        return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
    }
    PixelRect intersection(const PixelRect& o) const noexcept
    {
        return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
    }
    PixelRect hull(const PixelRect& o) const noexcept
    {
        return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
    }
    void scissor() const noexcept { glScissor(x0, y0, x1 - x0, y1 - y0); }
};

/// The window pixels that triangles with corners `points` can cover when drawn with
/// `modelViewProjection` into `viewport`; the whole viewport when a point is not in front of the
/// camera.
PixelRect windowBounds(const Eigen::Matrix4f& modelViewProjection,
                       const std::vector<Eigen::Vector3f>& points,
                       const PixelRect& viewport) noexcept;

/// The distinct points of a list of xyz points (a mesh's vertices, shared corners once).
std::vector<Eigen::Vector3f> distinctPoints(std::vector<std::array<float, 3>> points);

}  // namespace render::detail
