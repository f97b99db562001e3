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

// ---- the full pose of an AAM fit (§5.3) -----------------------------------------------------

TEST(HeadPoseFromFit, UnturnedFitIsTheBoxPoseOfTheSameSizeAndEyes)
{
    const CameraModel camera{{640, 480}, 50.f};
    TrackedFace face;
    face.centre = {300.f, 200.f};
    face.size = 120.f;
    const HeadPose box = headPoseFromFace(face, camera, 0.15f);
    vision::FaceFit fit;
    fit.faceSize = 120.f;
    fit.eyeMidpoint = {300.f, 200.f - vision::kEyeMidpointAboveBoxCentre * 120.f};
    const HeadPose fitted = headPoseFromFit(fit, camera, 0.15f);
    EXPECT_TRUE(fitted.rotation.isApprox(Eigen::Matrix3f::Identity(), 1e-6f));
    EXPECT_TRUE(fitted.translation.isApprox(box.translation, 1e-5f));
}

TEST(HeadPoseFromFit, RotationIsTheFitsProjectionTurnedIntoTheHeadFrame)
{
    // The fit projects a CANDIDE point g (x to the person's left, y up, z towards the camera) as
    // Roll(roll) * Flip * Rx(pitch) * Ry(yaw) * g (aam_fitter.hpp); the same point in the head
    // frame is (g.x, -g.y, -g.z), and the pose's rotation must put it where the fit does.
    const float angles[][3] = {{20.f, 0.f, 0.f}, {0.f, 15.f, 0.f}, {0.f, 0.f, 10.f},
                               {-25.f, 10.f, -7.f}, {30.f, -12.f, 18.f}};
    const Eigen::Vector3f points[] = {{0.3f, 0.2f, 0.5f}, {-0.4f, -0.6f, 0.1f}, {0.f, 0.f, 1.f}};
    for (const auto& a : angles) {
        const float yaw = a[0] * kPi / 180.f, pitch = a[1] * kPi / 180.f,
                    roll = a[2] * kPi / 180.f;
        Eigen::Matrix3f rx, ry;
        rx << 1, 0, 0, 0, std::cos(pitch), -std::sin(pitch), 0, std::sin(pitch), std::cos(pitch);
        ry << std::cos(yaw), 0, std::sin(yaw), 0, 1, 0, -std::sin(yaw), 0, std::cos(yaw);
        Eigen::Matrix<float, 2, 3> rollFlip;
        rollFlip << std::cos(roll), std::sin(roll), 0, std::sin(roll), -std::cos(roll), 0;
        const Eigen::Matrix3f r = vision::headRotationFromAngles(a[0], a[1], a[2]);
        EXPECT_TRUE((r * r.transpose()).isApprox(Eigen::Matrix3f::Identity(), 1e-5f));
        EXPECT_NEAR(r.determinant(), 1.f, 1e-5f);
        for (const Eigen::Vector3f& g : points) {
            const Eigen::Vector2f fitted = rollFlip * rx * ry * g;
            const Eigen::Vector3f head(g.x(), -g.y(), -g.z());
            const Eigen::Vector3f camera = r * head;
            EXPECT_NEAR(camera.x(), fitted.x(), 1e-5f) << a[0] << " " << a[1] << " " << a[2];
            EXPECT_NEAR(camera.y(), fitted.y(), 1e-5f) << a[0] << " " << a[1] << " " << a[2];
        }
    }
}

TEST(HeadPoseFromFit, YawTurnsTheNoseToImageRightAndPitchTurnsItDown)
{
    const Eigen::Vector3f nose(0.f, 0.f, -1.f);  // head frame: out of the face, at the camera
    const Eigen::Vector3f turned = vision::headRotationFromAngles(30.f, 0.f, 0.f) * nose;
    EXPECT_GT(turned.x(), 0.4f);
    EXPECT_NEAR(turned.y(), 0.f, 1e-6f);
    const Eigen::Vector3f down = vision::headRotationFromAngles(0.f, 20.f, 0.f) * nose;
    EXPECT_GT(down.y(), 0.3f);
    EXPECT_NEAR(down.x(), 0.f, 1e-6f);
}

TEST(HeadPoseFromFit, DepthFollowsTheFittedSizeAndTheEyesStayWhereTheFitPutThem)
{
    const CameraModel camera{{640, 480}, 50.f};
    vision::FaceFit fit;
    fit.yawDegrees = 25.f;
    fit.pitchDegrees = -10.f;
    fit.rollDegrees = 5.f;
    fit.eyeMidpoint = {400.f, 180.f};
    fit.faceSize = 100.f;
    const HeadPose near = headPoseFromFit(fit, camera, 0.15f);
    fit.faceSize = 50.f;
    const HeadPose far = headPoseFromFit(fit, camera, 0.15f);
    EXPECT_NEAR(far.translation.z(), 2.f * near.translation.z(), 1e-4f);
    for (const HeadPose& pose : {near, far}) {
        const vision::Point2f eyes = project(pose.translation, camera);
        EXPECT_NEAR(eyes.x, 400.f, 1e-2f);
        EXPECT_NEAR(eyes.y, 180.f, 1e-2f);
    }
    fit.faceSize = 0.f;
    EXPECT_NEAR(headPoseFromFit(fit, camera).translation.z(), 1.f, 1e-6f);
}

}  // namespace

