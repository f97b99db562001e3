// The appearance model: eq. 57's gain and bias, the iterated mean, the Gram-matrix PCA.
#include "appearance_modes.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

namespace aam {

namespace {

constexpr int kMaxIterations = 50;
constexpr double kTolerance = 1e-9;  // the mean's rms change per pixel (its std is 1)

Eigen::VectorXd matchedTo(const Eigen::VectorXd& image, const Eigen::VectorXd& mean)
{
    const GainBias g = gainBiasOnto(image, mean);
    return g.alpha * image.array() + g.beta;
}

/// The iteration to the mean appearance; returns the images matched to it.
std::vector<Eigen::VectorXd> iterateMean(const std::vector<Eigen::VectorXd>& warped,
                                         AppearanceModes& model)
{
    model.mean = standardised(warped.front());
    std::vector<Eigen::VectorXd> matched(warped.size());
    for (model.iterations = 1; model.iterations <= kMaxIterations; ++model.iterations) {
        Eigen::VectorXd sum = Eigen::VectorXd::Zero(model.mean.size());
        for (std::size_t i = 0; i < warped.size(); ++i)
            sum += matched[i] = matchedTo(warped[i], model.mean);
        const Eigen::VectorXd next = standardised(sum);
        const double moved =
            (next - model.mean).norm() / std::sqrt(static_cast<double>(next.size()));
        model.mean = next;
        if (moved < kTolerance)
            break;
    }
    for (std::size_t i = 0; i < warped.size(); ++i)
        matched[i] = matchedTo(warped[i], model.mean);
    return matched;
}

void principalModes(const std::vector<Eigen::VectorXd>& matched, double fraction,
                    AppearanceModes& model)
{
    Eigen::MatrixXd deltas(model.mean.size(), static_cast<Eigen::Index>(matched.size()));
    for (std::size_t i = 0; i < matched.size(); ++i)
        deltas.col(static_cast<Eigen::Index>(i)) = matched[i] - model.mean;
    const double n = static_cast<double>(matched.size());
    // Eigenvectors v of the Gram matrix D'D/n give the covariance's, D v, with the same
    // eigenvalues.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> pca(deltas.transpose() * deltas / n);
    const Eigen::VectorXd values = pca.eigenvalues().reverse().cwiseMax(0.0);
    model.totalVariance = values.sum();
    Eigen::Index kept = 0;
    double reached = 0;
    while (kept < values.size() && values(kept) > 1e-12 * model.totalVariance &&
           (kept == 0 || reached < fraction * model.totalVariance)) {
        reached += values(kept++);
    }
    model.modes = deltas * pca.eigenvectors().rowwise().reverse().leftCols(kept);
    model.modes.colwise().normalize();
    model.variances = values.head(kept);
}

}  // namespace

GainBias gainBiasOnto(const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
    if (a.size() != b.size() || a.size() == 0)
        throw std::invalid_argument("gain and bias: images of different sizes");
    const double n = static_cast<double>(a.size()), meanA = a.mean(), meanB = b.mean();
    const double spread = a.squaredNorm() - n * meanA * meanA;
    if (!(spread > 1e-9 * n))
        throw std::invalid_argument("gain and bias: a flat image has no contrast to match");
    GainBias g;
    g.alpha = (a.dot(b) - n * meanA * meanB) / spread;
    g.beta = meanB - g.alpha * meanA;
    return g;
}

Eigen::VectorXd standardised(const Eigen::VectorXd& v)
{
    const Eigen::VectorXd centred = v.array() - v.mean();
    const double sd = std::sqrt(centred.squaredNorm() / static_cast<double>(v.size()));
    if (!(sd > 1e-9))
        throw std::invalid_argument("appearance: a flat image has no contrast to normalise");
    return centred / sd;
}

AppearanceModes appearanceModes(const std::vector<Eigen::VectorXd>& warped, double varianceFraction)
{
    if (!(varianceFraction > 0 && varianceFraction <= 1)) {
        throw std::invalid_argument("appearance modes: variance fraction " +
                                    std::to_string(varianceFraction) + " is not in (0, 1]");
    }
    if (warped.size() < 2)
        throw std::invalid_argument("appearance modes: " + std::to_string(warped.size()) +
                                    " images; at least 2 needed");
    for (const auto& w : warped) {
        if (w.size() != warped.front().size())
            throw std::invalid_argument("appearance modes: images of different sizes");
    }
    AppearanceModes model;
    principalModes(iterateMean(warped, model), varianceFraction, model);
    return model;
}

AppearanceResidual appearanceResidual(const AppearanceModes& model, const Eigen::VectorXd& warped)
{
    const GainBias g = gainBiasOnto(warped, model.mean);
    const Eigen::VectorXd delta = (g.alpha * warped.array() + g.beta).matrix() - model.mean;
    const Eigen::VectorXd rest = delta - model.modes * (model.modes.transpose() * delta);
    const double n = static_cast<double>(delta.size());
    return {std::sqrt(rest.squaredNorm() / n), std::sqrt(delta.squaredNorm() / n), g.alpha};
}

}  // namespace aam
