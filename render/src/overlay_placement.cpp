#include "overlay_placement.hpp"

#include "vision/geometry.hpp"

#include <Eigen/Geometry>

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
    }
    return head.eyeMidpoint;
}

}  // namespace

// FORMAT.md: rotate x, y, z, add the offset, scale by scale * measure, put at the anchor.
Affine modelToHead(const Overlay& overlay, const HeadModel& head)
{
    const float w = head.faceWidthMetres;
    const float measure =
        overlay.measure == HeadMeasure::Interocular ? w * head.interocularPerFaceWidth : w;
    const float s = overlay.scale * measure;
    const Eigen::Matrix3f rotation =
        (Eigen::AngleAxisf(vision::toRadians(overlay.rotationDegrees[2]),
                           Eigen::Vector3f::UnitZ()) *
         Eigen::AngleAxisf(vision::toRadians(overlay.rotationDegrees[1]),
                           Eigen::Vector3f::UnitY()) *
         Eigen::AngleAxisf(vision::toRadians(overlay.rotationDegrees[0]), Eigen::Vector3f::UnitX()))
            .toRotationMatrix();
    const std::array<float, 3>& anchor = anchorPoint(head, overlay.anchor);
    return {s * modelToHeadAxes() * rotation,
            modelToHeadAxes() * (toVector(anchor) * w + s * toVector(overlay.offset))};
}

}  // namespace render::detail
