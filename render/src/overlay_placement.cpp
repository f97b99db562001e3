#include "overlay_placement.hpp"

#include "vision/geometry.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace render::detail {

namespace {

const std::array<float, 3>& anchorPoint(const HeadModel& head, OverlayAnchor anchor) noexcept
{
    switch (anchor) {
        case OverlayAnchor::EyeMidpoint:
            return head.eyeMidpoint;
        case OverlayAnchor::NoseBridge:
            return head.noseBridge;
        case OverlayAnchor::ForeheadTop:
            return head.foreheadTop;
        case OverlayAnchor::HeadTop:
            return head.headTop;
        case OverlayAnchor::UpperLip:
            return head.upperLip;
        case OverlayAnchor::Chin:
            return head.chin;
    }
    return head.eyeMidpoint;
}

// A fitted animation value beyond what the model was built with is a fit gone astray: an overlay
// follows it no further than this (the builder's ranges are within +-1).
constexpr float kMaxFollowedValue = 1.5f;
// A stretch never flattens or blows up the mesh, whatever the catalogue and the fit say.
constexpr float kMinStretch = 0.25f;
constexpr float kMaxStretch = 4.f;

}  // namespace

// FORMAT.md: stretch by the follows, rotate x, y, z, add the offset, scale by scale * measure,
// put at the anchor.
Affine modelToHead(const Overlay& overlay, const HeadModel& head,
                   const std::array<float, vision::kAamAnimationUnits>* animation)
{
    const float w = head.faceWidthMetres;
    const float measure =
        overlay.measure == HeadMeasure::Interocular ? w * head.interocularPerFaceWidth : w;
    const float s = overlay.scale * measure;
    Eigen::Vector3f degrees = toVector(overlay.rotationDegrees);
    Eigen::Vector3f offset = toVector(overlay.offset);
    Eigen::Vector3f stretch = Eigen::Vector3f::Ones();
    if (animation != nullptr) {
        for (const OverlayFollow& f : overlay.follows) {
            const float v = std::clamp((*animation)[static_cast<std::size_t>(f.unit)],
                                       -kMaxFollowedValue, kMaxFollowedValue);
            if (!std::isfinite(v))
                continue;
            degrees += v * toVector(f.rotationDegrees);
            offset += v * toVector(f.offset);
            stretch += v * toVector(f.stretch);
        }
        stretch = stretch.cwiseMax(kMinStretch).cwiseMin(kMaxStretch);
    }
    const Eigen::Matrix3f rotation =
        (Eigen::AngleAxisf(vision::toRadians(degrees.z()), Eigen::Vector3f::UnitZ()) *
         Eigen::AngleAxisf(vision::toRadians(degrees.y()), Eigen::Vector3f::UnitY()) *
         Eigen::AngleAxisf(vision::toRadians(degrees.x()), Eigen::Vector3f::UnitX()))
            .toRotationMatrix();
    const std::array<float, 3>& anchor = anchorPoint(head, overlay.anchor);
    return {s * modelToHeadAxes() * rotation * stretch.asDiagonal(),
            modelToHeadAxes() * (toVector(anchor) * w + s * offset)};
}

}  // namespace render::detail
