#pragma once
// The shapes aligned before their PCA (§5, dissertation 5.3.1 after Cootes et al.): weighted
// Procrustes, so the shape modes capture shape, not scale, translation or roll.
//  - eq. 45: vertex k's weight w_k = (sum_j V(R_kj))^-1, R_kj the distance between vertices k and
//  j,
//    V its variance over the set: steady vertices count more;
//  - eqs. 46-53: the similarity (ax, ay) = s (cos phi, sin phi), t taking one shape onto another in
//    weighted least squares, a 4x4 linear system;
//  - the iteration: every shape aligned to the first; then repeatedly the mean, the mean aligned to
//    the first shape, every shape aligned to the mean, until the mean stops moving.

#include "shape_synthesis.hpp"

#include <Eigen/Core>
#include <vector>

namespace aam {

/// Eq. 45 over `shapes` (all of one size).
Eigen::VectorXd vertexWeights(const std::vector<Shape2d>& shapes);

/// p -> (ax x - ay y + tx, ay x + ax y + ty).
struct Similarity2d {
    double ax = 1, ay = 0, tx = 0, ty = 0;
    Eigen::Vector2d operator()(const Eigen::Vector2d& p) const;
    Shape2d operator()(const Shape2d& shape) const;
};

/// Eq. 47: the similarity taking `moving` onto `target` with vertex weights `w`.
Similarity2d alignSimilarity(const Shape2d& target, const Shape2d& moving,
                             const Eigen::VectorXd& w);

struct AlignedShapes {
    std::vector<Shape2d> shapes;  ///< in the first shape's (or the reference's) frame
    Shape2d mean;
    Eigen::VectorXd weights;
    int iterations = 0;
};

struct AlignmentOptions {
    int maxIterations = 100;
    double tolerance = 1e-9;  ///< the mean's rms move per vertex, over its rms size
    /// The frame to align into, in place of the first shape (the text's choice); aam-build gives
    /// the first image's frontal, neutral shape, so the mean is upright and not turned as a
    /// random pose would turn it.
    const Shape2d* reference = nullptr;
};

/// The iterated weighted Procrustes alignment of `shapes` (at least two, of one size, at least two
/// vertices); throws std::invalid_argument with one line otherwise.
AlignedShapes alignShapes(const std::vector<Shape2d>& shapes, const AlignmentOptions& options = {});

}  // namespace aam
