// RollByImageSymmetry: a synthetic mirror-symmetric face pattern rotated on screen by known
// angles comes back within half a degree (with the right sign, also with the box off the face's
// axis and near the ends of the angle range; by each cue alone within a degree), no allocation per
// estimate, flat images give no confidence, bad input and bad options; the coarse scan's
// whole-axis pair sum gives the reference loop's bits.
#include "vision/roll_by_image_symmetry.hpp"

#include "alloc_counter.hpp"
#include "symmetry_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

using namespace vision;

namespace {

constexpr double kPi = 3.14159265358979323846;

double blob(double u, double v, double cu, double cv, double su, double sv)
{
    const double a = (u - cu) / su, b = (v - cv) / sv;
    return std::exp(-0.5 * (a * a + b * b));
}

// A face-like pattern, mirror-symmetric about u = 0 (upright face coordinates, v down): a bright
// oval on a darker background, dark eyes and brows, a nose shadow and a mouth.
double face(double u, double v)
{
    double g = 70.0 + 90.0 / (1.0 + std::exp(((u * u) / 400.0 + (v * v) / 676.0 - 1.0) * 8.0));
    g -= 80.0 * (blob(u, v, -9.0, -6.0, 3.0, 2.0) + blob(u, v, 9.0, -6.0, 3.0, 2.0));
    g -= 40.0 * (blob(u, v, -9.0, -11.0, 4.5, 1.2) + blob(u, v, 9.0, -11.0, 4.5, 1.2));
    g -= 35.0 * (blob(u, v, -2.5, 5.0, 1.5, 1.5) + blob(u, v, 2.5, 5.0, 1.5, 1.5));
    g -= 70.0 * blob(u, v, 0.0, 12.0, 6.0, 1.6);
    return g;
}

// The face turned clockwise on screen (y down) by `degrees` about `centre`.
ImageBuffer rotatedFace(int w, int h, Point2f centre, double degrees)
{
    ImageBuffer img(w, h, PixelFormat::Gray8);
    const double c = std::cos(degrees * kPi / 180.0);
    const double s = std::sin(degrees * kPi / 180.0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double dx = x + 0.5 - centre.x;
            const double dy = y + 0.5 - centre.y;
            const double u = c * dx + s * dy;
            const double v = -s * dx + c * dy;
            img.view().row(y)[x] =
                static_cast<std::uint8_t>(std::lrint(std::clamp(face(u, v), 0.0, 255.0)));
        }
    }
    return img;
}

}  // namespace

TEST(RollByImageSymmetry, RotatedSymmetricFaceComesBackWithinHalfADegree)
{
    RollByImageSymmetry estimator;
    const Point2f centre{60.f, 60.f};
    for (double degrees : {-33.0, -21.7, -10.0, -3.3, 0.0, 4.6, 12.5, 19.0, 27.4, 34.0}) {
        const ImageBuffer img = rotatedFace(120, 120, centre, degrees);
        const RollEstimate e = estimator.estimate(img.view(), centre, 56.f);
        EXPECT_NEAR(e.rollDegrees, degrees, 0.5) << "rotated by " << degrees;
        EXPECT_GT(e.confidence, 0.3f) << "rotated by " << degrees;
        EXPECT_LT(e.symmetryDistance, 0.2f) << "rotated by " << degrees;
        EXPECT_STREQ(estimator.lastError(), "");
    }
}

TEST(RollByImageSymmetry, BoxOffTheFaceAxis)
{
    // Detector boxes are not centred on the face: 4 px (7% of the box) sideways and 3 px down.
    RollByImageSymmetry estimator;
    const Point2f faceCentre{60.f, 60.f};
    for (double degrees : {-24.0, 8.0, 22.5}) {
        const ImageBuffer img = rotatedFace(120, 120, faceCentre, degrees);
        const RollEstimate e = estimator.estimate(img.view(), {64.f, 63.f}, 56.f);
        EXPECT_NEAR(e.rollDegrees, degrees, 0.5) << "rotated by " << degrees;
    }
}

TEST(RollByImageSymmetry, RollNearTheEndOfTheRangeIsKept)
{
    // The coarse scan only takes minima where the curve rises again on both sides; it reaches a
    // step beyond each end of [-35, 35] so a roll just inside an end still qualifies.
    RollByImageSymmetry estimator;
    const Point2f centre{60.f, 60.f};
    for (double degrees : {-34.6, 34.6}) {
        const ImageBuffer img = rotatedFace(120, 120, centre, degrees);
        EXPECT_NEAR(estimator.estimate(img.view(), centre, 56.f).rollDegrees, degrees, 0.5)
            << "rotated by " << degrees;
    }
}

TEST(RollByImageSymmetry, EachCueAloneFindsTheRoll)
{
    // Symmetry only (no row term), and the row term dominating: both recover the synthetic face,
    // whose halves mirror each other and whose features run along its rows.
    RollByImageSymmetryOptions symmetryOnly;
    symmetryOnly.rowCoherenceWeight = 0.f;
    RollByImageSymmetryOptions rowsFirst;
    rowsFirst.rowCoherenceWeight = 4.f;
    rowsFirst.rowCueBelowConfidence = 2.f;  // always (the synthetic face is clearly symmetric)
    for (const auto& options : {symmetryOnly, rowsFirst}) {
        RollByImageSymmetry estimator(options);
        const Point2f centre{60.f, 60.f};
        for (double degrees : {-18.0, 7.3, 26.0}) {
            const ImageBuffer img = rotatedFace(120, 120, centre, degrees);
            EXPECT_NEAR(estimator.estimate(img.view(), centre, 56.f).rollDegrees, degrees, 1.0)
                << "rotated by " << degrees << ", row weight " << options.rowCoherenceWeight;
        }
    }
}

TEST(RollByImageSymmetry, AsymmetryIsLowestAtTheRoll)
{
    RollByImageSymmetry estimator;
    const Point2f centre{60.f, 60.f};
    const ImageBuffer img = rotatedFace(120, 120, centre, 15.0);
    const float atRoll = estimator.asymmetry(img.view(), centre, 56.f, 15.f);
    EXPECT_GE(atRoll, 0.f);
    EXPECT_LT(atRoll, estimator.asymmetry(img.view(), centre, 56.f, 5.f));
    EXPECT_LT(atRoll, estimator.asymmetry(img.view(), centre, 56.f, 25.f));
    EXPECT_LT(estimator.asymmetry(img.view(), centre, 56.f, std::nanf("")), 0.f);
}

TEST(RollByImageSymmetry, FlatImageHasNoConfidence)
{
    ImageBuffer img(80, 80, PixelFormat::Gray8);
    for (int y = 0; y < 80; ++y)
        for (int x = 0; x < 80; ++x)
            img.view().row(y)[x] = 100;
    RollByImageSymmetry estimator;
    const RollEstimate e = estimator.estimate(img.view(), {40.f, 40.f}, 40.f);
    EXPECT_EQ(e.confidence, 0.f);
}

TEST(RollByImageSymmetry, NoAllocationPerEstimate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting unavailable";
    const Point2f centre{60.f, 60.f};
    const ImageBuffer img = rotatedFace(120, 120, centre, 11.0);
    RollByImageSymmetry estimator;
    testing_support::AllocationScope scope;
    const RollEstimate e = estimator.estimate(img.view(), centre, 56.f);
    estimator.estimate(ConstImageView{}, centre, 56.f);  // the error path too
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
    EXPECT_NEAR(e.rollDegrees, 11.0, 0.5);
}

TEST(RollByImageSymmetry, BadInputGivesNoConfidenceAndSaysWhy)
{
    RollByImageSymmetry estimator;
    const ImageBuffer img = rotatedFace(64, 64, {32.f, 32.f}, 0.0);
    ImageBuffer rgb(64, 64, PixelFormat::RGB24);
    const float nan = std::numeric_limits<float>::quiet_NaN();

    RollEstimate e = estimator.estimate(ConstImageView{}, {32.f, 32.f}, 30.f);
    EXPECT_EQ(e.confidence, 0.f);
    EXPECT_EQ(e.rollDegrees, 0.f);
    EXPECT_STRNE(estimator.lastError(), "");

    e = estimator.estimate(rgb.view(), {32.f, 32.f}, 30.f);
    EXPECT_EQ(e.confidence, 0.f);
    EXPECT_STRNE(estimator.lastError(), "");

    for (float side : {0.f, -5.f, 2.f, nan, std::numeric_limits<float>::infinity()}) {
        e = estimator.estimate(img.view(), {32.f, 32.f}, side);
        EXPECT_EQ(e.confidence, 0.f) << side;
        EXPECT_STRNE(estimator.lastError(), "") << side;
    }
    e = estimator.estimate(img.view(), {nan, 32.f}, 30.f);
    EXPECT_EQ(e.confidence, 0.f);
    // A square far beyond the image (warpUpright refuses it).
    e = estimator.estimate(img.view(), {1e6f, 32.f}, 30.f);
    EXPECT_EQ(e.confidence, 0.f);
    EXPECT_STRNE(estimator.lastError(), "");

    // A good call clears the error.
    e = estimator.estimate(img.view(), {32.f, 32.f}, 30.f);
    EXPECT_STREQ(estimator.lastError(), "");
}

TEST(RollByImageSymmetry, InvalidOptionsThrowOneLine)
{
    auto make = [](auto change) {
        RollByImageSymmetryOptions o;
        change(o);
        RollByImageSymmetry estimator(o);
    };
    EXPECT_THROW(make([](auto& o) { o.patchSize = 4; }), std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.supersample = 0; }), std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.boxScale = 0.f; }), std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.coarseStepDegrees = 0.f; }), std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.maxDegrees = -40.f; }), std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.coarseStepDegrees = 0.01f; }), std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.maxAxisOffsetFraction = 0.5f; }), std::invalid_argument);
    EXPECT_THROW(make([](auto& o) {
                     o.regionTop = 0.9f;
                     o.regionBottom = 0.5f;
                 }),
                 std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.gradientSaturation = -1.f; }), std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.rowCoherenceWeight = -0.5f; }), std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.rowCoherenceWeight = std::nanf(""); }),
                 std::invalid_argument);
    EXPECT_THROW(make([](auto& o) { o.rowCueBelowConfidence = std::nanf(""); }),
                 std::invalid_argument);
    EXPECT_NO_THROW(make([](auto&) {}));
}

TEST(RollByImageSymmetry, WholeAxisPairsGiveTheReferenceBits)
{
    // The coarse scan's shortcut (symmetry_pairs.hpp) against the reference loop: every whole
    // axis of a 40-pixel patch, on planes of saturated gradients with zeros and both signs.
    constexpr int n = 40;
    std::vector<float> a(n * n), b(n * n), weight(2 * n + 32, 1.f);
    std::uint32_t state = 12345u;
    const auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        const int v = static_cast<int>(state >> 24) - 128;  // -128..127, zero included
        const float g = static_cast<float>(v) * 0.37f;
        return g / (1.f + std::fabs(g) / 8.f);
    };
    for (int trial = 0; trial < 4; ++trial) {
        std::generate(a.begin(), a.end(), next);
        std::generate(b.begin(), b.end(), next);
        if (trial == 3)
            std::fill(a.begin(), a.end(), 0.f);  // half flat
        const symmetry_detail::PairPlanes planes{a.data(), b.data(), weight.data(), n, 4, 38,
                                                 n - 2, true};
        for (int a2 = 20; a2 <= 58; ++a2) {
            const int xFirst = std::max({1, static_cast<int>(std::ceil(0.5f * a2 - 13.6f)),
                                         a2 - (n - 3)});
            const int xEnd = (a2 + 1) / 2;
            if (xFirst >= xEnd)
                continue;
            const float reference =
                symmetry_detail::pairAsymmetry(planes, xFirst, xEnd, static_cast<float>(a2));
            // The dispatched sum is NEON on aarch64 (the arm64 tests under qemu), scalar elsewhere.
            const float fast = symmetry_detail::pairAsymmetryWholeAxis(planes, xFirst, xEnd, a2);
            EXPECT_EQ(std::bit_cast<std::uint32_t>(reference), std::bit_cast<std::uint32_t>(fast))
                << "trial " << trial << " a2 " << a2;
            const float scalar =
                symmetry_detail::pairAsymmetryWholeAxisScalar(planes, xFirst, xEnd, a2);
            EXPECT_EQ(std::bit_cast<std::uint32_t>(reference), std::bit_cast<std::uint32_t>(scalar))
                << "trial " << trial << " a2 " << a2;
            // Uniform weights left out (null) on a fractional axis: the same bits too.
            symmetry_detail::PairPlanes unweighted = planes;
            unweighted.weight = nullptr;
            const float half = static_cast<float>(a2) + 0.37f;
            EXPECT_EQ(std::bit_cast<std::uint32_t>(
                          symmetry_detail::pairAsymmetry(planes, xFirst, xEnd - 1, half)),
                      std::bit_cast<std::uint32_t>(
                          symmetry_detail::pairAsymmetry(unweighted, xFirst, xEnd - 1, half)))
                << "trial " << trial << " a2 " << half;
        }
    }
}
