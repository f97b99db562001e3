// Training shapes synthesized from a CANDIDE fit (§5, 5.3.1): pose and expression at random, the
// fit's projection.
#include "shape_synthesis.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>

namespace aam {

Shape2d posedShape(const vision::CandideMesh& face, const CandideFit& fit, double yaw, double pitch,
                   const std::vector<float>& tau)
{
    const Eigen::Matrix3d turn = (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
                                  Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()))
                                     .toRotationMatrix();
    Shape2d shape;
    shape.reserve(face.vertices.size());
    for (const Eigen::Vector3f& v : vision::deformedVertices(face, fit.sigma, tau)) {
        const Eigen::Vector3d p = turn * v.cast<double>();
        shape.push_back(imagePoint(fit.translation, fit.a, fit.b, p.x(), p.y()));
    }
    return shape;
}

std::vector<Shape2d> synthesizeShapes(const vision::CandideMesh& face, const CandideFit& fit,
                                      const SynthesisOptions& options)
{
    if (face.animationUnits.size() != kAnimationRange.size()) {
        throw std::invalid_argument(
            "shape synthesis: the mesh has " + std::to_string(face.animationUnits.size()) +
            " animation units, the ranges are for " + std::to_string(kAnimationRange.size()));
    }
    constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;
    std::mt19937 random(options.seed);
    std::uniform_real_distribution<double> yaw(-options.maxYawDegrees * kRadiansPerDegree,
                                               options.maxYawDegrees * kRadiansPerDegree);
    std::uniform_real_distribution<double> pitch(-options.maxPitchDegrees * kRadiansPerDegree,
                                                 options.maxPitchDegrees * kRadiansPerDegree);
    std::vector<Shape2d> shapes;
    std::vector<float> tau(kAnimationRange.size());
    for (int i = 0; i < options.shapesPerImage; ++i) {
        for (std::size_t j = 0; j < tau.size(); ++j) {
            tau[j] = std::uniform_real_distribution<float>(kAnimationRange[j].low,
                                                           kAnimationRange[j].high)(random);
        }
        const double y = yaw(random);
        shapes.push_back(posedShape(face, fit, y, pitch(random), tau));
    }
    return shapes;
}

Eigen::VectorXd asVector(const Shape2d& shape)
{
    Eigen::VectorXd v(2 * static_cast<Eigen::Index>(shape.size()));
    for (std::size_t k = 0; k < shape.size(); ++k)
        v.segment<2>(2 * static_cast<Eigen::Index>(k)) = shape[k];
    return v;
}

}  // namespace aam
