#include "vision/connected_components.hpp"

#include <gtest/gtest.h>

using namespace vision;

namespace {

void fill(ImageBuffer& img, int x0, int y0, int x1, int y1)
{
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
            img.view().row(y)[x] = 255;
}

}  // namespace

TEST(ConnectedComponents, FindsTheLargestComponent)
{
    ImageBuffer m(64, 48, PixelFormat::Gray8);
    fill(m, 2, 2, 6, 6);      // 25
    fill(m, 20, 10, 39, 29);  // 400
    fill(m, 50, 40, 60, 45);  // 66
    ComponentLabeler l({64, 48});
    EXPECT_EQ(l.label(m.view()), 3);
    const Component c = l.largest();
    EXPECT_EQ(c.area, 400);
    EXPECT_EQ(c.bounds, (Rect{20, 10, 20, 20}));
    const Component s = l.selectLargest();
    EXPECT_EQ(s.area, 400);
    EXPECT_EQ(l.rowMin()[10], 20);
    EXPECT_EQ(l.rowMax()[10], 39);
    EXPECT_EQ(l.rowMin()[5], -1);
}

TEST(ConnectedComponents, DiagonalNeighboursJoin)
{
    // A diagonal staircase is one 8-connected component (it would be many 4-connected ones).
    ImageBuffer m(16, 16, PixelFormat::Gray8);
    for (int i = 0; i < 10; ++i)
        m.view().row(i)[i] = 255;
    fill(m, 12, 12, 14, 14);  // 9 pixels, separate
    ComponentLabeler l({16, 16});
    EXPECT_EQ(l.label(m.view()), 2);
    EXPECT_EQ(l.largest().area, 10);
}

TEST(ConnectedComponents, UShapeMergesLate)
{
    // Two arms that only join at the bottom: union-find must merge the labels.
    ImageBuffer m(20, 20, PixelFormat::Gray8);
    fill(m, 2, 2, 3, 15);
    fill(m, 10, 2, 11, 15);
    fill(m, 2, 16, 11, 16);
    fill(m, 15, 2, 18, 5);  // 16 pixels
    ComponentLabeler l({20, 20});
    EXPECT_EQ(l.label(m.view()), 2);
    EXPECT_EQ(l.largest().area, 28 + 28 + 10);
}

TEST(ConnectedComponents, SelectNearAddsCutOffPieces)
{
    ImageBuffer m(40, 20, PixelFormat::Gray8);
    fill(m, 2, 2, 15, 15);    // 196
    fill(m, 18, 2, 30, 15);   // 182: cut off by an occluder column
    fill(m, 36, 18, 37, 19);  // 4: far and small
    ComponentLabeler l({40, 20});
    l.label(m.view());
    const Component c = l.selectNear({0, 0, 32, 18}, 16);
    EXPECT_EQ(c.area, 196 + 182);
    EXPECT_EQ(l.rowMin()[5], 2);
    EXPECT_EQ(l.rowMax()[5], 30);
}

TEST(ConnectedComponents, SelectNearLeavesOutPiecesReachingOutsideAndAnchorsWhereTheObjectWas)
{
    ImageBuffer m(60, 30, PixelFormat::Gray8);
    fill(m, 2, 2, 15, 15);   // 196: the object, where it was
    fill(m, 18, 2, 22, 13);  // 60: a piece cut off it, inside the region
    fill(m, 2, 18, 15, 22);  // 70: touching the region's edge but reaching out of it
    fill(m, 30, 5, 59, 29);  // 750: the largest of all, away from the region
    ComponentLabeler l({60, 30});
    l.label(m.view());
    EXPECT_EQ(l.largest().area, 750);
    const Component c = l.selectNear({0, 0, 25, 20}, 16);
    EXPECT_EQ(c.area, 196 + 60);
    EXPECT_EQ(l.rowMax()[12], 22);
    EXPECT_EQ(l.rowMin()[20], -1);
    // Nothing where the object was: the largest of all.
    EXPECT_EQ(l.selectNear({0, 25, 10, 5}, 16).area, 750);
}

TEST(ConnectedComponents, EmptyAndFullMasks)
{
    ImageBuffer m(33, 7, PixelFormat::Gray8);
    ComponentLabeler l({33, 7});
    EXPECT_EQ(l.label(m.view()), 0);
    EXPECT_EQ(l.largest().area, 0);
    fill(m, 0, 0, 32, 6);
    EXPECT_EQ(l.label(m.view()), 1);
    EXPECT_EQ(l.largest().area, 33 * 7);
    // Checkerboard: the worst case for the run buffer; 8-connectivity makes it one component.
    for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 33; ++x)
            m.view().row(y)[x] = ((x + y) & 1) ? 0 : 255;
    EXPECT_EQ(l.label(m.view()), 1);
    EXPECT_EQ(l.largest().area, (33 * 7 + 1) / 2);
}
