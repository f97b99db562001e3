#include "vision/head_pose.hpp"

#include "vision/geometry.hpp"

#include <cmath>

namespace vision {

float CameraModel::focalPixels() const noexcept
{
    const float halfFov = toRadians(0.5f * verticalFovDegrees);
    return 0.5f * static_cast<float>(imageSize.height) / std::tan(halfFov);
}

HeadPose headPoseFromFace(const TrackedFace& face, const CameraModel& camera,
                          float faceWidthMetres) noexcept
{
    const float roll = toRadians(face.rollDegrees);
    const float c = std::cos(roll);
    const float s = std::sin(roll);
    HeadPose pose;
    // Positive roll turns +x towards +y (clockwise on screen, y down): a rotation about +z.
    pose.rotation << c, -s, 0.f, s, c, 0.f, 0.f, 0.f, 1.f;

    const float f = camera.focalPixels();
    const float depth = face.size > 0.f ? f * faceWidthMetres / face.size : 1.f;
    // The face's up axis is the head's -y rotated by the roll: (sin, -cos) on screen.
    const float above = kEyeMidpointAboveBoxCentre * face.size;
    const float u = face.centre.x + above * s;
    const float v = face.centre.y - above * c;
    const float cx = 0.5f * static_cast<float>(camera.imageSize.width);
    const float cy = 0.5f * static_cast<float>(camera.imageSize.height);
    pose.translation = Eigen::Vector3f((u - cx) * depth / f, (v - cy) * depth / f, depth);
    return pose;
}

}  // namespace vision
