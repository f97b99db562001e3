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

Eigen::Matrix3f headRotationFromAngles(float yawDegrees, float pitchDegrees,
                                       float rollDegrees) noexcept
{
    const float yaw = toRadians(yawDegrees), pitch = toRadians(pitchDegrees);
    const float roll = toRadians(rollDegrees);
    Eigen::Matrix3f rz, rx, ry;
    rz << std::cos(roll), -std::sin(roll), 0.f, std::sin(roll), std::cos(roll), 0.f, 0.f, 0.f, 1.f;
    rx << 1.f, 0.f, 0.f, 0.f, std::cos(pitch), -std::sin(pitch), 0.f, std::sin(pitch),
        std::cos(pitch);
    ry << std::cos(yaw), 0.f, std::sin(yaw), 0.f, 1.f, 0.f, -std::sin(yaw), 0.f, std::cos(yaw);
    const Eigen::Matrix3f d = Eigen::Vector3f(1.f, -1.f, -1.f).asDiagonal();
    return rz * d * rx * ry * d;
}

HeadPose headPoseFromFit(const FaceFit& fit, const CameraModel& camera,
                         float faceWidthMetres) noexcept
{
    HeadPose pose;
    pose.rotation = headRotationFromAngles(fit.yawDegrees, fit.pitchDegrees, fit.rollDegrees);
    const float f = camera.focalPixels();
    const float depth = fit.faceSize > 0.f ? f * faceWidthMetres / fit.faceSize : 1.f;
    const float cx = 0.5f * static_cast<float>(camera.imageSize.width);
    const float cy = 0.5f * static_cast<float>(camera.imageSize.height);
    pose.translation = Eigen::Vector3f((fit.eyeMidpoint.x - cx) * depth / f,
                                       (fit.eyeMidpoint.y - cy) * depth / f, depth);
    return pose;
}

}  // namespace vision
