#pragma once
// Where an overlay of the catalogue sits on the head model: model units to head-frame metres.

#include "render/head_model.hpp"
#include "render/overlay_catalogue.hpp"
#include "vision/face_fit.hpp"

#include <Eigen/Core>
#include <array>

namespace render::detail {

/// x -> linear * x + translation.
struct Affine {
    Eigen::Matrix3f linear;
    Eigen::Vector3f translation;
};

inline Eigen::Vector3f toVector(const std::array<float, 3>& a)
{
    return {a[0], a[1], a[2]};
}

/// Model units -> head frame metres for one overlay (assets/overlays/FORMAT.md). With
/// `animation` (a fitted face's six values, vision::FaceFit::animation) the overlay's follows
/// apply; without it (no fit) it sits as for a neutral face.
Affine modelToHead(const Overlay& overlay, const HeadModel& head,
                   const std::array<float, vision::kAamAnimationUnits>* animation = nullptr);

}  // namespace render::detail
