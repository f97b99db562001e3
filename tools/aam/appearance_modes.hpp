#pragma once
// The appearance model of §5 (dissertation 5.3.1, eqs. 43 and 54-59, after Cootes et al.): the
// warped training images' brightness and contrast matched, the mean iterated, and its PCA.
//  - eq. 57: the gain and bias (alpha, beta) taking image A onto image B in least squares;
//  - eq. 59: with B of zero mean, A' = alpha (A - mean(A)): A matched to the mean;
//  - the iteration: the first image, of zero mean and unit variance, is the first estimate; then
//    each image matched to the estimate, the estimate their mean, made zero-mean unit-variance
//    again (else it would shrink towards 0 round after round), until it stops moving;
//  - the PCA of the matched images less the mean, kept to a variance fraction. With fewer images
//    than pixels the modes come from the images' small Gram matrix (the same eigenvectors).

#include <Eigen/Core>
#include <vector>

namespace aam {

struct GainBias {
    double alpha = 1, beta = 0;
};

/// Eq. 57: alpha, beta minimising sum (alpha A + beta - B)^2. Throws std::invalid_argument (one
/// line) for a flat A (no contrast to match) or vectors of different sizes.
GainBias gainBiasOnto(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

/// `v` less its mean, scaled to unit variance per value.
Eigen::VectorXd standardised(const Eigen::VectorXd& v);

struct AppearanceModes {
    Eigen::VectorXd mean;       ///< A0: zero mean, unit variance
    Eigen::MatrixXd modes;      ///< pixels x m, orthonormal columns A_i
    Eigen::VectorXd variances;  ///< of each kept mode, largest first
    double totalVariance = 0;   ///< of all modes
    int iterations = 0;         ///< of the mean's estimate
};

/// The model of the warped training images (at least two, one size); throws std::invalid_argument
/// (one line) for fewer, for a fraction outside (0, 1] or for a flat image.
AppearanceModes appearanceModes(const std::vector<Eigen::VectorXd>& warped,
                                double varianceFraction = 0.95);

struct AppearanceResidual {
    double rms = 0;          ///< of the image matched to the mean, less its projection on the modes
    double rmsMeanOnly = 0;  ///< the same with no modes
    double alpha = 1;  ///< the gain that matched it: rms / alpha is in the image's grey levels
};

/// How well `model` reconstructs the warped image `warped` (normalised units: the mean's
/// standard deviation is 1).
AppearanceResidual appearanceResidual(const AppearanceModes& model, const Eigen::VectorXd& warped);

}  // namespace aam
