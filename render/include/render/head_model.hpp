#pragma once
// HeadModel: the average head the 3D overlays are placed on and hidden by (assets/overlays/
// FORMAT.md documents the same numbers for the people who make overlays).
//
// Positions are in the OBJ model axes of the catalogue (x towards image right = the wearer's left,
// y up, z out of the face towards the camera), in units of the face width W, origin at the eye
// midpoint. They map to the head frame of vision/head_pose.hpp (y down, z into the head) by
// (x, -y, -z) * W.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace render {

struct HeadModel {
    float faceWidthMetres = 0.15f;          ///< W: the face box side (vision::headPoseFromFace)
    float interocularPerFaceWidth = 0.42f;  ///< I / W (pupil to pupil: 0.063 m for W = 0.15 m)

    std::array<float, 3> eyeMidpoint{0.f, 0.f, 0.f};
    std::array<float, 3> noseBridge{0.f, -0.04f, 0.06f};
    std::array<float, 3> foreheadTop{0.f, 0.45f, -0.04f};
    std::array<float, 3> headTop{0.f, 0.80f, -0.55f};
    /// The middle of the upper lip's top (under the nose) and the chin's front, from CANDIDE-3
    /// (vertices 7 and 10, relative to its eye corners' midpoint, the mesh 0.735 of W wide as the
    /// AAM start places it).
    std::array<float, 3> upperLip{0.f, -0.34f, 0.12f};
    std::array<float, 3> chin{0.f, -0.60f, 0.06f};

    /// The invisible head that hides overlay parts behind it: an ellipsoid whose horizontal
    /// sections are superellipses |x/a|^n + |z/c|^n = 1 with n = proxySquareness (2 = ellipse):
    /// a face is flatter and wider in front than an ellipse, so n = 3 hides the far temple arm
    /// behind the eyes of a turned head and still keeps clear of the glasses' front.
    std::array<float, 3> proxyCentre{0.f, 0.f, -0.55f};
    std::array<float, 3> proxySemiAxes{0.5f, 0.8f, 0.62f};
    float proxySquareness = 3.f;
};

/// The head proxy of unit semi-axes and exponent `squareness` (HeadModel::proxySquareness) as an
/// indexed triangle mesh in the model axes: each distinct corner once (sorted), three indices a
/// triangle, wound counter-clockwise seen from outside. Made once at start-up.
struct HeadProxyMesh {
    std::vector<std::array<float, 3>> points;
    std::vector<std::uint16_t> indices;
};
HeadProxyMesh unitHeadProxy(float squareness);

/// The head frame of vision/head_pose.hpp (y down, z into the head) from the model axes above
/// (y up, z towards the camera): a half turn about x.
inline Eigen::Matrix3f modelToHeadAxes()
{
    return Eigen::Vector3f(1.f, -1.f, -1.f).asDiagonal();
}

}  // namespace render
