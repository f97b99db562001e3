// AamFitter: the fit of §5 (dissertation 5.3.2-5.3.4), one iteration as the text's steps: warp
// the image by the current shape, the error image against the mean appearance under the current
// gain and bias, its dot products with the steepest-descent images (the 2D term's gradient; its
// Hessian was precomputed), the 3D term's Jacobian and Hessian at the current head, the combined
// system solved, and the increment composed (2D) or added (gain, bias, head).
//
// Where the text is silent, and why:
//  - The 3D term is measured in the mean shape's frame pixels (image pixels over N's scale), so K
//    does not depend on how large the face is in the image; its value was chosen on the synthetic
//    tests (tests/vision/aam_fitter_test.cpp): large enough that the 2D shape follows a head
//    turn, small enough that the appearance still decides where the mesh sits.
//  - Gain and bias are fitted on the template side (the mean appearance made brighter or more
//    contrasted), as Baker et al.'s inverse compositional brightness: their steepest-descent
//    images are A0 and 1 (projected out), precomputed like the rest.
//  - The 2D term is measured in the gain at the fit's start, not the current gain: divided by the
//    current gain, a step that lowers the gain towards its least-squares value (which a misaligned
//    face asks for) raised the measured residual and was rejected, so on real faces the
//    similarity phase's first step looked like a doubling of the residual.
//  - A weak ridge (aam_head_term.cpp) keeps shape and animation units that the 2D shape cannot tell
//    apart (Mouth vertical position against Jaw drop) from drifting.
//  - A new face fits its similarity and gain/bias alone until they settle (progressive
//    complexity, 5.3.3), then the head is placed on the 2D shape by least squares (frontal) and
//    everything is fitted. A tracked face starts from its last fit moved with the tracker.
//  - The fit error is the projected-out residual's rms in units of the mean appearance's standard
//    deviation (the span of the modes removed: what no face of the model explains), measured on
//    the last iteration's error image. Verification rejects a fit above options.maxResidual or
//    turned beyond options.maxAngleDegrees; the caller then keeps the 2D pose.
#include "vision/aam_fitter.hpp"

#include "aam_composition.hpp"
#include "aam_fit_tables.hpp"
#include "aam_head_projection.hpp"
#include "aam_head_term.hpp"
#include "aam_kernels.hpp"
#include "aam_texture.hpp"
#include "aam_warp.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace vision {

namespace {

using aam::ParameterMatrix;
using aam::ParameterVector;

constexpr float kMinGain = 1.f, kMaxGain = 250.f;
constexpr double kFirstDamping = 0.1, kMaxDamping = 100.0;  // Levenberg-Marquardt, relative
/// The shape prior's weight: a mode's parameter at one standard deviation costs as much as this
/// much squared appearance residual (in the mean appearance's std units, summed over the pixels).
constexpr double kShapePrior = 1.0;
constexpr float kDegrees = 180.f / std::numbers::pi_v<float>;
/// A new face's turned start is taken over the frontal one only when its residual is lower by
/// this much (rms, mean appearance's std units): among near ties the frontal one. Chosen before
/// kTurnedStartAbove on the synthetic new faces (0: 78 % of them converge, 0.02: 82 %, 0.1: 93 %
/// but the synthetic turned heads lost) and IMM's turned heads.
constexpr float kTurnedStartMargin = 0.02f;
/// The turned starts are tried only when the frontal one's residual is at least this: the mean
/// appearance at the image's own contrast explains no more of the image than a flat template
/// would. Measured from dlib's boxes on IMM's held-out persons: frontal faces 0.54-1.06 (one
/// above 1), turned to their right 0.71-1.14, to their left 1.05-1.35. Without it, synthetic
/// sequences that start frontal sometimes started turned and froze the wrong shape units.
constexpr float kTurnedStartAbove = 1.f;

}  // namespace

struct AamFitter::Tables : aam::Tables {
    Tables(aam::Tables t, int textureGrid)
        : aam::Tables(std::move(t)), texture(aam::textureLayout(*this, textureGrid))
    {
    }
    aam::TextureLayout texture;  ///< the texture descriptor's cells (appearanceParameters)
};

struct AamFitter::Scratch {
    std::vector<std::int16_t> warped, error;
    std::vector<aam::TriangleAffine> triangleMaps, vertexMaps;
    std::vector<float> shape, before, head;
    std::vector<aam::HeadJacobian> headJacobian;
    std::vector<float> bestShape;
    std::vector<std::int16_t> textureFrame;       ///< the warp laid out as the frame's rectangle
    std::vector<std::uint16_t> textureHistogram;  ///< the descriptor's counts
    /// The gain the objective is measured in during one fit (its start's): fixed, so that a step
    /// that lowers the gain is not charged for the larger residual it measures in its own units.
    float referenceGain = 1.f;
    ParameterMatrix hessian, damped;
    ParameterVector rhs, step;
    Eigen::LDLT<ParameterMatrix> solver;

    explicit Scratch(const AamFitter::Tables& t)
        : warped(static_cast<std::size_t>(t.spanPixels)),
          error(static_cast<std::size_t>(t.spanPixels)),
          triangleMaps(static_cast<std::size_t>(t.triangles)),
          vertexMaps(static_cast<std::size_t>(t.vertices)),
          shape(2 * static_cast<std::size_t>(t.vertices)),
          before(2 * static_cast<std::size_t>(t.vertices)),
          head(2 * static_cast<std::size_t>(t.vertices)),
          headJacobian(static_cast<std::size_t>(t.vertices)),
          bestShape(2 * static_cast<std::size_t>(t.vertices)),
          textureFrame(static_cast<std::size_t>(t.texture.width) *
                       static_cast<std::size_t>(t.texture.height)),
          textureHistogram(static_cast<std::size_t>(t.texture.bins())),
          hessian(6 + t.shapeModeCount + aam::kHeadParameters,
                  6 + t.shapeModeCount + aam::kHeadParameters),
          damped(hessian.rows(), hessian.cols()),
          rhs(hessian.rows()),
          step(hessian.rows()),
          solver(hessian.rows())
    {
    }
};

namespace {

/// Gain and bias of the warped image over the model pixels: its mean and standard deviation (the
/// mean appearance has zero mean and unit variance).
void measureGainBias(const aam::Tables& t, const std::int16_t* warped, AamFaceState& face)
{
    double sum = 0, squares = 0;
    for (int i = 0; i < t.spanPixels; ++i) {
        const double v = t.mask[static_cast<std::size_t>(i)] != 0 ? warped[i] : 0.0;
        sum += v;
        squares += v * v;
    }
    const double mean = sum / t.modelPixels;
    const double variance = std::max(squares / t.modelPixels - mean * mean, 1.0);
    face.gain = std::clamp(static_cast<float>(std::sqrt(variance)), kMinGain, kMaxGain);
    face.bias = static_cast<float>(mean);
}

void errorImageOf(const aam::Tables& t, const AamFaceState& face, const std::int16_t* warped,
                  std::int16_t* error)
{
    const auto gain = static_cast<std::int32_t>(std::lround(face.gain * 256.f));
    const auto bias = static_cast<std::int32_t>(std::lround(face.bias * 65536.f));
    aam::errorImage(warped, t.meanAppearance.data(), t.mask.data(), gain, bias, error,
                    t.spanPixels);
}

/// Projected-out rms of the error image, in units of the mean appearance's std.
float fitErrorOf(const aam::Tables& t, const std::int16_t* error, float gain)
{
    const double scale = 1.0 / (aam::kErrorOne * static_cast<double>(gain));
    double energy =
        static_cast<double>(aam::dotProduct(error, error, t.spanPixels)) * scale * scale;
    for (const aam::Quantised& mode : t.appearanceModes) {
        const double along =
            static_cast<double>(aam::dotProduct(mode.values.data(), error, t.spanPixels)) * scale /
            mode.scale;
        energy -= along * along;
    }
    return static_cast<float>(std::sqrt(std::max(energy, 0.0) / t.modelPixels));
}

float largestMove(const std::vector<float>& a, const std::vector<float>& b)
{
    float largest = 0.f;
    for (std::size_t v = 0; v + 1 < a.size(); v += 2)
        largest = std::max(largest, std::hypot(a[v] - b[v], a[v + 1] - b[v + 1]));
    return largest;
}

bool finite(const std::vector<float>& values)
{
    for (float v : values)
        if (!std::isfinite(v))
            return false;
    return true;
}

/// Gain and bias (template side), the 2D shape composed with the increment's inverse, the head
/// moved by its increment.
void applyStep(const aam::Tables& t, AamFitter::Scratch& s, AamFaceState& face, bool withHead)
{
    const auto& d = s.step;
    const float gain = face.gain;
    face.gain = std::clamp(gain * (1.f + static_cast<float>(d(0))), kMinGain, kMaxGain);
    face.bias += gain * static_cast<float>(d(1));
    float dq[4], dp[kAamMaxShapeModes];
    for (int i = 0; i < 4; ++i)
        dq[i] = static_cast<float>(d(2 + i));
    for (int j = 0; j < t.shapeModeCount; ++j)
        dp[j] = static_cast<float>(d(6 + j));
    aam::vertexAffines(t, s.triangleMaps.data(), s.vertexMaps.data());
    aam::composeInverse(t, s.vertexMaps.data(), dq, dp, face.q.data(), face.p.data(),
                        s.shape.data());
    if (!withHead)
        return;
    Eigen::Matrix<float, aam::kHeadParameters, 1> r = aam::headParameters(face.head);
    r += d.tail<aam::kHeadParameters>().cast<float>();
    aam::setHeadParameters(face.head, r);
}

void finishResult(const AamFitterOptions& options, const std::vector<float>& shape,
                  AamFaceState& face, float fitError, int iterations, AamFitResult& result)
{
    const AamHead& h = face.head;
    result.iterations = iterations;
    result.fitError = fitError;
    result.yawDegrees = h.yaw * kDegrees;
    result.pitchDegrees = h.pitch * kDegrees;
    result.rollDegrees = h.roll * kDegrees;
    result.translation = h.translation;
    result.scale = h.scale;
    result.animation = h.tau;
    for (int v = 0; v < result.vertexCount; ++v)
        result.vertices[static_cast<std::size_t>(v)] = {shape[2 * static_cast<std::size_t>(v)],
                                                        shape[2 * static_cast<std::size_t>(v) + 1]};
    if (result.outcome == AamFitOutcome::Diverged)
        return;
    const bool plausible = face.headSet && fitError <= options.maxResidual &&
                           std::abs(result.yawDegrees) <= options.maxAngleDegrees &&
                           std::abs(result.pitchDegrees) <= options.maxAngleDegrees;
    if (!plausible)
        result.outcome = AamFitOutcome::Rejected;
    else
        ++face.fits;
}

}  // namespace

const char* aamFitOutcomeName(AamFitOutcome outcome) noexcept
{
    switch (outcome) {
        case AamFitOutcome::Converged:
            return "converged";
        case AamFitOutcome::IterationCap:
            return "iteration-cap";
        case AamFitOutcome::Rejected:
            return "rejected";
        case AamFitOutcome::Diverged:
            return "diverged";
    }
    return "?";
}

AamFitter::AamFitter(const AamModel& model, const AamFitterOptions& options)
    : tables_(std::make_unique<Tables>(aam::buildTables(model), options.textureGrid)),
      scratch_(std::make_unique<Scratch>(*tables_)),
      options_(options)
{
}

AamFitter::~AamFitter() = default;
AamFitter::AamFitter(AamFitter&&) noexcept = default;
AamFitter& AamFitter::operator=(AamFitter&&) noexcept = default;

const AamFitterOptions& AamFitter::options() const noexcept
{
    return options_;
}
void AamFitter::setSampling(AamSampling sampling) noexcept
{
    options_.sampling = sampling;
}
int AamFitter::vertexCount() const noexcept
{
    return tables_->vertices;
}
int AamFitter::appearanceModeCount() const noexcept
{
    return static_cast<int>(tables_->appearanceModes.size());
}

// §6: the fitted face's appearance parameters. The same steps as one iteration's error image (the
// warp, the mean appearance under gain and bias subtracted in 1/16 grey levels), then one exact
// integer dot product per mode; only the division into each mode's std is floating point.
int AamFitter::appearanceParameters(ConstImageView grey, const AamFaceState& face,
                                    std::span<float> out) noexcept
{
    return appearanceParameters(grey, face, out, {});
}

int AamFitter::textureSize() const noexcept
{
    return tables_->texture.bins();
}

// The texture descriptor (aam_texture.cpp) from the same warp, before the error image.
int AamFitter::appearanceParameters(ConstImageView grey, const AamFaceState& face,
                                    std::span<float> out, std::span<std::uint8_t> texture) noexcept
{
    const aam::Tables& t = *tables_;
    Scratch& s = *scratch_;
    const int n = static_cast<int>(std::min(out.size(), t.appearanceModes.size()));
    if (grey.empty() || grey.format != PixelFormat::Gray8 || n == 0 || !(face.gain > 0.f))
        return 0;
    aam::shapeFromParameters(t, face.q.data(), face.p.data(), s.shape.data());
    aam::triangleAffines(t, s.shape.data(), s.triangleMaps.data());
    aam::warpImage(t, s.triangleMaps.data(), grey, options_.appearanceSampling, s.warped.data());
    if (!texture.empty())
        aam::textureOf(tables_->texture, s.warped.data(), s.textureFrame.data(),
                       s.textureHistogram.data(), texture);
    errorImageOf(t, face, s.warped.data(), s.error.data());
    const double toAppearance = 1.0 / (aam::kErrorOne * static_cast<double>(face.gain));
    for (int k = 0; k < n; ++k) {
        const aam::Quantised& mode = t.appearanceModes[static_cast<std::size_t>(k)];
        const double along =
            static_cast<double>(aam::dotProduct(mode.values.data(), s.error.data(), t.spanPixels)) *
            toAppearance / mode.scale;
        out[static_cast<std::size_t>(k)] = static_cast<float>(
            along / std::max(t.appearanceModeStd[static_cast<std::size_t>(k)], 1e-6f));
    }
    return n;
}

void AamFitter::start(AamFaceState& face, const AamStart& start) const noexcept
{
    const aam::Tables& t = *tables_;
    face = AamFaceState{};
    const float k = start.width / std::max(t.boxSize.x(), 1.f);
    const float roll = start.rollDegrees / kDegrees;
    aam::Similarity n;
    n.linear << k * std::cos(roll), -k * std::sin(roll), k * std::sin(roll), k * std::cos(roll);
    const Eigen::Vector2f boxCentre = t.boxLow + 0.5f * t.boxSize;
    n.translation = Eigen::Vector2f(start.centre.x, start.centre.y) - t.centre -
                    n.linear * (boxCentre - t.centre);
    aam::parametersOf(t, n, face.q.data());
}

bool AamFitter::shapeUnitsFrozen(const AamFaceState& face) const noexcept
{
    return face.shapeUnitsKept || face.fits >= options_.fitsBeforeShapeFreeze;
}

void AamFitter::restart(AamFaceState& face, const AamStart& at) const noexcept
{
    const bool keep = shapeUnitsFrozen(face);
    const auto sigma = face.head.sigma;
    start(face, at);
    if (keep) {
        face.head.sigma = sigma;
        face.shapeUnitsKept = true;
    }
}

void AamFitter::follow(AamFaceState& face, const AamStart& from, const AamStart& to) const noexcept
{
    const aam::Tables& t = *tables_;
    const float k = to.width / std::max(from.width, 1.f);
    const float turn = (to.rollDegrees - from.rollDegrees) / kDegrees;
    Eigen::Matrix2f move;
    move << k * std::cos(turn), -k * std::sin(turn), k * std::sin(turn), k * std::cos(turn);
    const Eigen::Vector2f a(from.centre.x, from.centre.y), b(to.centre.x, to.centre.y);
    aam::Similarity n = aam::similarityOf(t, face.q.data());
    n.translation = b + move * (t.centre + n.translation - a) - t.centre;
    n.linear = move * n.linear;
    aam::parametersOf(t, n, face.q.data());
    if (face.headSet) {
        const Eigen::Vector2f h =
            b + move * (Eigen::Vector2f(face.head.translation.x, face.head.translation.y) - a);
        face.head.translation = {h.x(), h.y()};
        face.head.scale *= k;
        face.head.roll += turn;
    }
}

AamFitResult AamFitter::fit(ConstImageView grey, AamFaceState& face, bool fine) noexcept
{
    const aam::Tables& t = *tables_;
    Scratch& s = *scratch_;
    AamFitResult result;
    result.vertexCount = t.vertices;
    if (grey.empty() || grey.format != PixelFormat::Gray8)
        return result;

    if (!face.headSet && face.gain <= 0.f)
        chooseStart(grey, face);
    aam::shapeFromParameters(t, face.q.data(), face.p.data(), s.shape.data());
    bool similarityPhase = face.fits == 0;
    const bool coarse = face.fits > 0 && !fine;
    const float convergedPixels =
        coarse ? options_.trackedConvergedPixels : options_.convergedPixels;
    const float convergedDegrees =
        coarse ? options_.trackedConvergedDegrees : options_.convergedDegrees;
    const bool shapeFrozen = shapeUnitsFrozen(face);
    AamFaceState best = face;
    float bestError = 0.f, bestReferenceError = 0.f;
    double bestEnergy = 0.0;
    bool measured = false;
    double damping = 0.0;
    int iteration = 0;
    result.outcome = AamFitOutcome::IterationCap;
    for (; iteration < options_.maxIterations; ++iteration) {
        aam::triangleAffines(t, s.shape.data(), s.triangleMaps.data());
        const int outside =
            aam::warpImage(t, s.triangleMaps.data(), grey, options_.sampling, s.warped.data());
        if (4 * outside > t.modelPixels) {
            result.outcome = AamFitOutcome::Diverged;
            break;
        }
        if (face.gain <= 0.f)
            measureGainBias(t, s.warped.data(), face);
        if (iteration == 0)
            s.referenceGain = face.gain;
        errorImageOf(t, face, s.warped.data(), s.error.data());
        const float error = fitErrorOf(t, s.error.data(), s.referenceGain);
        const double energy = objective(face, error, similarityPhase);
        if (measured && energy > bestEnergy) {
            // The last step made the fit worse: back to the best state and a shorter step from
            // its system (Levenberg-Marquardt); when no step helps, the best state is the answer.
            face = best;
            s.shape = s.bestShape;
            damping = damping == 0.0 ? kFirstDamping : damping * 4.0;
            aam::triangleAffines(t, s.shape.data(), s.triangleMaps.data());
            if (damping > kMaxDamping && !similarityPhase) {
                result.outcome = AamFitOutcome::Converged;
                break;
            }
            if (damping > kMaxDamping) {  // the similarity has settled: on to everything
                similarityPhase = false;
                damping = 0.0;
                buildSystem(grey, face, similarityPhase, shapeFrozen);
                best = face;
                bestEnergy = objective(face, bestReferenceError, false);
            }
        } else {
            buildSystem(grey, face, similarityPhase, shapeFrozen);
            best = face;
            bestError = error * s.referenceGain / face.gain;
            bestReferenceError = error;
            bestEnergy = energy;
            s.bestShape = s.shape;
            measured = true;
            damping = damping < kFirstDamping ? 0.0 : damping / 4.0;
        }
        s.damped = s.hessian;
        s.damped.diagonal() *= 1.0 + damping;
        s.solver.compute(s.damped);
        s.step = s.solver.solve(s.rhs);
        if (!s.step.allFinite()) {
            result.outcome = AamFitOutcome::Diverged;
            break;
        }
        s.before = s.shape;
        const AamHead headBefore = face.head;
        applyStep(t, s, face, !similarityPhase);
        if (!finite(s.shape) || !std::isfinite(face.gain) || face.head.scale < 0.f) {
            result.outcome = AamFitOutcome::Diverged;
            break;
        }
        const float moved = largestMove(s.shape, s.before);
        const float turned = kDegrees * std::max({std::abs(face.head.roll - headBefore.roll),
                                                  std::abs(face.head.pitch - headBefore.pitch),
                                                  std::abs(face.head.yaw - headBefore.yaw)});
        if (similarityPhase) {
            if (moved < convergedPixels ||
                iteration + 1 >= options_.maxSimilarityIterations) {
                similarityPhase = false;
                measured = false;  // the next state is measured against the new system's
                damping = 0.0;
            }
            continue;
        }
        if (moved < convergedPixels && turned < convergedDegrees) {
            result.outcome = AamFitOutcome::Converged;
            ++iteration;
            break;
        }
    }
    if (result.outcome == AamFitOutcome::IterationCap && measured) {
        face = best;  // the last step was never measured: the best measured state stands
        s.shape = s.bestShape;
    }
    finishResult(options_, s.shape, face, bestError, iteration, result);
    return result;
}

/// A new face's start: the frontal mean shape where start() placed it, or the CANDIDE head
/// turned by options.startYawDegrees to either side over the same place, scale and roll (its 2D
/// shape decomposed into q and p, its yaw kept for the head's placement after the similarity
/// phase); the one whose warp matches the mean appearance best (the projected-out residual at the
/// image's own contrast). A head turned well away from the camera correlates poorly with the
/// frontal mean appearance, worst when its broad side is in shadow, and from there the first
/// steps lower the gain instead of moving the mesh (§5; measured on IMM's turned heads:
/// docs/aam-fit.md).
void AamFitter::chooseStart(ConstImageView grey, AamFaceState& face) noexcept
{
    const aam::Tables& t = *tables_;
    Scratch& s = *scratch_;
    if (!(options_.startYawDegrees > 0.f))
        return;
    aam::shapeFromParameters(t, face.q.data(), face.p.data(), s.shape.data());
    AamHead head{};
    aam::placeHeadOn(t, s.shape.data(), head);
    const AamFaceState frontal = face;
    float bestError = 0.f;
    bool found = false;
    for (int k = 0; k < 3; ++k) {
        AamFaceState c = frontal;
        if (k == 0) {
            aam::shapeFromParameters(t, c.q.data(), c.p.data(), s.shape.data());
        } else {
            head.yaw = (k == 1 ? -options_.startYawDegrees : options_.startYawDegrees) / kDegrees;
            aam::projectHead(t, head, s.shape.data(), nullptr);
            aam::decomposeShape(t, c.q.data(), c.p.data(), s.shape.data());
            c.head.yaw = head.yaw;
        }
        aam::triangleAffines(t, s.shape.data(), s.triangleMaps.data());
        const int outside =
            aam::warpImage(t, s.triangleMaps.data(), grey, options_.sampling, s.warped.data());
        if (4 * outside > t.modelPixels)
            continue;
        measureGainBias(t, s.warped.data(), c);
        errorImageOf(t, c, s.warped.data(), s.error.data());
        // A turned start must match better by kTurnedStartMargin: among near ties the frontal
        // one (most faces in front of a mirror look at it).
        const float error =
            fitErrorOf(t, s.error.data(), c.gain) + (k == 0 ? 0.f : kTurnedStartMargin);
        if (!found || error < bestError) {
            face = c;
            face.gain = 0.f;  // measured again at the fit's start
            bestError = error;
            found = true;
        }
        if (k == 0 && found && error < kTurnedStartAbove)
            return;  // the frontal start matches: the usual case, and the turned ones not tried
    }
}

/// What the Gauss-Newton steps minimise, at the current state: the 2D term (the projected-out
/// residual's squares), and after the similarity phase the shape prior and the 3D term. A step
/// that raises it is taken back (Levenberg-Marquardt).
double AamFitter::objective(AamFaceState& face, float error, bool similarityPhase) noexcept
{
    const aam::Tables& t = *tables_;
    Scratch& s = *scratch_;
    double energy = static_cast<double>(t.modelPixels) * error * error;
    if (similarityPhase)
        return energy;
    for (int j = 0; j < t.shapeModeCount; ++j) {
        const double limit = t.shapeLimits[static_cast<std::size_t>(j)] / 3.0;
        const double p = face.p[static_cast<std::size_t>(j)];
        energy += kShapePrior * p * p / std::max(limit * limit, 1e-6);
    }
    if (!face.headSet)
        return energy;
    aam::HeadTermInput in;
    in.shape = s.shape.data();
    in.frameScale = aam::similarityOf(t, face.q.data()).scale();
    in.weight = options_.constraintWeight;
    return energy + aam::headTermEnergy(t, face.head, in, s.head.data());
}

/// The Gauss-Newton system at the current state: the 2D term (eq. 70; its Hessian precomputed, its
/// gradient the error image's dot products), the shape prior, and after the similarity phase the
/// 3D term (eq. 83). Unknowns not fitted in this phase get a zero step.
void AamFitter::buildSystem(ConstImageView, AamFaceState& face, bool similarityPhase,
                            bool shapeFrozen) noexcept
{
    const aam::Tables& t = *tables_;
    Scratch& s = *scratch_;
    const int m = t.shapeModeCount;
    const int n = 6 + m + aam::kHeadParameters;
    // The 2D term in the reference gain's units: the template moves by gain * SD * step grey
    // levels, the residual is divided by the reference gain.
    const double relativeGain = static_cast<double>(face.gain) / s.referenceGain;
    const double toAppearance =
        relativeGain / (aam::kErrorOne * static_cast<double>(s.referenceGain));
    s.hessian.setZero();
    s.rhs.setZero();
    const int count2d = similarityPhase ? 6 : 6 + m;
    s.hessian.topLeftCorner(count2d, count2d) =
        relativeGain * relativeGain * t.hessian2d.topLeftCorner(count2d, count2d);
    for (int j = 0; j < count2d; ++j) {
        const aam::Quantised& sd = t.steepest[static_cast<std::size_t>(j)];
        s.rhs(j) =
            static_cast<double>(aam::dotProduct(sd.values.data(), s.error.data(), t.spanPixels)) *
            toAppearance / sd.scale;
    }
    int unknowns = count2d;
    if (!similarityPhase) {
        // The shape prior: sum p_i^2 / lambda_i, p's increment composed with a minus sign.
        for (int j = 0; j < m; ++j) {
            const double limit = t.shapeLimits[static_cast<std::size_t>(j)] / 3.0;
            const double weight = kShapePrior / std::max(limit * limit, 1e-6);
            s.hessian(6 + j, 6 + j) += weight;
            s.rhs(6 + j) += weight * face.p[static_cast<std::size_t>(j)];
        }
        if (!face.headSet) {
            aam::placeHeadOn(t, s.shape.data(), face.head);
            face.headSet = true;
        }
        unknowns = n;
        aam::HeadTermInput in;
        in.shape = s.shape.data();
        aam::vertexAffines(t, s.triangleMaps.data(), s.vertexMaps.data());
        in.vertexMaps = s.vertexMaps.data();
        in.frameScale = aam::similarityOf(t, face.q.data()).scale();
        in.weight = options_.constraintWeight;
        in.shapeUnitsFrozen = shapeFrozen;
        aam::addHeadTerm(t, face.head, in, s.head.data(), s.headJacobian.data(), s.hessian, s.rhs);
    }
    for (int j = unknowns; j < n; ++j)
        s.hessian(j, j) = 1.0;
}

}  // namespace vision
