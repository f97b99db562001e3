#pragma once
// Mesh building blocks for the overlay models: solids made of triangles over shared positions,
// built from parametric grids (lathes, tubes, prisms, brims), then welded and given normals.

#include <Eigen/Core>
#include <array>
#include <functional>
#include <string>
#include <vector>

namespace overlaygen {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

/// One triangle: three position indices (counter-clockwise seen from outside) and the index of
/// the model part (OBJ object) it belongs to.
struct Triangle {
    std::array<int, 3> v{};
    int part = 0;
};

/// \class Solid
/// A closed surface (or a union of closed surfaces) in metres. Parts of one solid may go to
/// different OBJ objects (e.g. the two colours of a striped cone) yet share their seam vertices,
/// so the normals stay smooth across the seam and the union stays watertight.
struct Solid {
    std::vector<Vec3> positions;
    std::vector<Triangle> triangles;
    /// Faces meeting at a larger angle than this keep separate normals (a sharp edge).
    double creaseDegrees = 45.0;

    /// Appends `other`, renumbering its indices.
    void append(const Solid& other);
    /// Applies p -> rotation * p + translation to every position.
    void transform(const Eigen::Matrix3d& rotation, const Vec3& translation);
};

/// Position of grid point (i, j) and the part of the quad whose lower corner is (i, j).
using GridPoint = std::function<Vec3(int i, int j)>;
using GridPart = std::function<int(int i, int j)>;

/// A surface over an nu x nv grid of points; wrapU/wrapV join the last column/row to the first.
/// Rows or columns that collapse to a single point (a pole, a cap centre) become fans once the
/// solid is welded. The result is oriented outwards by its signed volume, so it must be closed.
Solid gridSolid(int nu, int nv, bool wrapU, bool wrapV, const GridPoint& point,
                const GridPart& part);

/// A solid of revolution about +y: `profile` is (radius, y) from the bottom pole (radius 0) to
/// the top pole (radius 0). The radius is scaled by `scaleX`/`scaleZ` (elliptical sections);
/// angle 0 is the front (+z), increasing towards +x.
Solid lathe(const std::vector<Vec2>& profile, int segments, double scaleX, double scaleZ, int part);

/// A ring solid of revolution about +y: `loop` is a closed (radius, y) cross-section (no point on
/// the axis), e.g. a hat band. Radius scaled as in lathe().
Solid latheLoop(const std::vector<Vec2>& loop, int segments, double scaleX, double scaleZ,
                int part);

/// A smooth open curve through the control points (Catmull-Rom), `samples` points per span.
std::vector<Vec3> smoothPath(const std::vector<Vec3>& controls, int samples);

/// A tube of elliptical cross-section along `path`: `halfWidth` along reference x tangent (for a
/// rim in the xy plane with reference +z: the rim's width seen from the front), `halfDepth`
/// along the reference (the rim's depth). The reference must never be parallel to the path.
/// Closed paths are rings; open paths get flat end caps.
Solid tube(const std::vector<Vec3>& path, bool closedPath, double halfWidth, double halfDepth,
           const Vec3& reference, int sectionSegments, int part);

/// A prism: the star-shaped outline (in the plane z = 0, counter-clockwise seen from +z)
/// extruded from z = -halfThickness to +halfThickness, caps fanned from the outline's centroid.
Solid prism(const std::vector<Vec2>& outline, double halfThickness, int part);

/// A box centred on the origin.
Solid box(const Vec3& halfSize, int part);

/// An ellipsoid centred on the origin.
Solid ellipsoid(const Vec3& semiAxes, int segments, int rings, int part);

/// Points on a closed curve: a superellipse |x/a|^n + |y/b|^n = 1 (n = 2 ellipse, larger n
/// squarer), counter-clockwise from +x, with an optional narrowing of the bottom half
/// (`taper` > 0 makes the lower edge narrower, like a lens that follows the cheek).
std::vector<Vec2> superellipse(double a, double b, double exponent, int count, double taper = 0.0);

/// Rotation about the axis by the angle (radians).
Eigen::Matrix3d rotationX(double radians);
Eigen::Matrix3d rotationY(double radians);
Eigen::Matrix3d rotationZ(double radians);

/// Deterministic pseudo-random value in [-1, 1] from integers (no std distributions, whose
/// output is implementation-defined).
double hashNoise(int a, int b, int c);

}  // namespace overlaygen
