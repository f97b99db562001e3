// The AAM fit (§5, dissertation 5.3.2-5.3.4) on synthetic faces: the model's own appearance (mean
// and a few modes) warped onto the CANDIDE head at known poses and expressions over a textured
// background. From starts perturbed off the true face box a new face must converge and find its
// pose within stated bounds; a tracked face must follow a head turning through +-30 degrees, and
// return to a posed face from two pixels off. The parts the Gauss-Newton step is built from are
// checked against finite differences: the head projection's Jacobian, the composed shape's motion,
// and the steepest-descent images against the warped image's real change.
//
// The model is the demo model `scripts/dev model` writes (out/aam/imm-demo.aam, from IMM); the
// tests skip, saying so, when it has not been built.
#include "vision/aam_fitter.hpp"

#include "aam_composition.hpp"
#include "aam_demo_model.hpp"
#include "aam_fit_tables.hpp"
#include "aam_head_projection.hpp"
#include "aam_kernels.hpp"
#include "aam_synthetic_face.hpp"
#include "aam_warp.hpp"
#include "alloc_counter.hpp"
#include "test_paths.hpp"
#include "vision/aam_model.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <memory>
#include <random>

namespace {

using aam_test::renderSyntheticFace;
using aam_test::SyntheticFace;
using aam_test::SyntheticFaceSpec;

constexpr float kRadians = 3.14159265f / 180.f;
constexpr int kWidth = 320, kHeight = 240;

using aam_test::demoModel;

/// A face of width ~140 px at the centre of the image, posed and with an expression.
SyntheticFaceSpec posedSpec(float yawDeg, float pitchDeg, float rollDeg, std::mt19937& random)
{
    const vision::AamModel& m = *demoModel();
    SyntheticFaceSpec spec;
    static const vision::AamHead mean = aam_test::meanShapeHead(m);
    spec.head.sigma = mean.sigma;
    spec.head.scale = 140.f / aam_test::meshWidthUnits(m);
    spec.head.yaw = yawDeg * kRadians;
    spec.head.pitch = pitchDeg * kRadians;
    spec.head.roll = rollDeg * kRadians;
    spec.head.translation = {kWidth * 0.5f, kHeight * 0.5f};
    std::uniform_real_distribution<float> change(-0.1f, 0.1f), look(-1.f, 1.f);
    for (std::size_t k = 0; k < spec.head.tau.size(); ++k)
        spec.head.tau[k] = mean.tau[k] + change(random);

    spec.appearanceWeights = {look(random), look(random), look(random)};
    spec.backgroundSeed = random();
    return spec;
}

/// The true box moved by up to 4% of its width each way, scaled by up to 5% and turned by up to
/// 5 degrees.
vision::AamStart perturbed(vision::AamStart box, std::mt19937& random)
{
    std::uniform_real_distribution<float> unit(-1.f, 1.f);
    box.centre.x += 0.04f * box.width * unit(random);
    box.centre.y += 0.04f * box.width * unit(random);
    box.rollDegrees += 5.f * unit(random);
    box.width *= 1.f + 0.05f * unit(random);
    return box;
}

struct Tally {
    int fits = 0, converged = 0;
    double yaw = 0, pitch = 0, roll = 0, animationSquares = 0, iterations = 0, vertexRms = 0;
    int animationValues = 0;

    void add(const SyntheticFaceSpec& truth, const SyntheticFace& face,
             const vision::AamFitResult& fit)
    {
        ++fits;
        if (!fit.ok() || aam_test::rmsDistance(face.vertices, fit) > 3.f)
            return;
        ++converged;
        yaw += std::abs(fit.yawDegrees - truth.head.yaw / kRadians);
        pitch += std::abs(fit.pitchDegrees - truth.head.pitch / kRadians);
        roll += std::abs(fit.rollDegrees - truth.head.roll / kRadians);
        for (std::size_t k = 0; k < fit.animation.size(); ++k) {
            const double d = fit.animation[k] - truth.head.tau[k];
            animationSquares += d * d;
            ++animationValues;
        }
        iterations += fit.iterations;
        vertexRms += aam_test::rmsDistance(face.vertices, fit);
    }
    double rate() const { return static_cast<double>(converged) / std::max(fits, 1); }
    double mean(double sum) const { return sum / std::max(converged, 1); }
    double animationRmse() const
    {
        return std::sqrt(animationSquares / std::max(animationValues, 1));
    }
    void print(const char* what) const
    {
        std::printf(
            "%s: fits=%d converged=%.3f yaw_mae=%.2f pitch_mae=%.2f roll_mae=%.2f "
            "animation_rmse=%.3f vertex_rms_px=%.2f iterations=%.1f\n",
            what, fits, rate(), mean(yaw), mean(pitch), mean(roll), animationRmse(),
            mean(vertexRms), mean(iterations));
    }
};

/// New faces at known poses, from perturbed boxes: turned up to 15 degrees (a new face starts
/// from the mean, frontal shape; further turns are reached by tracking, below).
Tally fitPoseGrid(vision::AamFitter& fitter, std::uint32_t seed)
{
    std::mt19937 random(seed);
    Tally tally;
    for (float yaw : {-15.f, 0.f, 15.f})
        for (float pitch : {-10.f, 0.f, 10.f})
            for (float roll : {-20.f, 0.f, 20.f}) {
                const SyntheticFaceSpec spec = posedSpec(yaw, pitch, roll, random);
                const SyntheticFace face = renderSyntheticFace(*demoModel(), spec, kWidth, kHeight);
                vision::AamFaceState state;
                fitter.start(state, perturbed(face.box(roll), random));
                tally.add(spec, face, fitter.fit(face.image.view(), state));
            }
    return tally;
}

/// A head turning through +-30 degrees of yaw (and +-10 of pitch and roll) while its expression
/// changes, one fit per frame from the last, moved with the true box as the tracker would move it.
Tally trackTurningHead(vision::AamFitter& fitter, int frames, double* itersPerFrame = nullptr)
{
    const vision::AamModel& m = *demoModel();
    static const vision::AamHead mean = aam_test::meanShapeHead(m);
    Tally tally;
    vision::AamFaceState state;
    vision::AamStart previous;
    long iterations = 0;
    for (int f = 0; f < frames; ++f) {
        const float phase = 6.2832f * static_cast<float>(f) / static_cast<float>(frames);
        SyntheticFaceSpec spec;
        spec.head = mean;
        spec.head.scale = 140.f / aam_test::meshWidthUnits(m);
        spec.head.yaw = 30.f * kRadians * std::sin(phase);
        spec.head.pitch = 10.f * kRadians * std::sin(2.f * phase);
        spec.head.roll = 10.f * kRadians * std::sin(1.5f * phase);
        spec.head.translation = {kWidth * 0.5f + 10.f * std::sin(phase),
                                 kHeight * 0.5f + 5.f * std::cos(phase)};
        spec.head.tau[0] = mean.tau[0] + 0.3f * (0.5f - 0.5f * std::cos(3.f * phase));
        spec.head.tau[2] = mean.tau[2] + 0.3f * std::sin(2.f * phase);
        spec.appearanceWeights = {0.5f, -0.5f, 0.3f};
        spec.backgroundSeed = 3;
        const SyntheticFace face = renderSyntheticFace(m, spec, kWidth, kHeight);
        const vision::AamStart box = face.box(spec.head.roll / kRadians);
        if (f == 0)
            fitter.start(state, box);
        else
            fitter.follow(state, previous, box);
        previous = box;
        const vision::AamFitResult fit = fitter.fit(face.image.view(), state);
        tally.add(spec, face, fit);
        iterations += fit.iterations;
    }
    if (itersPerFrame != nullptr)
        *itersPerFrame = static_cast<double>(iterations) / frames;
    return tally;
}

TEST(AamFitter, NewFacesConvergeFromPerturbedBoxes)
{
    REQUIRE_DEMO_MODEL();
    vision::AamFitter fitter(*demoModel());
    const Tally tally = fitPoseGrid(fitter, 7);
    tally.print("synthetic new faces");
    EXPECT_GE(tally.rate(), 0.8);
    EXPECT_LE(tally.mean(tally.yaw), 3.0);
    EXPECT_LE(tally.mean(tally.pitch), 4.0);
    EXPECT_LE(tally.mean(tally.roll), 1.5);
}

TEST(AamFitter, FollowsAHeadTurningThroughThirtyDegrees)
{
    REQUIRE_DEMO_MODEL();
    vision::AamFitter fitter(*demoModel());
    double iterations = 0;
    const Tally tally = trackTurningHead(fitter, 60, &iterations);
    tally.print("synthetic tracking");
    std::printf("tracking iterations per frame: %.2f\n", iterations);
    EXPECT_GE(tally.rate(), 0.9);
    EXPECT_LE(tally.mean(tally.yaw), 3.0);
    EXPECT_LE(tally.mean(tally.pitch), 4.0);
    EXPECT_LE(tally.mean(tally.roll), 1.5);
    EXPECT_LE(tally.animationRmse(), 0.2);
    // A tracked face settles to a pixel, not a third of one (trackedConvergedPixels): the next
    // frame goes on from there. 3.5 iterations a frame at 0.3 px.
    EXPECT_LE(iterations, 3.0);
}

/// A head turned 35 degrees to either side, in even light and with its image-left side in shadow
/// (IMM's photographs are lit from the image's right), started as a new face from the box of the
/// same head facing the camera (where a face detector puts it): it must hold, turned the right way
/// and by at least 15 degrees, on both sides alike. (The fit's one-sided failure on IMM, turned
/// to the person's left, shadowed broad side, is checked on the photographs themselves:
/// tools/aam/tests/aam_fit_real_test.cpp.)
TEST(AamFitter, HeadsTurnedToEitherSideHoldWithTheirYawSign)
{
    REQUIRE_DEMO_MODEL();
    vision::AamFitter fitter(*demoModel());
    for (float yaw : {-35.f, 35.f}) {
        for (float light : {0.f, 0.5f}) {
            std::mt19937 random(11);
            SyntheticFaceSpec spec = posedSpec(yaw, 0.f, 0.f, random);
            spec.lightFromRight = light;
            spec.appearanceWeights.clear();
            const SyntheticFace face = renderSyntheticFace(*demoModel(), spec, kWidth, kHeight);
            SyntheticFaceSpec frontal = spec;
            frontal.head.yaw = 0.f;
            const vision::AamStart box =
                renderSyntheticFace(*demoModel(), frontal, kWidth, kHeight).box(0.f);
            vision::AamFaceState state;
            fitter.start(state, box);
            const vision::AamFitResult fit = fitter.fit(face.image.view(), state);
            std::printf("yaw %+.0f, shadow on the left %.1f: %s, error %.2f, yaw %.1f, %d it\n",
                        yaw, light, vision::aamFitOutcomeName(fit.outcome), fit.fitError,
                        fit.yawDegrees, fit.iterations);
            EXPECT_TRUE(fit.ok()) << "yaw " << yaw << " shadow " << light;
            EXPECT_GT(fit.yawDegrees * (yaw > 0.f ? 1.f : -1.f), 15.f)
                << "yaw " << yaw << " shadow " << light;
        }
    }
}

/// The posed face's true 2D shape as the fit's state: q and p of its projection onto the model
/// (the inverse composition with a zero increment), `shift` pixels to the right.
vision::AamFaceState stateAt(const vision::aam::Tables& t, const SyntheticFace& face, float shift)
{
    const auto v = static_cast<std::size_t>(t.vertices);
    std::vector<float> shape(2 * v);
    for (std::size_t k = 0; k < v; ++k) {
        shape[2 * k] = face.vertices[k].x + shift;
        shape[2 * k + 1] = face.vertices[k].y;
    }
    std::vector<vision::aam::TriangleAffine> maps(static_cast<std::size_t>(t.triangles)), at(v);
    vision::aam::triangleAffines(t, shape.data(), maps.data());
    vision::aam::vertexAffines(t, maps.data(), at.data());
    vision::AamFaceState state;
    const float none[vision::kAamMaxShapeModes] = {};
    vision::aam::composeInverse(t, at.data(), none, none, state.q.data(), state.p.data(),
                                shape.data());
    return state;
}

/// A tracked face two pixels off its true place (its head too) returns to it, turned or not.
/// Failed (0.85-1.08 px, the shape modes' steps rejected) while the model's outer ring of pixels,
/// where the image's face meets its background, was in the fit.
TEST(AamFitter, ReturnsFromATwoPixelShiftOfAPosedFace)
{
    REQUIRE_DEMO_MODEL();
    const vision::aam::Tables t = vision::aam::buildTables(*demoModel());
    vision::AamFitter fitter(*demoModel());
    for (float yaw : {0.f, 5.f, 10.f, 20.f}) {
        std::mt19937 random(5);
        const SyntheticFaceSpec spec = posedSpec(yaw, 0.f, 0.f, random);
        const SyntheticFace face = renderSyntheticFace(*demoModel(), spec, kWidth, kHeight);
        vision::AamFaceState state = stateAt(t, face, 2.f);
        state.gain = spec.gain;
        state.bias = spec.bias;
        state.head = spec.head;
        state.head.translation.x += 2.f;
        state.headSet = true;
        state.fits = 1;
        const vision::AamFitResult fit = fitter.fit(face.image.view(), state);
        std::printf("posed face at yaw %.0f from 2 px off: %s, vertex rms %.2f px, yaw %.1f\n", yaw,
                    vision::aamFitOutcomeName(fit.outcome),
                    aam_test::rmsDistance(face.vertices, fit), fit.yawDegrees);
        EXPECT_TRUE(fit.ok()) << "yaw " << yaw;
        EXPECT_LT(aam_test::rmsDistance(face.vertices, fit), 0.5f) << "yaw " << yaw;
        EXPECT_NEAR(fit.yawDegrees, yaw, 1.f);
    }
}

TEST(AamHeadProjection, JacobianMatchesFiniteDifferences)
{
    REQUIRE_DEMO_MODEL();
    const vision::aam::Tables t = vision::aam::buildTables(*demoModel());
    vision::AamHead head = aam_test::meanShapeHead(*demoModel());
    head.scale = 100.f;
    head.roll = 0.2f;
    head.pitch = 0.1f;
    head.yaw = -0.3f;
    head.translation = {160.f, 120.f};
    const auto v = static_cast<std::size_t>(t.vertices);
    std::vector<float> base(2 * v), moved(2 * v);
    std::vector<vision::aam::HeadJacobian> jacobian(v);
    vision::aam::projectHead(t, head, base.data(), jacobian.data());
    const auto r = vision::aam::headParameters(head);
    for (int k = 0; k < vision::aam::kHeadParameters; ++k) {
        const float eps = 1e-3f;
        auto r2 = r;
        r2(k) += eps;
        vision::AamHead h2 = head;
        vision::aam::setHeadParameters(h2, r2);
        vision::aam::projectHead(t, h2, moved.data(), nullptr);
        double worst = 0, scale = 1e-9;
        for (std::size_t i = 0; i < 2 * v; ++i) {
            const double numeric = (moved[i] - base[i]) / eps;
            worst =
                std::max(worst, std::abs(numeric - jacobian[i / 2](static_cast<int>(i % 2), k)));
            scale = std::max(scale, std::abs(numeric));
        }
        EXPECT_LT(worst, 0.02 * scale + 0.05) << "parameter " << k;
    }
}

/// The composed 2D shape moves as the 3D term's Jacobian assumes: vertex v by -L_v times the
/// increment's basis vector, for q and every p.
TEST(AamComposition, ShapeMovesAsTheHeadTermAssumes)
{
    REQUIRE_DEMO_MODEL();
    const vision::aam::Tables t = vision::aam::buildTables(*demoModel());
    const auto v = static_cast<std::size_t>(t.vertices);
    float q[4] = {30.f, 5.f, 900.f, 500.f}, p[vision::kAamMaxShapeModes] = {3.f, -2.f, 1.f};
    std::vector<float> shape(2 * v), after(2 * v);
    vision::aam::shapeFromParameters(t, q, p, shape.data());
    std::vector<vision::aam::TriangleAffine> maps(static_cast<std::size_t>(t.triangles)), at(v);
    vision::aam::triangleAffines(t, shape.data(), maps.data());
    vision::aam::vertexAffines(t, maps.data(), at.data());
    for (int k = 0; k < 4 + t.shapeModeCount; ++k) {
        float dq[4] = {}, dp[vision::kAamMaxShapeModes] = {};
        const float eps = 0.05f;
        (k < 4 ? dq[k] : dp[k - 4]) = eps;
        float q2[4] = {q[0], q[1], q[2], q[3]}, p2[vision::kAamMaxShapeModes];
        std::copy(std::begin(p), std::end(p), p2);
        vision::aam::composeInverse(t, at.data(), dq, dp, q2, p2, after.data());
        double worst = 0, scale = 1e-9;
        for (std::size_t i = 0; i < v; ++i) {
            const auto row = static_cast<Eigen::Index>(2 * i);
            const Eigen::Vector2f basis =
                k < 4 ? Eigen::Vector2f(t.similarity.block<2, 4>(row, 0).col(k))
                      : Eigen::Vector2f(t.shapeModes.col(k - 4).segment<2>(row));
            const Eigen::Vector2f predicted = -at[i].linear * basis;
            for (int a = 0; a < 2; ++a) {
                const double numeric = (after[2 * i + a] - shape[2 * i + a]) / eps;
                worst = std::max(worst, std::abs(numeric - predicted(a)));
                scale = std::max(scale, std::abs(numeric));
            }
        }
        EXPECT_LT(worst, 0.05 * scale + 0.01) << "parameter " << k;
    }
}

/// Each steepest-descent image of q and p against the warped image's real change (a central
/// difference of the inverse composition, projected out like the images) on a frontal face at its
/// true place: the same direction (cosine) and nearly the same length. With the model's outer ring
/// of pixels in the fit the cosines were 0.2-0.7.
TEST(AamFitTables, SteepestDescentMatchesTheWarpedImage)
{
    REQUIRE_DEMO_MODEL();
    const vision::aam::Tables t = vision::aam::buildTables(*demoModel());
    const auto v = static_cast<std::size_t>(t.vertices);
    std::mt19937 random(5);
    SyntheticFaceSpec spec = posedSpec(0.f, 0.f, 0.f, random);
    spec.appearanceWeights.clear();
    const SyntheticFace face = renderSyntheticFace(*demoModel(), spec, kWidth, kHeight);
    const vision::AamFaceState state = stateAt(t, face, 0.f);
    const auto n = static_cast<std::size_t>(t.spanPixels);
    auto errorAfter = [&](const float* dq, const float* dp) {
        std::array<float, 4> q = state.q;
        std::array<float, vision::kAamMaxShapeModes> p = state.p;
        std::vector<float> shape(2 * v);
        std::vector<vision::aam::TriangleAffine> maps(static_cast<std::size_t>(t.triangles)), at(v);
        vision::aam::shapeFromParameters(t, q.data(), p.data(), shape.data());
        vision::aam::triangleAffines(t, shape.data(), maps.data());
        vision::aam::vertexAffines(t, maps.data(), at.data());
        vision::aam::composeInverse(t, at.data(), dq, dp, q.data(), p.data(), shape.data());
        vision::aam::triangleAffines(t, shape.data(), maps.data());
        std::vector<std::int16_t> warped(n), error(n);
        vision::aam::warpImage(t, maps.data(), face.image.view(), vision::AamSampling::Bilinear,
                               warped.data());
        vision::aam::errorImage(warped.data(), t.meanAppearance.data(), t.mask.data(),
                                static_cast<std::int32_t>(std::lround(spec.gain * 256.f)),
                                static_cast<std::int32_t>(std::lround(spec.bias * 65536.f)),
                                error.data(), t.spanPixels);
        Eigen::VectorXd e(t.spanPixels);
        for (std::size_t i = 0; i < n; ++i)
            e(static_cast<Eigen::Index>(i)) = error[i] / (vision::aam::kErrorOne * spec.gain);
        return e;
    };
    auto dense = [&](const vision::aam::Quantised& image) {
        Eigen::VectorXd d(t.spanPixels);
        for (std::size_t i = 0; i < n; ++i)
            d(static_cast<Eigen::Index>(i)) = image.values[i] / image.scale;
        return d;
    };
    for (int k = 0; k < 4 + t.shapeModeCount; ++k) {
        // Steps of about a tenth of a pixel: q's scale and roll are relative, its shifts scaled.
        const float eps = k == 2 || k == 3 ? 5.f : 1.f;
        float dq[2][4] = {}, dp[2][vision::kAamMaxShapeModes] = {};
        (k < 4 ? dq[0][k] : dp[0][k - 4]) = eps;
        (k < 4 ? dq[1][k] : dp[1][k - 4]) = -eps;
        // The template moved by +step: the image's error changes by -SD * step.
        Eigen::VectorXd numeric = (errorAfter(dq[1], dp[1]) - errorAfter(dq[0], dp[0])) / (2 * eps);
        for (const vision::aam::Quantised& mode : t.appearanceModes) {
            const Eigen::VectorXd a = dense(mode);
            numeric -= a * a.dot(numeric) / a.squaredNorm();
        }
        const Eigen::VectorXd analytic = dense(t.steepest[static_cast<std::size_t>(2 + k)]);
        const double cosine = numeric.dot(analytic) / (numeric.norm() * analytic.norm());
        EXPECT_GT(cosine, k == 2 || k == 3 ? 0.97 : 0.85) << "parameter " << k;
        EXPECT_NEAR(analytic.norm() / numeric.norm(), 1.0, 0.2) << "parameter " << k;
    }
}

/// §6: a face's appearance parameters. Against a plain float reference (the same warp, then the
/// warped image less gain * A0 + bias, over the gain, in double, dotted with each mode as floats):
/// equal up to the error image's 1/16 grey level. And on a synthetic face drawn with known mode
/// weights (in standard deviations) at its true shape, gain and bias: the weights come back.
TEST(AamFitter, AppearanceParametersMatchAPlainReferenceAndTheWeightsAFaceWasDrawnWith)
{
    REQUIRE_DEMO_MODEL();
    const vision::aam::Tables t = vision::aam::buildTables(*demoModel());
    vision::AamFitter fitter(*demoModel());
    ASSERT_EQ(fitter.appearanceModeCount(), static_cast<int>(t.appearanceModes.size()));
    std::mt19937 random(11);
    SyntheticFaceSpec spec = posedSpec(0.f, 0.f, 0.f, random);
    spec.appearanceWeights = {1.2f, -0.8f, 0.5f, -0.3f};
    const SyntheticFace face = renderSyntheticFace(*demoModel(), spec, kWidth, kHeight);
    vision::AamFaceState state = stateAt(t, face, 0.f);
    state.gain = spec.gain;
    state.bias = spec.bias;
    std::array<float, 64> ours{};
    const int n = fitter.appearanceParameters(face.image.view(), state, ours);
    ASSERT_EQ(n, std::min(64, fitter.appearanceModeCount()));
    ASSERT_GE(n, 4);

    // The plain reference.
    const auto v = static_cast<std::size_t>(t.vertices);
    const auto pixels = static_cast<std::size_t>(t.spanPixels);
    std::vector<float> shape(2 * v);
    vision::aam::shapeFromParameters(t, state.q.data(), state.p.data(), shape.data());
    std::vector<vision::aam::TriangleAffine> maps(static_cast<std::size_t>(t.triangles));
    vision::aam::triangleAffines(t, shape.data(), maps.data());
    std::vector<std::int16_t> warped(pixels);
    vision::aam::warpImage(t, maps.data(), face.image.view(), vision::AamSampling::Bilinear,
                           warped.data());
    const vision::AamModel& model = *demoModel();
    std::vector<std::size_t> spanAt(static_cast<std::size_t>(model.frameWidth) * model.frameHeight);
    for (const vision::aam::WarpRun& run : t.runs)
        for (int x = 0; x < run.count; ++x)
            spanAt[static_cast<std::size_t>(run.y) * model.frameWidth + run.x0 + x] =
                run.offset + static_cast<std::size_t>(x);
    for (int k = 0; k < n; ++k) {
        const vision::aam::Quantised& mode = t.appearanceModes[static_cast<std::size_t>(k)];
        double along = 0;
        for (std::size_t i = 0; i < pixels; ++i) {
            if (t.mask[i] == 0)
                continue;
            const double a0 = t.meanAppearance[i] / double{vision::aam::kAppearanceOne};
            const double delta = (warped[i] - spec.bias - spec.gain * a0) / spec.gain;
            along += mode.values[i] / double{mode.scale} * delta;
        }
        const double reference = along / t.appearanceModeStd[static_cast<std::size_t>(k)];
        EXPECT_NEAR(ours[static_cast<std::size_t>(k)], reference, 0.01) << "mode " << k;
        // The face was drawn with these weights of the model's own modes (0 beyond them): what
        // they put along this mode (the model's modes with the mean's direction taken out, over
        // the fitted pixels) comes back, up to the rounding of the drawn grey levels.
        double drawn = 0;
        for (std::size_t j = 0; j < spec.appearanceWeights.size(); ++j) {
            double dot = 0;
            for (std::size_t i = 0; i < model.pixels.size(); ++i) {
                const std::size_t at =
                    spanAt[model.pixels[i].y * model.frameWidth + model.pixels[i].x];
                if (t.mask[at] != 0)
                    dot += mode.values[at] / double{mode.scale} *
                           model.appearanceModes[j * model.pixels.size() + i];
            }
            drawn += spec.appearanceWeights[j] * std::sqrt(model.appearanceVariances[j]) * dot;
        }
        drawn /= t.appearanceModeStd[static_cast<std::size_t>(k)];
        EXPECT_NEAR(ours[static_cast<std::size_t>(k)], drawn, 0.05) << "mode " << k;
        if (k >= 1 && k < 4) {
            EXPECT_NEAR(ours[static_cast<std::size_t>(k)], spec.appearanceWeights[k], 0.1)
                << "mode " << k << " is nearly the model's own";
        }
    }
    EXPECT_EQ(fitter.appearanceParameters(face.image.view(), vision::AamFaceState{}, ours), 0)
        << "no gain: no parameters";
    std::array<float, 2> two{};
    EXPECT_EQ(fitter.appearanceParameters(face.image.view(), state, two), 2);
    EXPECT_EQ(two[0], ours[0]);
}

/// The texture descriptor against a plain reference: the same warp laid out on the frame's
/// rectangle, every model pixel whose 8 neighbours were warped compared with them (round the
/// circle from the top left), its pattern's transitions counted to find the uniform ones (58,
/// numbered in increasing order, the rest one bin), counted per cell of a grid over the model
/// pixels' bounding box, 255 * sqrt of each bin's share of its cell. The appearance parameters
/// are the same with or without it.
TEST(AamFitter, TextureDescriptorMatchesAPlainReference)
{
    REQUIRE_DEMO_MODEL();
    const vision::aam::Tables t = vision::aam::buildTables(*demoModel());
    std::mt19937 random(13);
    const SyntheticFaceSpec spec = posedSpec(8.f, -4.f, 6.f, random);
    const SyntheticFace face = renderSyntheticFace(*demoModel(), spec, kWidth, kHeight);
    vision::AamFaceState state = stateAt(t, face, 0.f);
    state.gain = spec.gain;
    state.bias = spec.bias;
    for (const int grid : {4, 5}) {
        vision::AamFitterOptions options;
        options.textureGrid = grid;
        vision::AamFitter fitter(*demoModel(), options);
        ASSERT_EQ(fitter.textureSize(), grid * grid * vision::kAamLbpBins);
        std::array<float, 64> plain{}, withTexture{};
        std::vector<std::uint8_t> ours(static_cast<std::size_t>(fitter.textureSize()));
        const int n = fitter.appearanceParameters(face.image.view(), state, plain);
        ASSERT_EQ(fitter.appearanceParameters(face.image.view(), state, withTexture, ours), n);
        EXPECT_EQ(plain, withTexture);

        const auto pixels = static_cast<std::size_t>(t.spanPixels);
        std::vector<float> shape(2 * static_cast<std::size_t>(t.vertices));
        vision::aam::shapeFromParameters(t, state.q.data(), state.p.data(), shape.data());
        std::vector<vision::aam::TriangleAffine> maps(static_cast<std::size_t>(t.triangles));
        vision::aam::triangleAffines(t, shape.data(), maps.data());
        std::vector<std::int16_t> warped(pixels);
        vision::aam::warpImage(t, maps.data(), face.image.view(), vision::AamSampling::Bilinear,
                               warped.data());
        const int w = demoModel()->frameWidth + 2, h = demoModel()->frameHeight + 2;
        std::vector<int> value(static_cast<std::size_t>(w * h), -1);  // -1: not warped
        std::vector<bool> model(static_cast<std::size_t>(w * h), false);
        int x0 = w, x1 = -1, y0 = h, y1 = -1;
        for (const vision::aam::WarpRun& run : t.runs)
            for (int k = 0; k < run.count; ++k) {
                const std::size_t span = run.offset + static_cast<std::size_t>(k);
                const int x = run.x0 + k, y = run.y;
                value[static_cast<std::size_t>(y * w + x)] = warped[span];
                if (t.mask[span] != 0) {
                    model[static_cast<std::size_t>(y * w + x)] = true;
                    x0 = std::min(x0, x), x1 = std::max(x1, x);
                    y0 = std::min(y0, y), y1 = std::max(y1, y);
                }
            }
        std::vector<int> uniformBin(256);
        for (int code = 0, next = 0; code < 256; ++code) {
            int transitions = 0;
            for (int b = 0; b < 8; ++b)
                transitions += ((code >> b) & 1) != ((code >> ((b + 1) % 8)) & 1);
            uniformBin[static_cast<std::size_t>(code)] = transitions <= 2 ? next++ : 58;
        }
        const int cells = grid * grid;
        std::vector<double> histogram(static_cast<std::size_t>(cells * 59), 0.0);
        std::vector<double> total(static_cast<std::size_t>(cells), 0.0);
        const int dx[8] = {-1, 0, 1, 1, 1, 0, -1, -1}, dy[8] = {-1, -1, -1, 0, 1, 1, 1, 0};
        for (int y = 1; y + 1 < h; ++y)
            for (int x = 1; x + 1 < w; ++x) {
                if (!model[static_cast<std::size_t>(y * w + x)])
                    continue;
                const int c = value[static_cast<std::size_t>(y * w + x)];
                int code = 0;
                bool all = true;
                for (int k = 0; k < 8; ++k) {
                    const int v = value[static_cast<std::size_t>((y + dy[k]) * w + x + dx[k])];
                    all = all && v >= 0;
                    code |= (v >= c ? 1 : 0) << k;
                }
                if (!all)
                    continue;
                const int cell =
                    (y - y0) * grid / (y1 - y0 + 1) * grid + (x - x0) * grid / (x1 - x0 + 1);
                histogram[static_cast<std::size_t>(
                    cell * 59 + uniformBin[static_cast<std::size_t>(code)])] += 1;
                total[static_cast<std::size_t>(cell)] += 1;
            }
        for (int i = 0; i < cells * 59; ++i) {
            const double expected =
                255.0 * std::sqrt(histogram[static_cast<std::size_t>(i)] /
                                  std::max(total[static_cast<std::size_t>(i / 59)], 1.0));
            ASSERT_NEAR(ours[static_cast<std::size_t>(i)], expected, 0.5 + 1e-3)
                << "grid " << grid << " bin " << i;
        }
        // Each cell's values are a unit vector (255 * sqrt of shares that sum to 1).
        for (int cell = 0; cell < cells; ++cell) {
            double squares = 0;
            for (int b = 0; b < 59; ++b)
                squares += std::pow(ours[static_cast<std::size_t>(cell * 59 + b)] / 255.0, 2);
            EXPECT_NEAR(squares, 1.0, 0.05) << "cell " << cell;
            EXPECT_GT(total[static_cast<std::size_t>(cell)], 10)
                << "cell " << cell;  // the oval's corners are small
        }
        std::vector<std::uint8_t> tooSmall(ours.size() - 1, 7);
        fitter.appearanceParameters(face.image.view(), state, plain, tooSmall);
        EXPECT_EQ(tooSmall, std::vector<std::uint8_t>(ours.size() - 1, 7))
            << "too small: untouched";
    }
    vision::AamFitterOptions none;
    none.textureGrid = 0;
    EXPECT_EQ(vision::AamFitter(*demoModel(), none).textureSize(), 0);
}

TEST(AamFitter, AppearanceParametersAllocateNothing)
{
    REQUIRE_DEMO_MODEL();
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting is not available in this build";
    const vision::aam::Tables t = vision::aam::buildTables(*demoModel());
    std::mt19937 random(12);
    const SyntheticFaceSpec spec = posedSpec(10.f, 0.f, 5.f, random);
    const SyntheticFace face = renderSyntheticFace(*demoModel(), spec, kWidth, kHeight);
    vision::AamFaceState state = stateAt(t, face, 0.f);
    state.gain = spec.gain;
    state.bias = spec.bias;
    for (const vision::AamSampling sampling :
         {vision::AamSampling::Bilinear, vision::AamSampling::Nearest}) {
        vision::AamFitterOptions options;
        options.appearanceSampling = sampling;
        vision::AamFitter fitter(*demoModel(), options);
        std::array<float, 64> out{};
        std::array<std::uint8_t, vision::kAamMaxTextureBins> texture{};
        testing_support::AllocationScope scope;
        const int n = fitter.appearanceParameters(face.image.view(), state, out);
        EXPECT_GT(n, 0);
        EXPECT_EQ(fitter.appearanceParameters(face.image.view(), state, out, texture), n)
            << "with the texture descriptor too";
        EXPECT_EQ(scope.counts().cxxNew, 0);
        EXPECT_EQ(scope.counts().ownMalloc, 0);
    }
}

}  // namespace

namespace {

/// A face with shape units of its own (not the mean head's), at the image's centre.
SyntheticFace personFace(vision::AamStart& frontalBox)
{
    std::mt19937 random(3);
    SyntheticFaceSpec spec = posedSpec(0.f, 0.f, 0.f, random);
    for (std::size_t k = 0; k < spec.head.sigma.size(); ++k)
        spec.head.sigma[k] += (k % 2 == 0 ? 0.05f : -0.05f);
    SyntheticFace face = renderSyntheticFace(*demoModel(), spec, kWidth, kHeight);
    frontalBox = face.box(0.f);
    return face;
}

}  // namespace

/// A restart (a track's fit started again from its box) keeps the person's shape units once they
/// froze, and fits with them frozen; before they froze it is a new face's start.
TEST(AamFitter, ARestartKeepsThePersonsFrozenShapeUnits)
{
    REQUIRE_DEMO_MODEL();
    vision::AamFitter fitter(*demoModel());
    vision::AamStart box;
    const SyntheticFace face = personFace(box);

    vision::AamFaceState young;
    fitter.start(young, box);
    ASSERT_TRUE(fitter.fit(face.image.view(), young).ok());
    fitter.restart(young, box);
    EXPECT_FALSE(young.shapeUnitsKept) << "not frozen yet: started as a new face";
    EXPECT_EQ(young.head.sigma, vision::AamHead{}.sigma);

    vision::AamFaceState known;
    fitter.start(known, box);
    for (int k = 0; k < fitter.options().fitsBeforeShapeFreeze; ++k)
        ASSERT_TRUE(fitter.fit(face.image.view(), known).ok()) << "fit " << k;
    const auto sigma = known.head.sigma;
    EXPECT_NE(sigma, vision::AamHead{}.sigma);
    fitter.restart(known, box);
    EXPECT_TRUE(known.shapeUnitsKept);
    EXPECT_EQ(known.fits, 0);
    EXPECT_FALSE(known.headSet);
    EXPECT_EQ(known.head.sigma, sigma);
    const vision::AamFitResult fit = fitter.fit(face.image.view(), known);
    EXPECT_TRUE(fit.ok()) << vision::aamFitOutcomeName(fit.outcome);
    EXPECT_EQ(known.head.sigma, sigma) << "frozen through the restarted fit";
}
