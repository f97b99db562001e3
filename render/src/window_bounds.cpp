#include "window_bounds.hpp"

#include <cmath>

namespace render::detail {

// The projected points' bounds (a triangle in front of the camera projects to the triangle of
// its projected corners) plus a pixel.
PixelRect windowBounds(const Eigen::Matrix4f& modelViewProjection,
                       const std::vector<Eigen::Vector3f>& points,
                       const PixelRect& viewport) noexcept
{
    Eigen::Matrix<float, 3, 4> xyw;  // clip x, y and w; z is not needed
    xyw << modelViewProjection.row(0), modelViewProjection.row(1), modelViewProjection.row(3);
    Eigen::Vector2f lo(INFINITY, INFINITY);
    Eigen::Vector2f hi(-INFINITY, -INFINITY);
    for (const Eigen::Vector3f& p : points) {
        const Eigen::Vector3f clip = xyw.leftCols<3>() * p + xyw.col(3);
        if (!(clip.z() > 1e-6f))
            return viewport;
        const Eigen::Vector2f ndc = clip.head<2>() / clip.z();
        lo = lo.cwiseMin(ndc);
        hi = hi.cwiseMax(ndc);
    }
    if (!(lo.minCoeff() > -1e4f && hi.maxCoeff() < 1e4f))
        return viewport;  // no points, NaN or absurd: do not trust it
    const float sx = 0.5f * static_cast<float>(viewport.x1 - viewport.x0);
    const float sy = 0.5f * static_cast<float>(viewport.y1 - viewport.y0);
    const PixelRect bounds{viewport.x0 + static_cast<int>(std::floor((lo.x() + 1.f) * sx)) - 1,
                           viewport.y0 + static_cast<int>(std::floor((lo.y() + 1.f) * sy)) - 1,
                           viewport.x0 + static_cast<int>(std::ceil((hi.x() + 1.f) * sx)) + 1,
                           viewport.y0 + static_cast<int>(std::ceil((hi.y() + 1.f) * sy)) + 1};
    return bounds.intersection(viewport);
}

// The distinct points of a triangle list of xyz floats.
std::vector<Eigen::Vector3f> distinctPoints(std::vector<std::array<float, 3>> points)
{
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    std::vector<Eigen::Vector3f> out;
    out.reserve(points.size());
    for (const auto& p : points)
        out.emplace_back(p[0], p[1], p[2]);
    return out;
}

}  // namespace render::detail
