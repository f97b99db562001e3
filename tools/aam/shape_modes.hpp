#pragma once
// The 2D shape model of §5 (dissertation 5.3.1, eq. 42: s = s0 + sum p_i s_i): the aligned
// shapes' mean and their principal components, from the 2n x 2n covariance matrix of the shapes
// less the mean. Kept: the fewest modes whose variance reaches `varianceFraction` of the total
// (the text is silent; 0.98 is Cootes et al.'s usual choice, and the tests and `aam-build shapes`
// report how many that is).

#include "shape_alignment.hpp"

#include <Eigen/Core>

namespace aam {

struct ShapeModes {
    Shape2d mean;               ///< s0
    Eigen::MatrixXd modes;      ///< 2n x m, orthonormal columns s_i, (x0 y0 x1 y1 ...) as eq. 41
    Eigen::VectorXd variances;  ///< of each kept mode, largest first
    double totalVariance = 0;   ///< of all modes
};

/// Throws std::invalid_argument (one line) for a fraction outside (0, 1].
ShapeModes shapeModes(const AlignedShapes& aligned, double varianceFraction = 0.98);

}  // namespace aam
