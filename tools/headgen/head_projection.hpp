#pragma once
// Where a CANDIDE head lands in the image for a known pose (§5: the 3D model whose projection
// constrains the AAM's 2D shape). The projection is the one the model builder synthesizes its
// training shapes with (aam::posedShape): turn the deformed mesh by pitch and yaw, drop z
// (orthographic), then scale, roll and translate in the image. The depth kept beside each point
// orders the triangles when the head is drawn.
//
// Conventions (the truth file's): yaw turns the face to its left (the nose moves to the image's
// right), pitch turns it down, roll is clockwise on screen (y down) as the face tracker's;
// `scale` is pixels per CANDIDE model unit; `translation` is where the model origin lands.

#include "vision/candide_mesh.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace headgen {

/// The six tracked animation units' values, in vision::kTrackedAnimationUnits order.
using AnimationValues = std::array<float, 6>;

struct HeadPose2d {
    double yawDeg = 0, pitchDeg = 0, rollDeg = 0;
    double scale = 100;  ///< image pixels per model unit
    Eigen::Vector2d translation = Eigen::Vector2d::Zero();
    AnimationValues animation{};
};

struct ProjectedHead {
    std::vector<Eigen::Vector2d> image;  ///< every mesh vertex, image pixels
    std::vector<double> depth;           ///< towards the camera, model units
};

/// The mesh with the person's shape `sigma` (one per shape unit) posed by `pose`.
ProjectedHead projectHead(const vision::CandideMesh& mesh, const std::vector<float>& sigma,
                          const HeadPose2d& pose);

}  // namespace headgen
