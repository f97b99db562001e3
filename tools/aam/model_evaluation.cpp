// Leave-persons-out: the check that no evaluated person trained the model, then per image the
// shape residual and the appearance residual at the model's and at the reference resolution.
#include "model_evaluation.hpp"

#include "appearance_warp.hpp"
#include "training_image.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace aam {

namespace {

void shapeResidual(const BuiltModel& model, const FittedImage& image, HeldOutResult& out)
{
    const Similarity2d toMean =
        alignSimilarity(model.shape.mean, image.shape, model.aligned.weights);
    const Eigen::VectorXd delta = asVector(toMean(image.shape)) - asVector(model.shape.mean);
    const Eigen::VectorXd rest =
        delta - model.shape.modes * (model.shape.modes.transpose() * delta);
    const double perVertex = static_cast<double>(image.shape.size());
    const double pxPerUnit = 1.0 / std::hypot(toMean.ax, toMean.ay);
    out.shapeRmsPx = std::sqrt(rest.squaredNorm() / perVertex) * pxPerUnit;
    out.shapeMeanOnlyRmsPx = std::sqrt(delta.squaredNorm() / perVertex) * pxPerUnit;
}

/// The rms over the finite values of a - b.
double rmsOverFinite(const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
    double sum = 0;
    int n = 0;
    for (Eigen::Index i = 0; i < a.size(); ++i) {
        if (!std::isfinite(a(i)) || !std::isfinite(b(i)))
            continue;
        sum += (a(i) - b(i)) * (a(i) - b(i));
        ++n;
    }
    return n ? std::sqrt(sum / n) : 0;
}

void appearanceResiduals(const BuiltModel& model, const AppearanceFrame& reference,
                         const FittedImage& image, HeldOutResult& out)
{
    const Eigen::VectorXd warped = warpToFrame(image.grey, image.shape, model.face, model.frame);
    const AppearanceResidual r = appearanceResidual(model.appearance, warped);
    out.appearanceRms = r.rms / r.alpha;
    out.appearanceMeanOnlyRms = r.rmsMeanOnly / r.alpha;
    // The reconstruction in the image's grey levels, shown at the reference resolution.
    const GainBias g = gainBiasOnto(warped, model.appearance.mean);
    const Eigen::VectorXd delta =
        (g.alpha * warped.array() + g.beta).matrix() - model.appearance.mean;
    const Eigen::VectorXd rebuilt =
        model.appearance.mean +
        model.appearance.modes * (model.appearance.modes.transpose() * delta);
    const Eigen::VectorXd grey = (rebuilt.array() - g.beta) / g.alpha;
    const Eigen::VectorXd atReference = warpToFrame(image.grey, image.shape, model.face, reference);
    out.appearanceRmsAtReference =
        rmsOverFinite(resampledTo(model.frame, grey, reference), atReference);
    out.resolutionLoss = rmsOverFinite(resampledTo(model.frame, warped, reference), atReference);
}

}  // namespace

void refuseSeenPersons(const std::vector<std::string>& trainingPersons,
                       const std::vector<std::string>& heldOutPaths)
{
    for (const std::string& path : heldOutPaths) {
        const std::string person = personOf(path);
        if (std::find(trainingPersons.begin(), trainingPersons.end(), person) !=
            trainingPersons.end()) {
            throw std::invalid_argument(
                "evaluation: " + path + " is of person " + person +
                ", whom the model was built from (--person-specific to allow it, labelled so)");
        }
    }
}

std::vector<HeldOutResult> evaluateHeldOut(const BuiltModel& model,
                                           const std::vector<FittedImage>& heldOut,
                                           bool personSpecific)
{
    if (!personSpecific) {
        std::vector<std::string> paths;
        for (const FittedImage& image : heldOut)
            paths.push_back(image.annotationPath);
        refuseSeenPersons(model.persons, paths);
    }
    const AppearanceFrame reference =
        appearanceFrame(model.face, model.shape.mean, kReferenceResolution);
    std::vector<HeldOutResult> results;
    for (const FittedImage& image : heldOut) {
        HeldOutResult r;
        r.annotationPath = image.annotationPath;
        shapeResidual(model, image, r);
        appearanceResiduals(model, reference, image, r);
        results.push_back(r);
    }
    return results;
}

}  // namespace aam
