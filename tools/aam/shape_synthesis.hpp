#pragma once
// The training shapes of §5 (dissertation 5.3.1): from each image's CANDIDE fit, 2D shapes made by
// turning the 3D head (yaw, pitch) and changing its expression (the animation units) at random and
// projecting every vertex, so one marked image covers the poses and expressions the model must
// follow. Roll is not varied: the alignment removes it.
//
// Where the text is silent: the ranges. Yaw within +-30 degrees (the tracking target, and IMM's
// turned heads), pitch within +-20 degrees (a mirror is looked into from about its height); each
// animation unit uniform in kAnimationRange below (negative jaw drop or lip stretch would push a
// part through another; the brow units and the lip corner go both ways). The projection is the
// fit's own: orthographic, scaled, rolled and translated as fitted.

#include "candide_fit.hpp"
#include "vision/candide_mesh.hpp"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace aam {

/// One animation unit's synthesized range, in the order of vision::kTrackedAnimationUnits.
struct UnitRange {
    float low, high;
};
inline constexpr std::array<UnitRange, 6> kAnimationRange{{
    {0.f, 1.f},    // jaw drop: closed to wide open
    {-0.5f, 1.f},  // lip stretcher
    {-1.f, 1.f},   // brow lowerer (negative: raised)
    {-0.5f, 1.f},  // outer brow raiser
    {-0.5f, 1.f},  // upper lip raiser
    {-1.f, 1.f},   // lip corner depressor (negative: corners up)
}};

struct SynthesisOptions {
    int shapesPerImage = 100;
    float maxYawDegrees = 30.f;
    float maxPitchDegrees = 20.f;
    std::uint32_t seed = 1;  ///< the same seed gives the same shapes
};

/// A 2D shape: every vertex of the mesh, image pixels.
using Shape2d = std::vector<Eigen::Vector2d>;

/// The shape as one vector (x0, y0, x1, y1, ...), as the shape model's PCA and errors take it.
Eigen::VectorXd asVector(const Shape2d& shape);

/// The mesh under `fit` with yaw and pitch (radians; yaw about CANDIDE's y axis, positive turning
/// the face to its left: the nose moves to the image's right; pitch about its x axis, positive
/// turning the face down) and the animation values `tau` (the fit's shape units kept).
Shape2d posedShape(const vision::CandideMesh& face, const CandideFit& fit, double yaw, double pitch,
                   const std::vector<float>& tau);

/// `options.shapesPerImage` shapes from one fit, poses and expressions drawn at random.
std::vector<Shape2d> synthesizeShapes(const vision::CandideMesh& face, const CandideFit& fit,
                                      const SynthesisOptions& options = {});

}  // namespace aam
