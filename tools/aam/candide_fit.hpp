#pragma once
// The per-image CANDIDE fit of §5 (dissertation 5.3.1, eq. 44): from the marked points of one
// frontal image, the translation (tx, ty), scale and roll as (a, b) = (k cos phi, k sin phi), and
// the shape (sigma) and animation (tau) parameters, by linear least squares on the orthographic
// projection (z ignored).
//
// Eq. 44 as printed adds the units' displacements to the image unscaled and unrotated, i.e. it
// solves for k R(phi) sigma as if it were sigma: exact only at k = 1, phi = 0. We solve it so for a
// start, then alternate the two problems that are each linear: the similarity (t, a, b) with the
// units fixed, and the units with the similarity fixed (their displacements scaled and rotated by
// it), a few rounds. Where the text is silent: a weak prior on the unit parameters (ridge) keeps
// the units the marked points cannot see (a unit acting only on unmarked vertices) at 0.

#include "annotation_schemes.hpp"
#include "vision/candide_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace aam {

struct CandideFitOptions {
    /// Marking error over a unit parameter's spread, in model units per unit: the ridge's weight
    /// is (k * this)^2 per parameter. CANDIDE's units move vertices by ~0.1-0.25 model units per
    /// unit parameter; marking is good to about 0.02 model units (1-2 px on an IMM face).
    double priorWeight = 0.02;
    int rounds = 10;  ///< alternations after the eq. 44 start
};

struct CandideFit {
    Eigen::Vector2d translation = Eigen::Vector2d::Zero();  ///< image pixels
    double a = 1;                                           ///< k cos phi
    double b = 0;                                           ///< k sin phi
    std::vector<float> sigma;                               ///< one per shape unit of the mesh
    std::vector<float> tau;                                 ///< one per animation unit of the mesh
    double rmsResidualPx = 0;                               ///< over the marked points
    double maxResidualPx = 0;

    double scale() const;        ///< k, pixels per model unit
    double rollRadians() const;  ///< phi, counter-clockwise in the image as seen (y down)
};

/// Fits `face` to the marked points (at least as many coordinates as unknowns, 4 + units);
/// throws std::invalid_argument with one line when there are too few.
CandideFit fitCandide(const vision::CandideMesh& face, const std::vector<MarkedPoint>& marked,
                      const CandideFitOptions& options = {});

/// Every vertex of `face` in the image under `fit` (the orthographic projection of eq. 44).
std::vector<Eigen::Vector2d> projectedVertices(const vision::CandideMesh& face,
                                               const CandideFit& fit);

/// The image point of model point (x, y) under the similarity (t, a, b): CANDIDE's y is up, the
/// image's down.
Eigen::Vector2d imagePoint(const Eigen::Vector2d& t, double a, double b, double x, double y);

}  // namespace aam
