// The shape model's PCA (§5, 5.3.1): covariance of the aligned shapes, its eigenvectors, the
// modes kept to a variance fraction.
#include "shape_modes.hpp"

#include <Eigen/Eigenvalues>
#include <stdexcept>
#include <string>

namespace aam {

namespace {

Eigen::MatrixXd covarianceAbout(const std::vector<Shape2d>& shapes, const Eigen::VectorXd& mean)
{
    Eigen::MatrixXd deltas(mean.size(), static_cast<Eigen::Index>(shapes.size()));
    for (std::size_t i = 0; i < shapes.size(); ++i)
        deltas.col(static_cast<Eigen::Index>(i)) = asVector(shapes[i]) - mean;
    return deltas * deltas.transpose() / static_cast<double>(shapes.size());
}

}  // namespace

ShapeModes shapeModes(const AlignedShapes& aligned, double varianceFraction)
{
    if (!(varianceFraction > 0 && varianceFraction <= 1)) {
        throw std::invalid_argument("shape modes: variance fraction " +
                                    std::to_string(varianceFraction) + " is not in (0, 1]");
    }
    const Eigen::VectorXd mean = asVector(aligned.mean);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> pca(covarianceAbout(aligned.shapes, mean));
    // Eigen sorts eigenvalues ascending: walk from the largest.
    const Eigen::VectorXd values = pca.eigenvalues().reverse().cwiseMax(0.0);
    ShapeModes out{aligned.mean, {}, {}, values.sum()};
    Eigen::Index kept = 0;
    double reached = 0;
    while (kept < values.size() && (kept == 0 || reached < varianceFraction * out.totalVariance))
        reached += values(kept++);
    out.modes = pca.eigenvectors().rowwise().reverse().leftCols(kept);
    out.variances = values.head(kept);
    return out;
}

}  // namespace aam
