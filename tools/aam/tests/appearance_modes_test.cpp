// The appearance model (§5, 5.3.1, eqs. 54-59): a known gain and bias recovered; images that are
// one pattern under different gains and biases plus a known variation give that pattern as the
// mean and the variation as the first mode; held-out images of the same family reconstructed;
// flat images and bad fractions refused with one line.
#include "appearance_modes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

constexpr int kPixels = 500;

Eigen::VectorXd pattern(int which)
{
    Eigen::VectorXd v(kPixels);
    for (int i = 0; i < kPixels; ++i)
        v(i) = which == 0 ? std::sin(0.05 * i) + 0.3 * std::cos(0.31 * i) : std::cos(0.013 * i * i);
    return v;
}

std::vector<Eigen::VectorXd> family(int count, std::uint32_t seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> gain(20, 60), bias(50, 150), amount(-0.5, 0.5);
    std::vector<Eigen::VectorXd> images;
    for (int i = 0; i < count; ++i) {
        images.push_back(gain(random) * (pattern(0) + amount(random) * pattern(1)).array() +
                         bias(random));
    }
    return images;
}

TEST(AppearanceModes, GainAndBiasOfAKnownPairAreRecovered)
{
    const Eigen::VectorXd b = pattern(0);
    const Eigen::VectorXd a = (b.array() - 0.25) / 3.0;  // b = 3 a + 0.25
    const aam::GainBias g = aam::gainBiasOnto(a, b);
    EXPECT_NEAR(g.alpha, 3.0, 1e-9);
    EXPECT_NEAR(g.beta, 0.25, 1e-9);
}

TEST(AppearanceModes, TheMeanIsThePatternAndTheFirstModeTheVariation)
{
    const aam::AppearanceModes m = aam::appearanceModes(family(40, 3), 0.99);
    EXPECT_NEAR(m.mean.mean(), 0, 1e-9);
    EXPECT_NEAR(m.mean.squaredNorm() / kPixels, 1, 1e-9);
    EXPECT_GT(std::abs(m.mean.normalized().dot(aam::standardised(pattern(0)).normalized())), 0.98);
    ASSERT_GE(m.modes.cols(), 1);
    const Eigen::VectorXd variation = aam::standardised(pattern(1)).normalized();
    EXPECT_GT(std::abs(m.modes.col(0).dot(variation)), 0.95);
    EXPECT_LT(
        (m.modes.transpose() * m.modes - Eigen::MatrixXd::Identity(m.modes.cols(), m.modes.cols()))
            .norm(),
        1e-9);
    EXPECT_GT(m.iterations, 1);
}

TEST(AppearanceModes, ImagesOfTheFamilyNotTrainedOnAreReconstructed)
{
    const aam::AppearanceModes m = aam::appearanceModes(family(40, 3), 0.99);
    for (const Eigen::VectorXd& image : family(5, 99)) {
        const aam::AppearanceResidual r = aam::appearanceResidual(m, image);
        EXPECT_LT(r.rms, 0.05 * r.rmsMeanOnly + 1e-6);
        EXPECT_GT(r.alpha, 0);
    }
}

TEST(AppearanceModes, BadInputIsOneLine)
{
    const auto message = [](auto f) {
        try {
            f();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message([] { aam::appearanceModes(family(4, 1), 1.5); }),
              "appearance modes: variance fraction 1.500000 is not in (0, 1]");
    EXPECT_EQ(message([] { aam::appearanceModes(family(1, 1)); }),
              "appearance modes: 1 images; at least 2 needed");
    EXPECT_EQ(message([] {
                  aam::appearanceModes({Eigen::VectorXd::Constant(kPixels, 7), pattern(0)});
              }),
              "appearance: a flat image has no contrast to normalise");
}

}  // namespace
