#pragma once
// The CANDIDE head of the AAM fit's 3D term (§5; dissertation 5.3.2, eqs. 80, 81, 84, 86): every
// vertex projected by the head's parameters, and the projection's Jacobian. Private to
// vision/src.

#include "aam_fit_tables.hpp"

#include <Eigen/Core>

namespace vision::aam {

/// The head's parameters in the fit's order: scale, roll, pitch, yaw, tx, ty, sigma, tau.
inline constexpr int kHeadParameters = 6 + kAamShapeUnits + kAamAnimationUnits;
using HeadJacobian = Eigen::Matrix<float, 2, kHeadParameters>;

/// The head as one parameter vector, and back.
Eigen::Matrix<float, kHeadParameters, 1> headParameters(const AamHead& head) noexcept;
void setHeadParameters(AamHead& head, const Eigen::Matrix<float, kHeadParameters, 1>& r) noexcept;

/// Every vertex of the deformed CANDIDE shape projected (AamHead's projection) into `points`
/// (2V), and when `jacobian` is not null its derivative per vertex.
void projectHead(const Tables& t, const AamHead& head, float* points,
                 HeadJacobian* jacobian) noexcept;

/// The head's scale, roll and translation that best put its projection at its own yaw (pitch 0,
/// its own sigma and tau) onto `shape` (2V image points), by linear least squares; pitch set to
/// 0, yaw kept (0 for a frontal start; a turned start's yaw otherwise). The start of a new face's
/// 3D term.
void placeHeadOn(const Tables& t, const float* shape, AamHead& head) noexcept;

}  // namespace vision::aam
