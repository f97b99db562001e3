#include "vision/edge_refinement.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace vision;

namespace {

bool inside(const Quad& q, float x, float y)
{
    for (int i = 0; i < 4; ++i) {
        const Point2f a = q[i], b = q[(i + 1) % 4];
        if ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x) < 0)
            return false;
    }
    return true;
}

struct Colours {
    float card[3];
    float ground[3];  ///< plus a slight texture
};
constexpr Colours kBlueOnGrey = {{40.f, 80.f, 200.f}, {120.f, 120.f, 120.f}};

/// A card with anti-aliased edges (4x4 supersampling) on a slightly textured ground (by default a
/// blue card on grey).
ImageBuffer render(const Quad& card, int w, int h, PixelFormat format = PixelFormat::RGB24,
                   const Colours& colours = kBlueOnGrey)
{
    ImageBuffer img(w, h, format);
    const int bpp = bytesPerPixel(format);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int n = 0;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx)
                    n += inside(card, float(x) - 0.375f + 0.25f * float(sx),
                                float(y) - 0.375f + 0.25f * float(sy));
            const float c = float(n) / 16.f;
            const float t = 10.f * std::sin(float(x) * 0.3f) * std::cos(float(y) * 0.2f);
            float rgb[3];
            for (int k = 0; k < 3; ++k) {
                const float g = colours.ground[k] + t;
                rgb[k] = g + c * (colours.card[k] - g);
            }
            std::uint8_t* p = img.view().row(y) + x * bpp;
            for (int k = 0; k < 3; ++k)
                p[k] = static_cast<std::uint8_t>(std::lround(rgb[k]));
        }
    return img;
}

/// A card turned a little in depth and in the image (no edge along a row or column).
constexpr Quad kSkewedCard = {{{52.3f, 41.7f}, {181.6f, 55.2f}, {170.4f, 148.9f}, {45.1f, 131.3f}}};

/// `truth` with each corner 2-3 px off, in a different direction each: a quad to refine.
Quad offsetGuess(const Quad& truth)
{
    Quad guess = truth;
    const float off[4][2] = {{3, 2}, {-2, 3}, {-3, -2}, {2, -3}};
    for (int i = 0; i < 4; ++i)
        guess[i] = {truth[i].x + off[i][0], truth[i].y + off[i][1]};
    return guess;
}

double maxCornerError(const Quad& a, const Quad& b)
{
    double e = 0;
    for (int i = 0; i < 4; ++i)
        e = std::max(e, double(std::hypot(a[i].x - b[i].x, a[i].y - b[i].y)));
    return e;
}

}  // namespace

TEST(EdgeRefinement, SaturationOfAPixel)
{
    const std::uint8_t grey[3] = {90, 90, 90}, red[3] = {200, 0, 0}, black[3] = {0, 0, 0},
                       half[3] = {100, 50, 100};
    EXPECT_EQ(saturation8(grey), 0);
    EXPECT_EQ(saturation8(red), 255);
    EXPECT_EQ(saturation8(black), 0);
    EXPECT_EQ(saturation8(half), 128);  // 255 * 50 / 100 = 127.5, rounded up
}

TEST(EdgeRefinement, FindsTheTrueCornersFromAnOffsetQuad)
{
    const Quad truth = kSkewedCard;
    const ImageBuffer img = render(truth, 240, 190);
    const Quad guess = offsetGuess(truth);  // 2-4 px inside
    EdgeRefinement r;
    ASSERT_TRUE(refineQuad(img.view(), guess, {}, r));
    EXPECT_EQ(r.edgesFitted, 4);
    EXPECT_LT(maxCornerError(r.quad, truth), 0.35);
    // Same answer from XRGB8888 (order-independent saturation).
    const ImageBuffer x = render(truth, 240, 190, PixelFormat::XRGB8888);
    EdgeRefinement rx;
    ASSERT_TRUE(refineQuad(x.view(), guess, {}, rx));
    EXPECT_LT(maxCornerError(rx.quad, r.quad), 1e-4);
}

TEST(EdgeRefinement, ChromaticityFindsTheEdgesSaturationDoesNotSee)
{
    // A red card on an orange ground: both as saturated, and their blend too (no grey between
    // them), so saturation has no step at the card's edges; chromaticity does change there.
    const Colours redOnOrange = {{190.f, 36.f, 44.f}, {220.f, 110.f, 30.f}};
    const Quad truth = kSkewedCard;
    const ImageBuffer img = render(truth, 240, 190, PixelFormat::RGB24, redOnOrange);
    const Quad guess = offsetGuess(truth);
    EdgeRefinementOptions o;
    EdgeRefinement r;
    ASSERT_TRUE(refineQuad(img.view(), guess, o, r));
    EXPECT_LT(r.edgesFitted, 3);
    o.chromaticityStep = 0.2f;
    ASSERT_TRUE(refineQuad(img.view(), guess, o, r));
    EXPECT_EQ(r.edgesFitted, 4);
    EXPECT_LT(maxCornerError(r.quad, truth), 0.5);
    // On the blue card and grey ground it changes nothing that saturation found.
    const ImageBuffer grey = render(truth, 240, 190);
    EdgeRefinement plain, both;
    ASSERT_TRUE(refineQuad(grey.view(), guess, {}, plain));
    ASSERT_TRUE(refineQuad(grey.view(), guess, o, both));
    EXPECT_LT(maxCornerError(plain.quad, both.quad), 0.2);
}

TEST(EdgeRefinement, ABrightnessStepMarksTheEdgeOfACardOnABackgroundOfItsOwnColour)
{
    // An orange card on a brighter orange ground: R, G, B all scaled by 1.6, so saturation and
    // chromaticity are the same on both sides; only brightness changes at the card's edges.
    const Colours ownColour = {{125.f, 62.f, 19.f}, {200.f, 99.f, 30.f}};
    const Quad truth = kSkewedCard;
    const ImageBuffer img = render(truth, 240, 190, PixelFormat::RGB24, ownColour);
    const Quad guess = offsetGuess(truth);
    EdgeRefinementOptions o;
    o.chromaticityStep = 0.2f;
    EdgeRefinement r;
    ASSERT_TRUE(refineQuad(img.view(), guess, o, r));
    EXPECT_EQ(r.edgesFitted, 0) << "no colour cue sees these edges";
    EXPECT_EQ(r.brightnessSamples, 0);
    o.brightnessStep = 0.1f;
    ASSERT_TRUE(refineQuad(img.view(), guess, o, r));
    EXPECT_EQ(r.edgesFitted, 4);
    EXPECT_GT(r.brightnessSamples, 0);
    EXPECT_LT(maxCornerError(r.quad, truth), 0.5);
    // Where a colour cue finds the edge, brightness is not asked.
    const ImageBuffer grey = render(truth, 240, 190);
    EdgeRefinement colour;
    ASSERT_TRUE(refineQuad(grey.view(), guess, o, colour));
    EXPECT_EQ(colour.edgesFitted, 4);
    EXPECT_EQ(colour.brightnessSamples, 0);
}

TEST(EdgeRefinement, AGuidedEdgeKeepsItsLineWhenOnlySomethingElsesOutlineIsNear)
{
    // The seed's top edge lies 3 px above the card's; a second, tilted "card" edge (a strip
    // across the top of the card, as an arm's outline) is what an unguided fit finds first.
    const Quad truth = {{{52.f, 50.f}, {182.f, 50.f}, {182.f, 150.f}, {52.f, 150.f}}};
    ImageBuffer img = render(truth, 240, 190);
    for (int y = 0; y < 190; ++y)
        for (int x = 0; x < 240; ++x) {
            // A grey strip whose lower side runs from (40, 58) to (200, 90): 11 degrees.
            const float lower = 58.f + 0.2f * (static_cast<float>(x) - 40.f);
            if (static_cast<float>(y) < lower && static_cast<float>(y) > lower - 16.f) {
                std::uint8_t* p = img.view().row(y) + 3 * x;
                p[0] = p[1] = p[2] = 150;
            }
        }
    Quad seed = truth;
    seed[0].y -= 3.f;
    seed[1].y -= 3.f;
    EdgeRefinementOptions o;
    o.searchInside = o.searchOutside = 20.f;
    EdgeRefinement free;
    ASSERT_TRUE(refineQuad(img.view(), seed, o, free));
    EXPECT_TRUE(free.fitted[0]);
    o.maxSeedDistance = 6.f;
    EdgeRefinement guided;
    ASSERT_TRUE(refineQuad(img.view(), seed, o, guided));
    // Guided, the strip's points are dropped (too far) or its line refused (turned): the top
    // edge is the card's where visible, or the seed's; never the strip's 11-degree line.
    EXPECT_LT(std::fabs(guided.quad[1].y - truth[1].y), 3.5f);
    EXPECT_LT(std::fabs(guided.quad[0].y - truth[0].y), 3.5f);
    EXPECT_EQ(guided.fitted[2], true);
    EXPECT_GT(std::fabs(free.quad[1].y - truth[1].y), 10.f);  // unguided: the strip's line
}

TEST(EdgeRefinement, AnEdgeAlmostWhollyOutOfViewIsNotFitted)
{
    // The left edge has 4 px in view: too little to tell its direction; it keeps the seed's.
    const Quad truth = {{{-40.f, 30.f}, {150.f, 20.f}, {160.f, 130.f}, {3.f, 140.f}}};
    const ImageBuffer img = render(truth, 200, 170);
    EdgeRefinement r;
    ASSERT_TRUE(refineQuad(img.view(), truth, {}, r));
    EXPECT_FALSE(r.fitted[3]);
    EXPECT_TRUE(r.fitted[0] && r.fitted[1] && r.fitted[2]);
}

TEST(EdgeRefinement, RansacIgnoresAnOccluderOnAnEdge)
{
    const Quad truth = {{{40.f, 30.f}, {200.f, 30.f}, {200.f, 150.f}, {40.f, 150.f}}};
    ImageBuffer img = render(truth, 240, 190);
    // A skin-coloured block over a third of the right edge.
    for (int y = 60; y < 100; ++y)
        for (int x = 180; x < 215; ++x) {
            std::uint8_t* p = img.view().row(y) + x * 3;
            p[0] = 210;
            p[1] = 160;
            p[2] = 130;
        }
    Quad guess = truth;
    guess[1].x -= 3;
    guess[2].x -= 2;
    EdgeRefinement r;
    ASSERT_TRUE(refineQuad(img.view(), guess, {}, r));
    EXPECT_EQ(r.edgesFitted, 4);
    EXPECT_LT(maxCornerError(r.quad, truth), 0.5);
}

TEST(EdgeRefinement, CornerOutsideTheFrameIsExtrapolated)
{
    const Quad truth = {{{-20.f, 30.f}, {150.f, 20.f}, {160.f, 130.f}, {10.f, 140.f}}};
    const ImageBuffer img = render(truth, 200, 170);
    Quad guess = truth;
    for (Point2f& p : guess)
        p.x += 2.f;
    EdgeRefinement r;
    ASSERT_TRUE(refineQuad(img.view(), guess, {}, r));
    EXPECT_EQ(r.edgesFitted, 4);  // the left edge is half visible
    // The corner 20 px outside is extrapolated from the visible third of its edge.
    EXPECT_LT(maxCornerError(r.quad, truth), 1.5);
}

TEST(EdgeRefinement, RejectsDegenerateInput)
{
    const ImageBuffer img = render({{{10, 10}, {50, 10}, {50, 50}, {10, 50}}}, 64, 64);
    EdgeRefinement r;
    EXPECT_FALSE(refineQuad(img.view(), {{{10, 10}, {11, 10}, {11, 11}, {10, 11}}}, {}, r));
    ImageBuffer gray(64, 64, PixelFormat::Gray8);
    EXPECT_FALSE(refineQuad(gray.view(), {{{10, 10}, {50, 10}, {50, 50}, {10, 50}}}, {}, r));
}
