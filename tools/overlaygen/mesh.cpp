#include "mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace overlaygen {

namespace {

double signedVolume(const Solid& solid)
{
    double volume = 0.0;
    for (const Triangle& t : solid.triangles) {
        const Vec3& a = solid.positions[static_cast<std::size_t>(t.v[0])];
        const Vec3& b = solid.positions[static_cast<std::size_t>(t.v[1])];
        const Vec3& c = solid.positions[static_cast<std::size_t>(t.v[2])];
        volume += a.dot(b.cross(c)) / 6.0;
    }
    return volume;
}

}  // namespace

void Solid::append(const Solid& other)
{
    const int base = static_cast<int>(positions.size());
    positions.insert(positions.end(), other.positions.begin(), other.positions.end());
    for (Triangle t : other.triangles) {
        for (int& v : t.v)
            v += base;
        triangles.push_back(t);
    }
}

void Solid::transform(const Eigen::Matrix3d& rotation, const Vec3& translation)
{
    for (Vec3& p : positions)
        p = rotation * p + translation;
}

Solid gridSolid(int nu, int nv, bool wrapU, bool wrapV, const GridPoint& point,
                const GridPart& part)
{
    Solid solid;
    solid.positions.reserve(static_cast<std::size_t>(nu * nv));
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            solid.positions.push_back(point(i, j));
    const auto index = [nu](int i, int j) { return j * nu + i; };
    const int quadsU = wrapU ? nu : nu - 1;
    const int quadsV = wrapV ? nv : nv - 1;
    for (int j = 0; j < quadsV; ++j) {
        const int j1 = (j + 1) % nv;
        for (int i = 0; i < quadsU; ++i) {
            const int i1 = (i + 1) % nu;
            const int p = part(i, j);
            solid.triangles.push_back({{index(i, j), index(i1, j), index(i1, j1)}, p});
            solid.triangles.push_back({{index(i, j), index(i1, j1), index(i, j1)}, p});
        }
    }
    // Outward by construction is easy to get wrong for every parameterisation; the signed
    // volume of a closed surface says which way it faces.
    if (signedVolume(solid) < 0.0)
        for (Triangle& t : solid.triangles)
            std::swap(t.v[1], t.v[2]);
    return solid;
}

Solid lathe(const std::vector<Vec2>& profile, int segments, double scaleX, double scaleZ, int part)
{
    return gridSolid(
        segments, static_cast<int>(profile.size()), true, false,
        [&](int i, int j) {
            const double angle = 2.0 * std::numbers::pi * i / segments;
            const Vec2& p = profile[static_cast<std::size_t>(j)];
            return Vec3(p.x() * scaleX * std::sin(angle), p.y(), p.x() * scaleZ * std::cos(angle));
        },
        [part](int, int) { return part; });
}

Solid latheLoop(const std::vector<Vec2>& loop, int segments, double scaleX, double scaleZ, int part)
{
    return gridSolid(
        segments, static_cast<int>(loop.size()), true, true,
        [&](int i, int j) {
            const double angle = 2.0 * std::numbers::pi * i / segments;
            const Vec2& p = loop[static_cast<std::size_t>(j)];
            return Vec3(p.x() * scaleX * std::sin(angle), p.y(), p.x() * scaleZ * std::cos(angle));
        },
        [part](int, int) { return part; });
}

std::vector<Vec3> smoothPath(const std::vector<Vec3>& controls, int samples)
{
    std::vector<Vec3> path;
    const int n = static_cast<int>(controls.size());
    const auto at = [&](int k) {
        return controls[static_cast<std::size_t>(std::clamp(k, 0, n - 1))];
    };
    for (int k = 0; k + 1 < n; ++k) {
        const Vec3 p0 = at(k - 1), p1 = at(k), p2 = at(k + 1), p3 = at(k + 2);
        for (int s = 0; s < samples; ++s) {
            const double t = static_cast<double>(s) / samples;
            const double t2 = t * t, t3 = t2 * t;
            path.push_back(0.5 *
                           (2.0 * p1 + (p2 - p0) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 +
                            (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3));
        }
    }
    path.push_back(controls.back());
    return path;
}

Solid tube(const std::vector<Vec3>& path, bool closedPath, double halfWidth, double halfDepth,
           const Vec3& reference, int sectionSegments, int part)
{
    const int n = static_cast<int>(path.size());
    std::vector<Vec3> axisA(path.size());
    std::vector<Vec3> axisB(path.size());
    for (int k = 0; k < n; ++k) {
        const Vec3& prev =
            path[static_cast<std::size_t>(closedPath ? (k + n - 1) % n : std::max(k - 1, 0))];
        const Vec3& next =
            path[static_cast<std::size_t>(closedPath ? (k + 1) % n : std::min(k + 1, n - 1))];
        const Vec3 tangent = (next - prev).normalized();
        axisA[static_cast<std::size_t>(k)] = reference.cross(tangent).normalized();
        axisB[static_cast<std::size_t>(k)] =
            tangent.cross(axisA[static_cast<std::size_t>(k)]).normalized();
    }
    const auto ring = [&](int k, int s) {
        const double angle = 2.0 * std::numbers::pi * s / sectionSegments;
        const std::size_t kk = static_cast<std::size_t>(k);
        return Vec3(path[kk] + axisA[kk] * (halfWidth * std::cos(angle)) +
                    axisB[kk] * (halfDepth * std::sin(angle)));
    };
    if (closedPath)
        return gridSolid(n, sectionSegments, true, true, ring, [part](int, int) { return part; });
    // Rows 0 and n + 1 are the cap centres (collapsed rings).
    return gridSolid(
        n + 2, sectionSegments, false, true,
        [&](int u, int s) {
            if (u == 0)
                return path.front();
            if (u == n + 1)
                return path.back();
            return ring(u - 1, s);
        },
        [part](int, int) { return part; });
}

Solid prism(const std::vector<Vec2>& outline, double halfThickness, int part)
{
    Vec2 centre = Vec2::Zero();
    for (const Vec2& p : outline)
        centre += p;
    centre /= static_cast<double>(outline.size());
    Solid solid = gridSolid(
        static_cast<int>(outline.size()), 4, true, false,
        [&](int i, int j) {
            const Vec2& p = (j == 0 || j == 3) ? centre : outline[static_cast<std::size_t>(i)];
            return Vec3(p.x(), p.y(), j < 2 ? -halfThickness : halfThickness);
        },
        [part](int, int) { return part; });
    solid.creaseDegrees = 30.0;
    return solid;
}

Solid box(const Vec3& halfSize, int part)
{
    const std::vector<Vec2> outline = {{-halfSize.x(), -halfSize.y()},
                                       {halfSize.x(), -halfSize.y()},
                                       {halfSize.x(), halfSize.y()},
                                       {-halfSize.x(), halfSize.y()}};
    return prism(outline, halfSize.z(), part);
}

Solid ellipsoid(const Vec3& semiAxes, int segments, int rings, int part)
{
    std::vector<Vec2> profile;
    for (int k = 0; k <= rings; ++k) {
        const double angle = std::numbers::pi * k / rings - std::numbers::pi / 2.0;
        profile.emplace_back(k == 0 || k == rings ? 0.0 : std::cos(angle), std::sin(angle));
    }
    Solid solid = lathe(profile, segments, semiAxes.x(), semiAxes.z(), part);
    for (Vec3& p : solid.positions)
        p.y() *= semiAxes.y();
    return solid;
}

std::vector<Vec2> superellipse(double a, double b, double exponent, int count, double taper)
{
    std::vector<Vec2> points;
    for (int k = 0; k < count; ++k) {
        const double t = 2.0 * std::numbers::pi * k / count;
        const double c = std::cos(t);
        const double s = std::sin(t);
        double x = a * std::copysign(std::pow(std::abs(c), 2.0 / exponent), c);
        const double y = b * std::copysign(std::pow(std::abs(s), 2.0 / exponent), s);
        if (y < 0.0)
            x *= 1.0 - taper * (-y / b);
        points.emplace_back(x, y);
    }
    return points;
}

Eigen::Matrix3d rotationX(double radians)
{
    return Eigen::AngleAxisd(radians, Vec3::UnitX()).toRotationMatrix();
}

Eigen::Matrix3d rotationY(double radians)
{
    return Eigen::AngleAxisd(radians, Vec3::UnitY()).toRotationMatrix();
}

Eigen::Matrix3d rotationZ(double radians)
{
    return Eigen::AngleAxisd(radians, Vec3::UnitZ()).toRotationMatrix();
}

double hashNoise(int a, int b, int c)
{
    std::uint32_t h = static_cast<std::uint32_t>(a) * 73856093u ^
                      static_cast<std::uint32_t>(b) * 19349663u ^
                      static_cast<std::uint32_t>(c) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return static_cast<double>(h & 0xffffu) / 32767.5 - 1.0;
}

}  // namespace overlaygen
