#include "vision/card_color_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace vision;

namespace {

struct Planes {
    ImageBuffer r{8, 4, PixelFormat::Gray8}, g{8, 4, PixelFormat::Gray8},
        b{8, 4, PixelFormat::Gray8};
    ChromaticityPlanes view() { return {r.view(), g.view(), b.view()}; }
};

}  // namespace

TEST(CardColorModel, TrainsMeanAndSigmaWithFloor)
{
    Planes p;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            p.r.view().row(y)[x] = static_cast<std::uint8_t>(x < 4 ? 100 : 110);  // sigma 5
            p.g.view().row(y)[x] = 80;                                            // sigma 0
            p.b.view().row(y)[x] = 75;
        }
    CardColorModel m;
    ASSERT_TRUE(trainColorModel(p.view(), {0, 0, 8, 4}, 2.f, m));
    EXPECT_TRUE(m.valid);
    EXPECT_FLOAT_EQ(m.mean[0], 105.f);
    EXPECT_FLOAT_EQ(m.sigma[0], 5.f);
    EXPECT_FLOAT_EQ(m.mean[1], 80.f);
    EXPECT_FLOAT_EQ(m.sigma[1], 2.f);  // floored
    CardColorModel untouched;
    EXPECT_FALSE(trainColorModel(p.view(), {20, 20, 5, 5}, 2.f, untouched));
    EXPECT_FALSE(untouched.valid);
    // Clipped region: only the left half.
    ASSERT_TRUE(trainColorModel(p.view(), {-4, -4, 8, 20}, 2.f, m));
    EXPECT_FLOAT_EQ(m.mean[0], 100.f);
}

TEST(CardColorModel, BoundsEqualTheStrictGaussianTest)
{
    CardColorModel m;
    m.mean[0] = 100.3f;
    m.sigma[0] = 2.f;
    m.mean[1] = 10.f;
    m.sigma[1] = 5.f;
    m.mean[2] = 250.f;
    m.sigma[2] = 4.f;
    m.valid = true;
    const float t = 2.5f;
    const ColorBounds b = colorBounds(m, t);
    for (int c = 0; c < 3; ++c)
        for (int x = 0; x < 256; ++x) {
            const bool expected = std::fabs(float(x) - m.mean[c]) < t * m.sigma[c];
            const bool got = x >= b.lo[c] && x <= b.hi[c];
            EXPECT_EQ(got, expected) << "channel " << c << " x " << x;
        }
    EXPECT_TRUE(matchesColor(b, 100, 10, 250));
    EXPECT_FALSE(matchesColor(b, 106, 10, 250));
    EXPECT_FALSE(matchesColor(colorBounds(CardColorModel{}, t), 0, 0, 0));
}

TEST(CardColorModel, JoinedBoundsHoldBoth)
{
    ColorBounds a, b;
    a.lo[0] = 10, a.hi[0] = 20, a.lo[1] = 50, a.hi[1] = 60, a.lo[2] = 1, a.hi[2] = 0;  // 2: empty
    b.lo[0] = 15, b.hi[0] = 30, b.lo[1] = 70, b.hi[1] = 80, b.lo[2] = 5, b.hi[2] = 9;
    const ColorBounds j = joinedBounds(a, b);
    EXPECT_EQ(j.lo[0], 10);
    EXPECT_EQ(j.hi[0], 30);
    EXPECT_EQ(j.lo[1], 50);  // the gap between them too: bounds are one range a channel
    EXPECT_EQ(j.hi[1], 80);
    EXPECT_EQ(j.lo[2], 5);
    EXPECT_EQ(j.hi[2], 9);
    EXPECT_TRUE(matchesColor(j, 25, 65, 7));
    EXPECT_FALSE(matchesColor(j, 25, 65, 10));
}

TEST(CardColorModel, UpdateFormula)
{
    CardColorModel trained, prev, cur;
    trained.valid = prev.valid = cur.valid = true;
    for (int c = 0; c < 3; ++c) {
        trained.mean[c] = 100.f;
        trained.sigma[c] = 4.f;
        prev.mean[c] = 110.f;
        prev.sigma[c] = 6.f;
        cur.mean[c] = 130.f;
        cur.sigma[c] = 10.f;
    }
    const float a = 0.25f, b = 0.75f;
    const CardColorModel out = blendColorModel(trained, prev, cur, a, b);
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(out.mean[c], a * 100.f + (1 - a) * (b * 110.f + (1 - b) * 130.f));
        EXPECT_FLOAT_EQ(out.sigma[c], a * 4.f + (1 - a) * (b * 6.f + (1 - b) * 10.f));
    }
    // a = 1 anchors to training; a = 0, b = 1 keeps the previous model.
    EXPECT_FLOAT_EQ(blendColorModel(trained, prev, cur, 1.f, 0.3f).mean[0], 100.f);
    EXPECT_FLOAT_EQ(blendColorModel(trained, prev, cur, 0.f, 1.f).mean[0], 110.f);
    // Repeated updates with a > 0 stay bounded near training even when the current runs away.
    CardColorModel m = trained;
    for (int i = 0; i < 200; ++i)
        m = blendColorModel(trained, m, cur, a, b);
    EXPECT_NEAR(m.mean[0], 100.f + (1 - a) * (1 - b) * 30.f / (1 - (1 - a) * b), 1e-3f);
}

// colorTest's vectorised loop against matchesColor, pixel by pixel: random planes and bands (empty,
// full and ordinary ones), regions whose start and width leave every tail of a 16-pixel step, and
// the mask outside the region untouched.
TEST(CardColorModel, ColorTestIsMatchesColorEverywhere)
{
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> byte(0, 255);
    constexpr int kW = 53, kH = 3;
    ImageBuffer r(kW, kH, PixelFormat::Gray8), g(kW, kH, PixelFormat::Gray8),
        b(kW, kH, PixelFormat::Gray8), mask(kW, kH, PixelFormat::Gray8);
    const ChromaticityPlanes planes{r.view(), g.view(), b.view()};
    for (int trial = 0; trial < 60; ++trial) {
        for (const ImageView v : {r.view(), g.view(), b.view(), mask.view()})
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x)
                    v.row(y)[x] = static_cast<std::uint8_t>(byte(rng));
        ColorBounds bounds;
        for (int c = 0; c < 3; ++c) {
            const int lo = byte(rng) / 2, hi = lo + byte(rng) / 2;
            bounds.lo[c] = static_cast<std::uint8_t>(lo);
            bounds.hi[c] = static_cast<std::uint8_t>(hi);
        }
        if (trial % 4 == 1)
            std::swap(bounds.lo[trial % 3], bounds.hi[trial % 3]);  // empty unless lo == hi
        if (trial % 4 == 2)
            bounds = ColorBounds{{0, 0, 0}, {255, 255, 255}};
        const Rect region{trial % 17, trial % 2, kW - trial % 17 - trial % 5, kH - trial % 2};
        ImageBuffer before(kW, kH, PixelFormat::Gray8);
        std::copy_n(mask.view().data, mask.bytes(), before.view().data);
        colorTest(planes, bounds, region, mask.view());
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const bool inside = x >= region.x && x < region.x + region.width && y >= region.y &&
                                    y < region.y + region.height;
                const std::uint8_t want =
                    inside ? (matchesColor(bounds, r.view().row(y)[x], g.view().row(y)[x],
                                           b.view().row(y)[x])
                                  ? 255
                                  : 0)
                           : before.view().row(y)[x];
                ASSERT_EQ(mask.view().row(y)[x], want)
                    << "trial " << trial << " at " << x << "," << y;
            }
    }
}

TEST(CardColorModel, ColorTestAndMeasureOverAMask)
{
    Planes p;
    ImageBuffer mask(8, 4, PixelFormat::Gray8);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            const bool card = x >= 2 && x < 6;
            p.r.view().row(y)[x] = card ? 40 : 85;
            p.g.view().row(y)[x] = card ? 60 : 85;
            p.b.view().row(y)[x] = card ? 155 : 85;
        }
    CardColorModel m;
    ASSERT_TRUE(trainColorModel(p.view(), {2, 0, 4, 4}, 2.f, m));
    colorTest(p.view(), colorBounds(m, 3.f), {0, 0, 8, 4}, mask.view());
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            EXPECT_EQ(mask.view().row(y)[x], (x >= 2 && x < 6) ? 255 : 0);
    CardColorModel measured;
    ASSERT_TRUE(measureColorModel(p.view(), mask.view(), {0, 0, 8, 4}, 1, 2.f, 4, measured));
    EXPECT_FLOAT_EQ(measured.mean[2], 155.f);
    EXPECT_FLOAT_EQ(colorFit(m, measured, 3.f), 1.f);
    EXPECT_FALSE(measureColorModel(p.view(), mask.view(), {0, 0, 2, 4}, 1, 2.f, 1, measured));
}
