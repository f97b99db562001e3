#include "render/head_model.hpp"

#include "vision/geometry.hpp"

#include <algorithm>
#include <cmath>

namespace render {

namespace {

// 960 triangles. Not for the silhouette (8 rings of 16 already keep it within 2 % of the
// radius) but for the depth: a facet is a chord, behind the surface, and where a hat's brim passes
// behind the head the brim is cut along the facets. With 8 rings a near face (FGNet: 26 cm from
// the camera, the brim seen from below) had its brim cut along a straight ring edge, a box across
// the forehead; 16 rings of 32 follow the round head (drawn depth-only, inside the overlays'
// rectangles).
constexpr int kProxySegments = 32;  // around the vertical axis
constexpr int kProxyRings = 16;     // pole to pole

// The head proxy of unit semi-axes as a triangle list (positions only): a sphere whose
// horizontal sections are superellipses of exponent `n` (HeadModel::proxySquareness). Wound
// counter-clockwise seen from outside like the closed overlay meshes, so its back half is culled
// (it is convex: the front half is the nearer one everywhere), and without the zero-area
// triangles at the poles.
std::vector<float> unitProxyTriangles(float n)
{
    std::vector<float> out;
    auto superPower = [n](float c) { return std::copysign(std::pow(std::fabs(c), 2.f / n), c); };
    auto point = [&](int ring, int segment) {
        const float theta = vision::toRadians(static_cast<float>(ring) * 180.f / kProxyRings);
        const float phi = vision::toRadians(static_cast<float>(segment) * 360.f / kProxySegments);
        out.push_back(std::sin(theta) * superPower(std::cos(phi)));
        out.push_back(std::cos(theta));
        out.push_back(std::sin(theta) * superPower(std::sin(phi)));
    };
    for (int r = 0; r < kProxyRings; ++r)
        for (int s = 0; s < kProxySegments; ++s) {
            // Ring r + 1 is below ring r, segment s + 1 is further round towards +z.
            if (r + 1 < kProxyRings) {
                point(r, s);
                point(r + 1, s + 1);
                point(r + 1, s);
            }
            if (r > 0) {
                point(r, s);
                point(r, s + 1);
                point(r + 1, s + 1);
            }
        }
    return out;
}

}  // namespace

HeadProxyMesh unitHeadProxy(float squareness)
{
    // Indexed: each distinct vertex is transformed once.
    const std::vector<float> sphere = unitProxyTriangles(squareness);
    std::vector<std::array<float, 3>> corners;
    for (std::size_t i = 0; i + 2 < sphere.size(); i += 3)
        corners.push_back({sphere[i], sphere[i + 1], sphere[i + 2]});
    HeadProxyMesh mesh;
    mesh.points = corners;
    std::sort(mesh.points.begin(), mesh.points.end());
    mesh.points.erase(std::unique(mesh.points.begin(), mesh.points.end()), mesh.points.end());
    for (const auto& corner : corners)
        mesh.indices.push_back(static_cast<std::uint16_t>(
            std::lower_bound(mesh.points.begin(), mesh.points.end(), corner) -
            mesh.points.begin()));
    return mesh;
}

}  // namespace render
