#include "vision/head_pose.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

namespace {

using vision::CameraModel;
using vision::HeadPose;
using vision::TrackedFace;

constexpr float kPi = 3.14159265358979f;

// Projects a camera-frame point to the image, as the file comment of head_pose.hpp defines it.
vision::Point2f project(const Eigen::Vector3f& p, const CameraModel& camera)
{
    const float f = camera.focalPixels();
    return {f * p.x() / p.z() + 0.5f * static_cast<float>(camera.imageSize.width),
            f * p.y() / p.z() + 0.5f * static_cast<float>(camera.imageSize.height)};
}

TEST(HeadPose, FocalLengthFollowsTheVerticalFieldOfView)
{
    const CameraModel camera{{640, 480}, 90.f};
    EXPECT_NEAR(camera.focalPixels(), 240.f, 1e-3f);
}

TEST(HeadPose, UprightFaceEyesAboveTheBoxCentreAtTheDepthOfItsWidth)
{
    const CameraModel camera{{640, 480}, 50.f};
    TrackedFace face;
    face.centre = {400.f, 200.f};
    face.size = 120.f;
    const HeadPose pose = headPoseFromFace(face, camera, 0.15f);
    EXPECT_TRUE(pose.rotation.isApprox(Eigen::Matrix3f::Identity()));
    EXPECT_NEAR(pose.translation.z(), camera.focalPixels() * 0.15f / 120.f, 1e-5f);
    const vision::Point2f eyes = project(pose.translation, camera);
    EXPECT_NEAR(eyes.x, 400.f, 1e-3f);
    EXPECT_NEAR(eyes.y, 200.f - vision::kEyeMidpointAboveBoxCentre * 120.f, 1e-3f);
    // A face half as big is twice as far.
    face.size = 60.f;
    EXPECT_NEAR(headPoseFromFace(face, camera, 0.15f).translation.z(), 2.f * pose.translation.z(),
                1e-5f);
}

TEST(HeadPose, RollTurnsTheHeadClockwiseOnScreenAndMovesTheEyesAlongItsUpAxis)
{
    const CameraModel camera{{640, 480}, 50.f};
    TrackedFace face;
    face.centre = {320.f, 240.f};
    face.size = 100.f;
    face.rollDegrees = 90.f;  // face lying on its side: its top points to image right
    const HeadPose pose = headPoseFromFace(face, camera);
    // The head's x axis (towards image right when upright) now points down the image.
    const Eigen::Vector3f x = pose.rotation * Eigen::Vector3f::UnitX();
    EXPECT_NEAR(x.x(), 0.f, 1e-5f);
    EXPECT_NEAR(x.y(), 1.f, 1e-5f);
    EXPECT_NEAR(pose.rotation.determinant(), 1.f, 1e-5f);
    const vision::Point2f eyes = project(pose.translation, camera);
    EXPECT_NEAR(eyes.x, 320.f + vision::kEyeMidpointAboveBoxCentre * 100.f, 1e-3f);
    EXPECT_NEAR(eyes.y, 240.f, 1e-3f);

    face.rollDegrees = 30.f;
    const HeadPose p30 = headPoseFromFace(face, camera);
    const Eigen::Vector3f x30 = p30.rotation * Eigen::Vector3f::UnitX();
    EXPECT_NEAR(std::atan2(x30.y(), x30.x()), 30.f * kPi / 180.f, 1e-5f);
}

TEST(HeadPose, HeadPointsProjectWhereTheFaceIs)
{
    // A point of the head frame one face width to the right of the eyes lands one box side to
    // the right of the eye midpoint in the image (same depth).
    const CameraModel camera{{1280, 720}, 45.f};
    TrackedFace face;
    face.centre = {500.f, 300.f};
    face.size = 200.f;
    const HeadPose pose = headPoseFromFace(face, camera, 0.15f);
    const vision::Point2f a = project(pose.translation, camera);
    const vision::Point2f b =
        project(pose.rotation * Eigen::Vector3f(0.15f, 0.f, 0.f) + pose.translation, camera);
    EXPECT_NEAR(b.x - a.x, 200.f, 1e-2f);
    EXPECT_NEAR(b.y - a.y, 0.f, 1e-3f);
}

TEST(HeadPose, FaceWithoutSizeIsOneMetreAway)
{
    const CameraModel camera{{640, 480}, 50.f};
    TrackedFace face;
    face.centre = {320.f, 240.f};
    EXPECT_NEAR(headPoseFromFace(face, camera).translation.z(), 1.f, 1e-6f);
}

}  // namespace
