// The card's shape model: prediction from the last measured motion, no extrapolation of a quad
// with an edge kept from its seed, corners paired by the best cyclic shift.

#include "card_shape_model.hpp"

#include <gtest/gtest.h>

using namespace vision;

namespace {

Quad moved(const Quad& q, float dx, float dy)
{
    Quad out = q;
    for (Point2f& p : out)
        p = {p.x + dx, p.y + dy};
    return out;
}

const Quad kCard = {{{100.f, 100.f}, {260.f, 100.f}, {260.f, 210.f}, {100.f, 210.f}}};
constexpr float kArea = 160.f * 110.f;

TEST(CardShapeModel, PredictsFromTheLastMeasuredMotion)
{
    CardShapeModel m;
    EXPECT_FALSE(m.haveLast());
    m.track(kCard, kArea, 160.f / 110.f, 0, true, true);
    EXPECT_LT(quadDistance(m.predicted(0), kCard), 1e-4f);  // no motion known yet
    m.track(moved(kCard, 6.f, -2.f), kArea, 160.f / 110.f, 0, true, true);
    EXPECT_LT(quadDistance(m.predicted(0), moved(kCard, 12.f, -4.f)), 1e-4f);
    EXPECT_LT(quadDistance(m.predicted(2), moved(kCard, 24.f, -8.f)), 1e-4f);
    // Two frames missed before the next one: the motion is per frame.
    m.track(moved(kCard, 12.f, -8.f), kArea, 160.f / 110.f, 2, true, true);
    EXPECT_LT(quadDistance(m.predicted(0), moved(kCard, 14.f, -10.f)), 1e-4f);
    // Where the card can be: around the prediction.
    const Rect r = m.expectedBounds(0);
    EXPECT_LE(r.x, 114);
    EXPECT_GE(r.x + r.width, 274);
    EXPECT_EQ(m.goodArea(), kArea);
}

TEST(CardShapeModel, AQuadWithAnEdgeNotMeasuredIsNotExtrapolated)
{
    CardShapeModel m;
    m.track(kCard, kArea, 1.45f, 0, true, true);
    m.track(moved(kCard, 8.f, 0.f), kArea, 1.45f, 0, true, false);
    EXPECT_LT(quadDistance(m.predicted(0), moved(kCard, 8.f, 0.f)), 1e-4f);
    m.track(moved(kCard, 16.f, 0.f), kArea, 1.45f, 0, true, true);  // the one before was not
    EXPECT_LT(quadDistance(m.predicted(0), moved(kCard, 16.f, 0.f)), 1e-4f);
}

TEST(CardShapeModel, AJumpIsANewTrackNotMotion)
{
    CardShapeModel m;
    m.track(kCard, kArea, 1.45f, 0, true, true);
    m.track(moved(kCard, 120.f, 0.f), kArea, 1.45f, 0, true, true);
    EXPECT_LT(quadDistance(m.predicted(0), moved(kCard, 120.f, 0.f)), 1e-4f);
}

TEST(CardShapeModel, TheShapeToRecoverToIsOneSeenWhole)
{
    CardShapeModel m;
    m.track(kCard, kArea, 1.45f, 0, false, true);  // the first one is kept anyway
    EXPECT_EQ(m.goodArea(), kArea);
    m.track(kCard, 2.f * kArea, 1.45f, 0, false, true);
    EXPECT_EQ(m.goodArea(), kArea);
    m.track(kCard, 3.f * kArea, 2.f, 0, true, true);
    EXPECT_EQ(m.goodArea(), 3.f * kArea);
    EXPECT_EQ(m.goodAspect(), 2.f);
}

TEST(CardShapeModel, QuadDistancePairsCornersByTheBestCyclicShift)
{
    const Quad shifted = {kCard[1], kCard[2], kCard[3], kCard[0]};
    EXPECT_LT(quadDistance(shifted, kCard), 1e-4f);
    EXPECT_NEAR(quadDistance(moved(kCard, 3.f, 4.f), kCard), 5.f, 1e-4f);
}

}  // namespace
