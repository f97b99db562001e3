// The card's shape model: prediction from the last measured motion, no extrapolation of a quad
// with an edge kept from its seed, corners paired by the best cyclic shift, a hidden edge carried
// from the last quad measured on all four edges.

#include "card_shape_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

// kCard moved by (dx, dy) and turned by `angle` about its centre; edge `hidden` without evidence
// (the seed's wrong line kept).
EdgeRefinement withHiddenEdge(const Quad& now, int hidden)
{
    EdgeRefinement r;
    for (int i = 0; i < 4; ++i) {
        lineThrough(now[i], now[(i + 1) % 4], r.lines[i]);
        r.fitted[i] = i != hidden;
        r.quad[i] = now[i];
    }
    r.edgesFitted = 3;
    lineThrough({230.f, 90.f}, {240.f, 230.f}, r.lines[hidden]);
    r.quad[hidden] = {231.f, 97.f};
    r.quad[(hidden + 1) % 4] = {239.f, 215.f};
    return r;
}

Quad movedAndTurned(float dx, float dy, float angle)
{
    const float c = std::cos(angle), s = std::sin(angle);
    Quad q;
    for (int i = 0; i < 4; ++i) {
        const float x = kCard[i].x - 180.f, y = kCard[i].y - 155.f;
        q[i] = {180.f + dx + c * x - s * y, 155.f + dy + s * x + c * y};
    }
    return q;
}

TEST(CardShapeModel, KeepsTheLastQuadMeasuredOnAllFourEdges)
{
    CardShapeModel m;
    EXPECT_EQ(m.lastMeasured(), nullptr);
    m.track(kCard, kArea, 160.f / 110.f, 0, true, true);
    m.track(moved(kCard, 5.f, 0.f), kArea, 160.f / 110.f, 0, true, false);  // an edge carried
    ASSERT_NE(m.lastMeasured(), nullptr);
    EXPECT_LT(quadDistance(*m.lastMeasured(), kCard), 1e-4f);
}

TEST(CardShapeModel, AnEdgeUnderAHandMovesWithTheCard)
{
    // Many frames after the reference: moved by (90, 40) (more than half the card) and turned.
    const Quad now = movedAndTurned(90.f, 40.f, 0.03f);
    EdgeRefinement r = withHiddenEdge(now, 1);
    ASSERT_TRUE(carryHiddenEdge(kCard, {640, 480}, r));
    EXPECT_LT(quadDistance(r.quad, now), 0.05f);
    // Not an edge at the border: out of view it is unknowable, not hidden.
    EdgeRefinement atBorder = withHiddenEdge(now, 1);
    EXPECT_FALSE(carryHiddenEdge(moved(kCard, 375.f, 0.f), {640, 480}, atBorder));
    // Two hidden edges: nothing to carry them with.
    r.fitted[2] = false;
    r.edgesFitted = 2;
    EXPECT_FALSE(carryHiddenEdge(kCard, {640, 480}, r));
}

TEST(CardShapeModel, AnEdgeRunningOutOfViewIsCarriedByItsEndInView)
{
    // The right edge's top end beyond the top of the frame, then and now: its bottom end is in
    // view, so the edge is the card's there and moves with it.
    const Quad then = moved(kCard, 0.f, -95.f);
    const Quad now = moved(kCard, 6.f, -95.f);
    EdgeRefinement r = withHiddenEdge(now, 1);
    ASSERT_TRUE(carryHiddenEdge(then, {640, 480}, r));
    EXPECT_LT(quadDistance(r.quad, now), 0.05f);
}

TEST(CardShapeModel, AnEdgeIsNotCarriedWhenTheCardTurnedInDepth)
{
    // The top and bottom edges converge now (the card turned about a vertical axis): the measured
    // left edge's motion says nothing about where the right edge went.
    const Quad now = {{{100.f, 100.f}, {240.f, 115.f}, {240.f, 195.f}, {100.f, 210.f}}};
    EdgeRefinement r = withHiddenEdge(now, 1);
    EXPECT_FALSE(carryHiddenEdge(kCard, {640, 480}, r));
}

TEST(CardShapeModel, QuadDistancePairsCornersByTheBestCyclicShift)
{
    const Quad shifted = {kCard[1], kCard[2], kCard[3], kCard[0]};
    EXPECT_LT(quadDistance(shifted, kCard), 1e-4f);
    EXPECT_NEAR(quadDistance(moved(kCard, 3.f, 4.f), kCard), 5.f, 1e-4f);
}

}  // namespace
