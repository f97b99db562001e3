#include "vision/line_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

using vision::Line2f;
using vision::Point2f;

TEST(LineFit, RansacRejectsOutliers)
{
    // y = 0.3 x + 5 with small noise, plus 30% gross outliers.
    std::vector<Point2f> pts;
    std::uint32_t seed = 99;
    auto noise = [&seed] {
        seed = seed * 1664525u + 1013904223u;
        return (float((seed >> 16) % 1000) / 1000.f - 0.5f) * 0.4f;
    };
    for (int i = 0; i < 14; ++i)
        pts.push_back({float(i * 5), 0.3f * float(i * 5) + 5.f + noise()});
    for (int i = 0; i < 6; ++i)
        pts.push_back({float(i * 11 + 3), 40.f + float(i * 7)});
    Line2f line;
    std::vector<std::uint8_t> in(pts.size());
    const int count =
        vision::fitLineRansac(pts.data(), int(pts.size()), 1.0f, 200, line, in.data());
    EXPECT_EQ(count, 14);
    for (int i = 0; i < 14; ++i)
        EXPECT_EQ(in[i], 1);
    for (int i = 14; i < 20; ++i)
        EXPECT_EQ(in[i], 0);
    // Compare with the true line at a few x.
    for (float x : {0.f, 30.f, 65.f}) {
        const float y = (line.c - line.nx * x) / line.ny;
        EXPECT_NEAR(y, 0.3f * x + 5.f, 0.2f);
    }
}

TEST(LineFit, DeterministicWithSampledHypotheses)
{
    std::vector<Point2f> pts;
    for (int i = 0; i < 100; ++i)
        pts.push_back({float(i), (i % 4 == 0) ? float(50 + i) : 2.f * float(i)});
    Line2f a, b;
    const int ca = vision::fitLineRansac(pts.data(), 100, 0.5f, 60, a);
    const int cb = vision::fitLineRansac(pts.data(), 100, 0.5f, 60, b);
    EXPECT_EQ(ca, 75);
    EXPECT_EQ(ca, cb);
    EXPECT_EQ(a.nx, b.nx);
    EXPECT_EQ(a.c, b.c);
}

TEST(LineFit, LeastSquaresVerticalLineAndIntersection)
{
    const Point2f v[] = {{10, 0}, {10, 5}, {10, 9}};
    Line2f vertical;
    ASSERT_TRUE(vision::fitLineLeastSquares(v, 3, nullptr, vertical));
    EXPECT_NEAR(std::fabs(vertical.nx), 1.f, 1e-6f);
    EXPECT_NEAR(vertical.c / vertical.nx, 10.f, 1e-5f);
    Line2f horizontal;
    ASSERT_TRUE(vision::lineThrough({0, 3}, {20, 3}, horizontal));
    Point2f p;
    ASSERT_TRUE(vision::intersectLines(vertical, horizontal, p));
    EXPECT_NEAR(p.x, 10.f, 1e-5f);
    EXPECT_NEAR(p.y, 3.f, 1e-5f);
    Line2f parallel;
    ASSERT_TRUE(vision::lineThrough({0, 7}, {20, 7}, parallel));
    EXPECT_FALSE(vision::intersectLines(horizontal, parallel, p));
    const Point2f one[] = {{1, 1}};
    EXPECT_EQ(vision::fitLineRansac(one, 1, 1.f, 10, horizontal), 0);
}
