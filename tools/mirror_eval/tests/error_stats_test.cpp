// The error summaries and the covariance behind mirror-eval roll's truth-noise estimate.

#include "error_stats.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace {

using namespace mirror_eval;

TEST(ErrorStats, MeanWithinAndPercentile)
{
    const ErrorStats e{"e", {4.0, 1.0, 3.0, 2.0}};
    EXPECT_DOUBLE_EQ(e.mean(), 2.5);
    EXPECT_DOUBLE_EQ(e.within(2.0), 0.5);
    EXPECT_DOUBLE_EQ(e.percentile(0.5), 3.0);
    const ErrorStats none{"none", {}};
    EXPECT_EQ(none.mean(), 0.0);
    EXPECT_EQ(none.within(1.0), 0.0);
    EXPECT_EQ(none.percentile(0.9), 0.0);
}

TEST(ErrorStats, CovarianceIsTheSampleOneAndZeroWhenUndefined)
{
    EXPECT_DOUBLE_EQ(covarianceOf({1.0, 2.0, 3.0}, {2.0, 4.0, 6.0}), 2.0);
    EXPECT_DOUBLE_EQ(covarianceOf({1.0, 2.0, 3.0}, {3.0, 2.0, 1.0}), -1.0);
    EXPECT_EQ(covarianceOf({1.0}, {1.0}), 0.0);
    EXPECT_EQ(covarianceOf({1.0, 2.0}, {1.0}), 0.0);
}

// The three-cornered hat as mirror-eval roll uses it: two measurements of the same quantity with
// independent errors covary by the quantity's variance, so a variance less that covariance is the
// measurement's own noise.
TEST(ErrorStats, CovarianceSeparatesAMeasurementsNoiseFromWhatItMeasures)
{
    std::mt19937 rng(4);
    std::normal_distribution<double> real(0.0, 3.0), noisy(0.0, 4.0), sharp(0.0, 1.0);
    std::vector<double> a, b;
    for (int i = 0; i < 20000; ++i) {
        const double r = real(rng);
        a.push_back(r + noisy(rng));
        b.push_back(r + sharp(rng));
    }
    EXPECT_NEAR(covarianceOf(a, b), 9.0, 0.5);
    EXPECT_NEAR(covarianceOf(a, a) - covarianceOf(a, b), 16.0, 0.8);
}

}  // namespace
