// The hidden edge weighed between its placement in 3D and in the image (card_hidden_edge_blend).

#include "card_hidden_edge_blend.hpp"

#include <gtest/gtest.h>

using namespace vision;

namespace {

/// A quad with edge 0 (corners 0 and 1) not fitted, its hidden corners at y = top.
EdgeRefinement withTop(float top, float skew)
{
    EdgeRefinement r;
    r.quad = {Point2f{100.f + skew, top}, Point2f{300.f - skew, top}, Point2f{300.f, 300.f},
              Point2f{100.f, 300.f}};
    for (int i = 0; i < 4; ++i) {
        lineThrough(r.quad[i], r.quad[(i + 1) % 4], r.lines[i]);
        r.fitted[i] = i != 0;
    }
    r.edgesFitted = 3;
    return r;
}

}  // namespace

TEST(CardHiddenEdgeBlend, EqualUncertaintiesMeetHalfWay)
{
    EdgeRefinement depth = withTop(100.f, 0.f);
    ASSERT_TRUE(blendHiddenEdge(withTop(120.f, 0.f), 2.f, 2.f, depth));
    EXPECT_NEAR(depth.quad[0].y, 110.f, 1e-3f);
    EXPECT_NEAR(depth.quad[1].y, 110.f, 1e-3f);
    EXPECT_NEAR(depth.lines[0].distance({200.f, 110.f}), 0.f, 1e-3f);
    EXPECT_NEAR(depth.quad[2].y, 300.f, 1e-6f);  // the measured corners stay
}

TEST(CardHiddenEdgeBlend, TheSurerPlacementWins)
{
    EdgeRefinement depth = withTop(100.f, 0.f);
    ASSERT_TRUE(blendHiddenEdge(withTop(120.f, 0.f), 10.f, 1.f, depth));
    EXPECT_NEAR(depth.quad[0].y, 100.f + 20.f / 101.f, 1e-3f);
    EdgeRefinement unsure = withTop(100.f, 0.f);
    ASSERT_TRUE(blendHiddenEdge(withTop(120.f, 0.f), 1.f, 10.f, unsure));
    EXPECT_NEAR(unsure.quad[0].y, 120.f - 20.f / 101.f, 1e-3f);
}

TEST(CardHiddenEdgeBlend, NeedsExactlyOneHiddenEdge)
{
    EdgeRefinement all = withTop(100.f, 0.f);
    all.fitted[0] = true;
    all.edgesFitted = 4;
    EXPECT_FALSE(blendHiddenEdge(withTop(120.f, 0.f), 1.f, 1.f, all));
}
