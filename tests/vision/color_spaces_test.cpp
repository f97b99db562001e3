// The double-precision colour-space reference (ch. 3, METHOD.md §1): known values, the values
// defined at the unstable points, and the invariance properties the illumination experiment tests.
#include "vision/color_spaces.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>

namespace {

using vision::ColorSpace;
using vision::convertReference;

std::array<double, 3> conv(ColorSpace s, double r, double g, double b)
{
    return convertReference(s, r, g, b);
}

void expectNear3(const std::array<double, 3>& got, const std::array<double, 3>& want, double tol,
                 const std::string& what)
{
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(got[i], want[i], tol) << what << " component " << i;
}

TEST(ColorSpaceInfo, TableMatchesTheEnumAndNamesAreUnique)
{
    const auto spaces = vision::colorSpaces();
    ASSERT_EQ(spaces.size(), static_cast<std::size_t>(vision::kColorSpaceCount));
    std::set<std::string> names;
    for (std::size_t i = 0; i < spaces.size(); ++i) {
        EXPECT_EQ(static_cast<std::size_t>(spaces[i].space), i);
        EXPECT_EQ(&vision::colorSpaceInfo(spaces[i].space), &spaces[i]);
        EXPECT_TRUE(names.insert(spaces[i].name).second) << spaces[i].name;
        ASSERT_GE(spaces[i].components, 1);
        ASSERT_LE(spaces[i].components, 3);
        int chromatic = 0;
        for (int c = 0; c < spaces[i].components; ++c) {
            EXPECT_NE(std::string(spaces[i].componentNames[c]), "");
            chromatic += spaces[i].chromatic[c] ? 1 : 0;
        }
        EXPECT_GE(chromatic, 1) << spaces[i].name;
    }
    // The components ch. 3 drops from the invariance and DP measures.
    EXPECT_FALSE(vision::colorSpaceInfo(ColorSpace::Yiq).chromatic[0]);
    EXPECT_FALSE(vision::colorSpaceInfo(ColorSpace::Hsv).chromatic[2]);
    EXPECT_FALSE(vision::colorSpaceInfo(ColorSpace::Hls).chromatic[1]);
    EXPECT_FALSE(vision::colorSpaceInfo(ColorSpace::Cielab).chromatic[0]);
    EXPECT_FALSE(vision::colorSpaceInfo(ColorSpace::GaussianDerivative).chromatic[0]);
    EXPECT_STREQ(vision::colorSpaceInfo(ColorSpace::LogHue).name, "loghue");
    EXPECT_EQ(vision::colorSpaceInfo(ColorSpace::LogHue).components, 1);
}

TEST(ColorSpaces, RgbIsTheInput)
{
    expectNear3(conv(ColorSpace::Rgb, 12, 34, 250), {12, 34, 250}, 0, "rgb");
}

TEST(ColorSpaces, YiqPrimariesAndWhite)
{
    expectNear3(conv(ColorSpace::Yiq, 255, 0, 0), {0.299 * 255, 0.596 * 255, 0.212 * 255}, 1e-9,
                "red");
    expectNear3(conv(ColorSpace::Yiq, 0, 255, 0), {0.587 * 255, -0.275 * 255, -0.523 * 255}, 1e-9,
                "green");
    expectNear3(conv(ColorSpace::Yiq, 0, 0, 255), {0.114 * 255, -0.321 * 255, 0.311 * 255}, 1e-9,
                "blue");
    // White and every grey: Y = the grey, I = Q = 0.
    for (double v : {0.0, 77.0, 255.0})
        expectNear3(conv(ColorSpace::Yiq, v, v, v), {v, 0, 0}, 1e-9, "grey");
}

TEST(ColorSpaces, HsvAndHlsKnownValues)
{
    // Hue in [-180, 180): red 0, yellow 60, green 120, blue -120, magenta -60, cyan -180.
    struct Case {
        double r, g, b, hue;
    };
    for (const Case& c :
         {Case{255, 0, 0, 0}, Case{255, 255, 0, 60}, Case{0, 255, 0, 120}, Case{0, 0, 255, -120},
          Case{255, 0, 255, -60}, Case{0, 255, 255, -180}, Case{255, 128, 0, 60.0 * 128 / 255}}) {
        EXPECT_NEAR(conv(ColorSpace::Hsv, c.r, c.g, c.b)[0], c.hue, 1e-9) << c.r << c.g << c.b;
        EXPECT_NEAR(conv(ColorSpace::Hls, c.r, c.g, c.b)[0], c.hue, 1e-9) << c.r << c.g << c.b;
    }
    expectNear3(conv(ColorSpace::Hsv, 255, 0, 0), {0, 255, 255}, 1e-9, "hsv red");
    expectNear3(conv(ColorSpace::Hls, 255, 0, 0), {0, 127.5, 255}, 1e-9, "hls red");
    // Dark red (L < .5) and light red (L > .5) take the two branches of the HLS saturation.
    expectNear3(conv(ColorSpace::Hls, 102, 51, 51), {0, 76.5, 255.0 * 0.2 / 0.6}, 1e-9, "hls dark");
    expectNear3(conv(ColorSpace::Hls, 255, 204, 204), {0, 229.5, 255.0 * 0.2 / 0.2}, 1e-9,
                "hls light");
    // Greys: hue and saturation defined as 0; white and black too.
    for (double v : {0.0, 1.0, 128.0, 255.0}) {
        expectNear3(conv(ColorSpace::Hsv, v, v, v), {0, 0, v}, 1e-12, "hsv grey");
        expectNear3(conv(ColorSpace::Hls, v, v, v), {0, v, 0}, 1e-12, "hls grey");
    }
}

TEST(ColorSpaces, HueStaysInItsHalfOpenRangeAndWrapsNearTeal)
{
    // Around teal (hue 180) the value jumps from just below 180 to -180, never reaching 180.
    const double below = conv(ColorSpace::Hsv, 0, 255, 250)[0];  // green side of cyan
    const double above = conv(ColorSpace::Hsv, 0, 250, 255)[0];  // blue side of cyan
    EXPECT_GT(below, 170.0);
    EXPECT_LT(below, 180.0);
    EXPECT_GE(above, -180.0);
    EXPECT_LT(above, -170.0);
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> u(0, 255);
    for (int i = 0; i < 20000; ++i) {
        const double r = u(rng), g = u(rng), b = u(rng);
        for (ColorSpace s : {ColorSpace::Hsv, ColorSpace::Hls}) {
            const double h = conv(s, r, g, b)[0];
            ASSERT_GE(h, -180.0);
            ASSERT_LT(h, 180.0);
        }
    }
}

TEST(ColorSpaces, CielabMatchesPublishedSrgbD65Values)
{
    // Published sRGB (D65, 2 deg) L*a*b* of the primaries, secondaries and white (e.g. Bruce
    // Lindbloom's calculator). Gamma does not matter at 0 and 255.
    struct Case {
        double r, g, b, l, a, bb;
    };
    for (const Case& c :
         {Case{255, 0, 0, 53.2408, 80.0925, 67.2032}, Case{0, 255, 0, 87.7347, -86.1827, 83.1793},
          Case{0, 0, 255, 32.2970, 79.1875, -107.8602},
          Case{255, 255, 0, 97.1393, -21.5537, 94.4780},
          Case{0, 255, 255, 91.1132, -48.0875, -14.1312},
          Case{255, 0, 255, 60.3242, 98.2343, -60.8249}, Case{255, 255, 255, 100.0, 0.0, 0.0},
          Case{0, 0, 0, 0.0, 0.0, 0.0}})
        expectNear3(
            conv(ColorSpace::Cielab, c.r, c.g, c.b), {c.l, c.a, c.bb}, 0.01,
            "lab " + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b));
}

TEST(ColorSpaces, CielabGreysAreNeutralWithBothLightnessSegments)
{
    // White = XYZ of RGB (1,1,1), so a* = b* = 0 for every grey; RGB taken as linear.
    for (int v = 0; v <= 255; ++v) {
        const auto lab = conv(ColorSpace::Cielab, v, v, v);
        const double y = v / 255.0;
        const double l = y > 0.008856 ? 116.0 * std::cbrt(y) - 16.0 : 903.3 * y;
        EXPECT_NEAR(lab[0], l, 1e-9) << v;
        EXPECT_NEAR(lab[1], 0.0, 1e-9) << v;
        EXPECT_NEAR(lab[2], 0.0, 1e-9) << v;
    }
    // The linear segment and the cube root meet (nearly) continuously at Y = 0.008856.
    const double v = 0.008856 * 255.0;
    EXPECT_NEAR(conv(ColorSpace::Cielab, v - 1e-6, v - 1e-6, v - 1e-6)[0],
                conv(ColorSpace::Cielab, v + 1e-6, v + 1e-6, v + 1e-6)[0], 0.01);
}

TEST(ColorSpaces, ChromaticityKnownValuesAndBlack)
{
    expectNear3(conv(ColorSpace::Chromaticity, 255, 0, 0), {255, 0, 0}, 1e-12, "red");
    expectNear3(conv(ColorSpace::Chromaticity, 10, 20, 30), {42.5, 85, 127.5}, 1e-12, "mix");
    for (double v : {1.0, 128.0, 255.0})
        expectNear3(conv(ColorSpace::Chromaticity, v, v, v), {85, 85, 85}, 1e-12, "grey");
    expectNear3(conv(ColorSpace::Chromaticity, 0, 0, 0), {0, 0, 0}, 0, "black");
}

TEST(ColorSpaces, C1c2c3KnownValues)
{
    expectNear3(conv(ColorSpace::C1C2C3, 255, 0, 0), {255, 0, 0}, 1e-9, "red");
    expectNear3(conv(ColorSpace::C1C2C3, 0, 0, 200), {0, 0, 255}, 1e-9, "blue");
    for (double v : {1.0, 128.0, 255.0})
        expectNear3(conv(ColorSpace::C1C2C3, v, v, v), {127.5, 127.5, 127.5}, 1e-9, "grey");
    expectNear3(conv(ColorSpace::C1C2C3, 0, 0, 0), {0, 0, 0}, 0, "black");
    // c1 = atan(R / max(G, B)) in [0, pi/2] scaled to 0..255.
    const double k = 255.0 / (std::numbers::pi / 2.0);
    expectNear3(conv(ColorSpace::C1C2C3, 100, 50, 200),
                {k * std::atan(0.5), k * std::atan(0.25), k * std::atan(2.0)}, 1e-9, "mix");
}

TEST(ColorSpaces, L1l2l3KnownValuesAndGrey)
{
    expectNear3(conv(ColorSpace::L1L2L3, 255, 0, 0), {127.5, 127.5, 0}, 1e-9, "red");
    expectNear3(conv(ColorSpace::L1L2L3, 255, 255, 0), {0, 127.5, 127.5}, 1e-9, "yellow");
    for (double v : {0.0, 90.0, 255.0})
        expectNear3(conv(ColorSpace::L1L2L3, v, v, v), {0, 0, 0}, 0, "grey");
    const auto l = conv(ColorSpace::L1L2L3, 10, 70, 200);
    EXPECT_NEAR(l[0] + l[1] + l[2], 255.0, 1e-9);
}

TEST(ColorSpaces, GaussianDerivativeKnownValues)
{
    // Pure red: E = .06 R, E_l = .30 R, E_ll = .34 R.
    expectNear3(conv(ColorSpace::GaussianDerivative, 255, 0, 0), {0.30 / 0.34, 5.0, 0.34 / 0.06},
                1e-9, "red");
    expectNear3(conv(ColorSpace::GaussianDerivative, 0, 0, 255),
                {-0.35 / 0.17, -0.35 / 0.27, 0.17 / 0.27}, 1e-9, "blue");
    // Grey: E = .96 v, E_l = -.01 v, E_ll = -.09 v.
    expectNear3(conv(ColorSpace::GaussianDerivative, 100, 100, 100),
                {0.01 / 0.09, -0.01 / 0.96, -0.09 / 0.96}, 1e-9, "grey");
    expectNear3(conv(ColorSpace::GaussianDerivative, 0, 0, 0), {0, 0, 0}, 0, "black");
}

TEST(ColorSpaces, LogHueKnownValuesAndSingularities)
{
    // R = e^2 G, B = G: num = 2, den = 2 -> 45 degrees.
    const double g = 20.0;
    EXPECT_NEAR(conv(ColorSpace::LogHue, g * std::exp(2.0), g, g)[0], 45.0, 1e-9);
    // Grey: 0/0 -> 0; black counts as 1,1,1 -> grey.
    EXPECT_EQ(conv(ColorSpace::LogHue, 100, 100, 100)[0], 0.0);
    EXPECT_EQ(conv(ColorSpace::LogHue, 0, 0, 0)[0], 0.0);
    // Zero denominator with a non-zero numerator: the limit +-90.
    // R = 4, G = 1, B = 2: log 4 + 0 - 2 log 2 = 0.
    EXPECT_NEAR(conv(ColorSpace::LogHue, 4, 1, 2)[0], 90.0, 1e-9);
    EXPECT_NEAR(conv(ColorSpace::LogHue, 1, 4, 2)[0], -90.0, 1e-9);
    const auto v = conv(ColorSpace::LogHue, 200, 30, 0);  // zero channel treated as 1
    EXPECT_TRUE(std::isfinite(v[0]));
    EXPECT_EQ(v[1], 0.0);
    EXPECT_EQ(v[2], 0.0);
}

TEST(ColorSpaces, TotalEverywhereIncludingOutOfRangeInput)
{
    const double odd[] = {-5.0, 0.0, 1e-12, 0.5, 1.0, 254.9, 255.0, 300.0, std::nan("")};
    for (const auto& info : vision::colorSpaces())
        for (double r : odd)
            for (double g : odd)
                for (double b : odd) {
                    const auto v = convertReference(info.space, r, g, b);
                    for (int c = 0; c < 3; ++c) {
                        ASSERT_TRUE(std::isfinite(v[c]))
                            << info.name << " " << r << "," << g << "," << b << " c" << c;
                        if (c >= info.components) {
                            ASSERT_EQ(v[c], 0.0) << info.name;
                        }
                    }
                }
    // Out-of-range input is clamped to 0..255.
    expectNear3(conv(ColorSpace::Rgb, -5, 300, 12), {0, 255, 12}, 0, "clamp");
}

TEST(ColorSpaces, ChromaticityAndC1c2c3AreInvariantToScalingYiqIsNot)
{
    // Intensity scaling (R,G,B) -> k (R,G,B) without clipping: eq. 3 of ch. 3.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(4.0, 120.0);  // k r >= 1: no log clamp
    for (int i = 0; i < 2000; ++i) {
        const double r = u(rng), g = u(rng), b = u(rng);
        for (double k : {0.25, 0.5, 2.0}) {
            for (ColorSpace s :
                 {ColorSpace::Chromaticity, ColorSpace::C1C2C3, ColorSpace::L1L2L3}) {
                const auto a = conv(s, r, g, b);
                const auto sk = conv(s, k * r, k * g, k * b);
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(a[c], sk[c], 1e-9) << static_cast<int>(s) << " k=" << k;
            }
            // HSV hue and saturation, HLS hue, and the Gaussian C_l, C_ll cancel the scale too.
            ASSERT_NEAR(conv(ColorSpace::Hsv, r, g, b)[0],
                        conv(ColorSpace::Hsv, k * r, k * g, k * b)[0], 1e-9);
            ASSERT_NEAR(conv(ColorSpace::Hsv, r, g, b)[1],
                        conv(ColorSpace::Hsv, k * r, k * g, k * b)[1], 1e-9);
            ASSERT_NEAR(conv(ColorSpace::GaussianDerivative, r, g, b)[1],
                        conv(ColorSpace::GaussianDerivative, k * r, k * g, k * b)[1], 1e-9);
            ASSERT_NEAR(conv(ColorSpace::LogHue, r, g, b)[0],
                        conv(ColorSpace::LogHue, k * r, k * g, k * b)[0], 1e-9);
            // YIQ: I and Q scale with k (they change unless the colour is grey).
            const auto y = conv(ColorSpace::Yiq, r, g, b);
            const auto yk = conv(ColorSpace::Yiq, k * r, k * g, k * b);
            ASSERT_NEAR(yk[1], k * y[1], 1e-9);
            ASSERT_NEAR(yk[2], k * y[2], 1e-9);
        }
    }
    const auto y = conv(ColorSpace::Yiq, 200, 60, 30);
    const auto y2 = conv(ColorSpace::Yiq, 100, 30, 15);
    EXPECT_GT(std::abs(y[1] - y2[1]), 10.0);
    EXPECT_GT(std::abs(y[2] - y2[2]), 1.0);
    // The HLS saturation is not invariant once lightness passes 0.5.
    EXPECT_GT(
        std::abs(conv(ColorSpace::Hls, 250, 200, 180)[2] - conv(ColorSpace::Hls, 125, 100, 90)[2]),
        10.0);
}

TEST(ColorSpaces, ComponentsStayInTheirDocumentedRanges)
{
    // The bounds documented in color_spaces.cpp (colorlab normalises by them).
    for (int r = 0; r <= 255; r += 15)
        for (int g = 0; g <= 255; g += 15)
            for (int b = 0; b <= 255; b += 15) {
                const auto yiq = conv(ColorSpace::Yiq, r, g, b);
                ASSERT_LE(std::abs(yiq[1]), 151.98 + 1e-9);
                ASSERT_LE(std::abs(yiq[2]), 133.37 + 1e-9);
                const auto lab = conv(ColorSpace::Cielab, r, g, b);
                ASSERT_GE(lab[0], 0.0);
                ASSERT_LE(lab[0], 100.0 + 1e-9);
                ASSERT_GE(lab[1], -128.0);
                ASSERT_LT(lab[1], 128.0);
                ASSERT_GE(lab[2], -128.0);
                ASSERT_LT(lab[2], 128.0);
                for (ColorSpace s :
                     {ColorSpace::Chromaticity, ColorSpace::C1C2C3, ColorSpace::L1L2L3}) {
                    const auto v = conv(s, r, g, b);
                    for (double c : v) {
                        ASSERT_GE(c, 0.0);
                        ASSERT_LE(c, 255.0 + 1e-9);
                    }
                }
                const auto d = conv(ColorSpace::GaussianDerivative, r, g, b);
                ASSERT_GE(d[1], -0.35 / 0.27 - 1e-9);
                ASSERT_LE(d[1], 5.0 + 1e-9);
                ASSERT_GE(d[2], -0.60 / 0.63 - 1e-9);
                ASSERT_LE(d[2], 0.34 / 0.06 + 1e-9);
                const double lh = conv(ColorSpace::LogHue, r, g, b)[0];
                ASSERT_GE(lh, -90.0);
                ASSERT_LE(lh, 90.0);
            }
}

}  // namespace
