// Fixed-point colour spaces against the double-precision reference (color_spaces.hpp), densely
// over the RGB cube: every 3rd value per channel (0, 3, ..., 255; 636 056 colours) plus every
// colour with a channel at 0, 1 or 255, where the spaces are least stable. The bounds asserted
// here are the ones documented in color_spaces_fixed.hpp.
#include "vision/color_spaces_fixed.hpp"

#include "vision/chromaticity.hpp"
#include "vision/color_spaces.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

namespace {

using vision::ColorSpace;
using vision::FixedColorSpaces;

const FixedColorSpaces& fixed()
{
    static const auto* f = new FixedColorSpaces();
    return *f;
}

/// The dense sample of the cube described above.
void forCube(const std::function<void(int, int, int)>& f)
{
    std::vector<int> values;
    for (int v = 0; v < 256; v += 3)
        values.push_back(v);
    for (int r : values)
        for (int g : values)
            for (int b : values)
                f(r, g, b);
    // Edges of the cube at full resolution along one channel.
    for (int v = 0; v < 256; ++v)
        for (int e : {0, 1, 255})
            for (int w : {0, 1, 2, 128, 254, 255}) {
                f(v, e, w);
                f(e, v, w);
                f(w, e, v);
            }
}

double circularDiff(double a, double b, double turn)
{
    double d = std::fmod(std::abs(a - b), turn);
    return std::min(d, turn - d);
}

TEST(FixedColorSpaces, C1C2C3WithinHalfAUnit)
{
    double worst = 0;
    forCube([&](int r, int g, int b) {
        const auto ref = vision::convertReference(ColorSpace::C1C2C3, r, g, b);
        const auto got = fixed().c1c2c3(r, g, b);
        for (int k = 0; k < 3; ++k)
            worst = std::max(worst, std::abs(got[k] - ref[k]));
    });
    EXPECT_LE(worst, 0.5 + 1e-9);
    RecordProperty("c1c2c3_max_error", std::to_string(worst));
}

TEST(FixedColorSpaces, HsvHueAndSaturationWithinHalfAUnit)
{
    double worstHue = 0, worstSat = 0;
    forCube([&](int r, int g, int b) {
        const auto ref = vision::convertReference(ColorSpace::Hsv, r, g, b);
        const double hue = fixed().hsvHue(r, g, b) / double{FixedColorSpaces::kHueUnitsPerDegree};
        worstHue = std::max(worstHue, circularDiff(hue, ref[0], 360.0));
        worstSat = std::max(worstSat, std::abs(fixed().hsvSaturation(r, g, b) - ref[1]));
        const int h = fixed().hsvHue(r, g, b);
        ASSERT_TRUE(h >= -11520 && h < 11520) << h;
    });
    EXPECT_LE(worstHue * FixedColorSpaces::kHueUnitsPerDegree, 0.5 + 1e-9);
    EXPECT_LE(worstSat, 0.5 + 1e-9);
}

TEST(FixedColorSpaces, SaturationIsExactlyTheChromaticityStyleRounding)
{
    for (int mx = 0; mx < 256; ++mx)
        for (int mn = 0; mn <= mx; ++mn)
            ASSERT_EQ(fixed().hsvSaturation(mx, mn, mn),
                      vision::ChromaticityTable::exact(mx - mn, mx));
}

TEST(FixedColorSpaces, GaussianInvariantsWithin055OfAQ12Unit)
{
    double worst = 0;
    forCube([&](int r, int g, int b) {
        const auto ref = vision::convertReference(ColorSpace::GaussianDerivative, r, g, b);
        const auto got = fixed().gaussianInvariants(r, g, b);
        for (int k = 0; k < 2; ++k)
            worst =
                std::max(worst, std::abs(got[k] - ref[k + 1] * FixedColorSpaces::kInvariantOne));
    });
    EXPECT_LE(worst, 0.55);
}

TEST(FixedColorSpaces, LogHueWithinSixTenthsOfAUnitOffTheSingularSet)
{
    double worst = 0;
    long singular = 0;
    forCube([&](int r, int g, int b) {
        const int h = fixed().logHue(r, g, b);
        const long r1 = std::max(r, 1), g1 = std::max(g, 1), b1 = std::max(b, 1);
        if (r1 * g1 == b1 * b1) {
            // Denominator exactly 0: the reference's sign follows double rounding. Ours is
            // defined: +-90 degrees by the numerator's sign, 0 for grey.
            ++singular;
            const int expected = r1 > g1 ? 5760 : (r1 < g1 ? -5760 : 0);
            ASSERT_EQ(h, expected) << r << "," << g << "," << b;
            return;
        }
        const double ref = vision::convertReference(ColorSpace::LogHue, r, g, b)[0];
        worst = std::max(worst, std::abs(h - ref * FixedColorSpaces::kHueUnitsPerDegree));
    });
    EXPECT_GT(singular, 0);
    EXPECT_LE(worst, 0.6);
}

}  // namespace
