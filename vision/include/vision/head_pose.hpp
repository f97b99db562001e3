#pragma once
// HeadPose: where a head is and how it is turned, in the camera's 3D frame, for placing 3D
// overlays (hats, glasses) on a tracked face (§6). With an AAM fit that holds (§5.3), the full
// 6-DoF pose comes from it (headPoseFromFit); otherwise from the face box alone
// (headPoseFromFace): position, scale and roll, yaw and pitch 0.
//
// Frames (all right-handed, metres):
//  - camera frame (as OpenCV): origin at the camera's centre of projection, x towards image right,
//    y towards image bottom, z forward along the optical axis (into the scene). A point (X, Y, Z)
//    projects to the pixel (f X / Z + cx, f Y / Z + cy) of the unmirrored camera image.
//  - head frame: origin at the eye midpoint (between the pupils, at the depth of the eyes); for a
//    face looking straight at the camera, unrolled and unmirrored, its axes are the camera's:
//    x towards image right (the person's left), y down (towards the chin), z into the head (away
//    from the camera).
// A head point p maps to the camera frame as rotation * p + translation.

#include "vision/face_fit.hpp"
#include "vision/face_tracker.hpp"
#include "vision/image.hpp"

#include <Eigen/Core>

namespace vision {

/// A pinhole camera without distortion, principal point at the image centre, square pixels.
struct CameraModel {
    Size imageSize{};                 ///< the image the face coordinates are in
    float verticalFovDegrees = 50.f;  ///< full vertical field of view

    /// Focal length in pixels: (height / 2) / tan(fov / 2).
    float focalPixels() const noexcept;
};

/// Rigid transform from the head frame to the camera frame (see the file comment).
struct HeadPose {
    Eigen::Matrix3f rotation = Eigen::Matrix3f::Identity();
    Eigen::Vector3f translation = Eigen::Vector3f::Zero();  ///< the eye midpoint, camera frame
};

/// Where the eye midpoint lies in a tracker face box: above the box centre by this fraction of the
/// box side, along the face's rolled up axis (the Viola-Jones frontal-face box puts the eyes at
/// about 0.38 of its height from the top).
inline constexpr float kEyeMidpointAboveBoxCentre = 0.12f;

/// The pose of the head of `face` (coordinates in `camera.imageSize`): yaw and pitch zero, roll
/// `face.rollDegrees` (clockwise on screen, i.e. about the camera's +z), depth from the box side
/// taken as the face width: Z = f * faceWidthMetres / face.size. The translation is the eye
/// midpoint (see kEyeMidpointAboveBoxCentre) back-projected to that depth. A face without a size
/// (size <= 0) is placed at a depth of 1 m.
HeadPose headPoseFromFace(const TrackedFace& face, const CameraModel& camera,
                          float faceWidthMetres = 0.15f) noexcept;

/// The rotation of a head turned by yaw, pitch and roll as the AAM fit reports them (AamHead:
/// image = t + scale * Roll(roll) * Flip * Rx(pitch) * Ry(yaw) * g, g in CANDIDE's frame: x to the
/// person's left, y up, z towards the camera): the head frame is CANDIDE's turned half-way about
/// x (D = diag(1, -1, -1)), so the rotation is Rz(roll) * D * Rx(pitch) * Ry(yaw) * D. Zero angles
/// give the identity; positive yaw turns the nose towards image right, positive pitch turns it
/// down, positive roll is clockwise on screen as in headPoseFromFace.
Eigen::Matrix3f headRotationFromAngles(float yawDegrees, float pitchDegrees,
                                       float rollDegrees) noexcept;

/// The full pose of a fitted head (the fit in `camera.imageSize` coordinates): the rotation of
/// its yaw, pitch and roll (headRotationFromAngles), the eye midpoint back-projected from the
/// fitted eye corners' midpoint at the depth of headPoseFromFace for a box of side
/// fit.faceSize (the tracker box the fitted mesh corresponds to), so a face switching between the
/// fit and the 2D pose stays where it is. Meaningful only when fit.ok(); a fit without a size is
/// placed at 1 m.
HeadPose headPoseFromFit(const FaceFit& fit, const CameraModel& camera,
                         float faceWidthMetres = 0.15f) noexcept;

}  // namespace vision
