// The projection of a posed CANDIDE head (§5), as aam::posedShape draws the training shapes.
#include "head_projection.hpp"

#include "candide_fit.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace headgen {

ProjectedHead projectHead(const vision::CandideMesh& mesh, const std::vector<float>& sigma,
                          const HeadPose2d& pose)
{
    constexpr double kRad = 3.14159265358979323846 / 180.0;
    const Eigen::Matrix3d turn =
        (Eigen::AngleAxisd(pose.pitchDeg * kRad, Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(pose.yawDeg * kRad, Eigen::Vector3d::UnitY()))
            .toRotationMatrix();
    // Clockwise on screen is aam's positive phi: imagePoint maps the model's x axis to
    // (cos phi, sin phi), which points down the image for phi > 0.
    const double a = pose.scale * std::cos(pose.rollDeg * kRad);
    const double b = pose.scale * std::sin(pose.rollDeg * kRad);
    const std::vector<float> tau(pose.animation.begin(), pose.animation.end());
    ProjectedHead head;
    for (const Eigen::Vector3f& v : vision::deformedVertices(mesh, sigma, tau)) {
        const Eigen::Vector3d p = turn * v.cast<double>();
        head.image.push_back(aam::imagePoint(pose.translation, a, b, p.x(), p.y()));
        head.depth.push_back(p.z());
    }
    return head;
}

}  // namespace headgen
