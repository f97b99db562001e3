// The shape model's PCA (§5, 5.3.1): one known direction of variation found as the first mode,
// the modes orthonormal and kept to the fraction, a bad fraction refused with one line.
#include "shape_modes.hpp"

#include <gtest/gtest.h>

#include <random>

namespace {

aam::AlignedShapes varyingSquare()
{
    // The square's right side moves by t (large), its top by u (small); nothing else.
    std::mt19937 random(5);
    std::normal_distribution<double> t(0, 2), u(0, 0.2);
    aam::AlignedShapes set;
    for (int i = 0; i < 400; ++i) {
        const double a = t(random), b = u(random);
        set.shapes.push_back({{0, 0}, {10 + a, 0}, {10 + a, 10 + b}, {0, 10 + b}});
    }
    set.mean.assign(4, Eigen::Vector2d::Zero());
    for (const auto& s : set.shapes) {
        for (std::size_t k = 0; k < 4; ++k)
            set.mean[k] += s[k] / 400.0;
    }
    return set;
}

TEST(ShapeModes, FindsTheKnownDirectionsLargestFirst)
{
    const aam::ShapeModes m = aam::shapeModes(varyingSquare(), 0.999);
    ASSERT_EQ(m.modes.cols(), 2);
    Eigen::VectorXd right = Eigen::VectorXd::Zero(8);
    right(2) = right(4) = std::sqrt(0.5);  // x of vertices 1 and 2
    EXPECT_NEAR(std::abs(m.modes.col(0).dot(right)), 1.0, 1e-6);
    EXPECT_NEAR(m.variances(0), 2 * 4.0, 0.2 * 8);  // two coordinates of variance ~4
    EXPECT_LT(m.variances(1), 0.02 * m.variances(0));
    EXPECT_LT((m.modes.transpose() * m.modes - Eigen::MatrixXd::Identity(2, 2)).norm(), 1e-9);
}

TEST(ShapeModes, KeepsTheFewestModesForTheFraction)
{
    const aam::ShapeModes m = aam::shapeModes(varyingSquare(), 0.9);
    EXPECT_EQ(m.modes.cols(), 1);
    EXPECT_GE(m.variances.sum(), 0.9 * m.totalVariance);
}

TEST(ShapeModes, ABadFractionIsOneLine)
{
    try {
        aam::shapeModes(varyingSquare(), 1.5);
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "shape modes: variance fraction 1.500000 is not in (0, 1]");
    }
}

}  // namespace
