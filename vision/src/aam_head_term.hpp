#pragma once
// The AAM fit's 3D term (§5; dissertation 5.3.2, eqs. 80, 83, 86): the soft constraint that the
// 2D shape be a projection of the CANDIDE head, added to the Gauss-Newton system each iteration
// (its Jacobian depends on the parameters; the 2D term's does not). Private to vision/src.

#include "aam_fit_tables.hpp"
#include "aam_head_projection.hpp"
#include "aam_warp.hpp"

#include <Eigen/Core>

namespace vision::aam {

/// The fit's unknowns: alpha, beta, q (4), p (m), then the head (kHeadParameters).
inline constexpr int kMaxParameters = 6 + kAamMaxShapeModes + kHeadParameters;
using ParameterMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxParameters, kMaxParameters>;
using ParameterVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxParameters, 1>;

struct HeadTermInput {
    const float* shape = nullptr;                ///< the current 2D shape, image (2V)
    const TriangleAffine* vertexMaps = nullptr;  ///< each vertex's frame -> image map
    float frameScale = 1.f;                      ///< N's scale: image pixels per frame pixel
    float weight = 1.f;                          ///< K
    bool shapeUnitsFrozen = false;
};

/// Adds K * J^T J to the lower triangle of `hessian` and -K * J^T e to `rhs`, where e is each
/// vertex's 2D shape less its head projection in frame pixels and J its derivative in every
/// unknown (the 2D shape's through the inverse composition, the head's directly), plus the
/// units' ridge. Frozen shape units get a zero step. `points` and `jacobian` are scratch (V).
void addHeadTerm(const Tables& t, const AamHead& head, const HeadTermInput& in, float* points,
                 HeadJacobian* jacobian, ParameterMatrix& hessian, ParameterVector& rhs) noexcept;

/// The 3D term's value at `head` and `in.shape`: K times the squared distances (frame pixels)
/// between the 2D shape and the head's projection, plus the units' ridge. What the step that
/// addHeadTerm's system gives must lower, with the 2D term and the shape prior.
double headTermEnergy(const Tables& t, const AamHead& head, const HeadTermInput& in,
                      float* points) noexcept;

}  // namespace vision::aam
