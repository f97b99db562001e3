// The face motion model: exact recovery of known motions about a centre, outlier rejection,
// determinism, degenerate input, no allocation.
#include "vision/motion_model.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

using vision::MotionFitOptions;
using vision::MotionKind;
using vision::MotionModel;
using vision::Point2f;

namespace {

constexpr float kPi = 3.14159265f;

struct Pairs {
    std::vector<Point2f> from, to;
};

// Points on a face-sized patch moved by scale s and roll th about c, then shifted by (tx, ty),
// with uniform noise of +-noise px; the last `outliers` pairs are thrown far off.
Pairs makePairs(Point2f c, float s, float th, float tx, float ty, int n, float noise, int outliers)
{
    Pairs p;
    std::uint32_t seed = 12345;
    auto rnd = [&seed] {
        seed = seed * 1664525u + 1013904223u;
        return float(seed >> 8) / float(1u << 24);  // [0, 1)
    };
    for (int i = 0; i < n; ++i) {
        const Point2f a{c.x + (rnd() - 0.5f) * 80.f, c.y + (rnd() - 0.5f) * 90.f};
        const float u = a.x - c.x;
        const float v = a.y - c.y;
        Point2f b{
            c.x + s * (std::cos(th) * u - std::sin(th) * v) + tx + (rnd() - 0.5f) * 2 * noise,
            c.y + s * (std::sin(th) * u + std::cos(th) * v) + ty + (rnd() - 0.5f) * 2 * noise};
        if (i >= n - outliers) {
            b.x += 15.f + 20.f * rnd();
            b.y -= 12.f + 20.f * rnd();
        }
        p.from.push_back(a);
        p.to.push_back(b);
    }
    return p;
}

}  // namespace

TEST(MotionModel, SimilarityRecoversScaleRollAndTranslationExactly)
{
    const Point2f c{320.f, 240.f};
    const float th = 12.f * kPi / 180.f;
    Pairs p = makePairs(c, 1.08f, th, 3.5f, -2.25f, 30, 0.f, 0);
    MotionModel m;
    ASSERT_TRUE(vision::fitMotionLeastSquares(p.from.data(), p.to.data(), 30, nullptr, c,
                                              MotionKind::Similarity, m));
    EXPECT_NEAR(m.scale(), 1.08f, 1e-4f);
    EXPECT_NEAR(m.roll(), th, 1e-4f);
    EXPECT_NEAR(m.b1, 3.5f, 1e-3f);
    EXPECT_NEAR(m.b2, -2.25f, 1e-3f);
    const Point2f q = m.apply(p.from[4]);
    EXPECT_NEAR(q.x, p.to[4].x, 1e-3f);
    EXPECT_NEAR(q.y, p.to[4].y, 1e-3f);
}

TEST(MotionModel, TranslationAndAffine)
{
    const Point2f c{100.f, 80.f};
    Pairs p = makePairs(c, 1.f, 0.f, -4.f, 7.5f, 20, 0.f, 0);
    MotionModel t;
    ASSERT_TRUE(vision::fitMotionLeastSquares(p.from.data(), p.to.data(), 20, nullptr, c,
                                              MotionKind::Translation, t));
    EXPECT_NEAR(t.b1, -4.f, 1e-4f);
    EXPECT_NEAR(t.b2, 7.5f, 1e-4f);

    // A shear no similarity can express.
    std::vector<Point2f> to(p.from.size());
    for (std::size_t i = 0; i < to.size(); ++i) {
        const float u = p.from[i].x - c.x, v = p.from[i].y - c.y;
        to[i] = {c.x + 1.1f * u + 0.2f * v + 2.f, c.y - 0.1f * u + 0.9f * v - 1.f};
    }
    MotionModel a;
    ASSERT_TRUE(vision::fitMotionLeastSquares(p.from.data(), to.data(), 20, nullptr, c,
                                              MotionKind::Affine, a));
    EXPECT_NEAR(a.a11, 1.1f, 1e-4f);
    EXPECT_NEAR(a.a12, 0.2f, 1e-4f);
    EXPECT_NEAR(a.a21, -0.1f, 1e-4f);
    EXPECT_NEAR(a.a22, 0.9f, 1e-4f);
    EXPECT_NEAR(a.b1, 2.f, 1e-3f);
    EXPECT_NEAR(a.b2, -1.f, 1e-3f);
}

TEST(MotionModel, RobustFitRejectsOutliersUnderNoise)
{
    const Point2f c{200.f, 150.f};
    const float th = -25.f * kPi / 180.f;
    const int n = 40, bad = 12;  // 30% gross outliers
    Pairs p = makePairs(c, 0.92f, th, -6.f, 4.f, n, 0.3f, bad);
    for (MotionKind kind : {MotionKind::Similarity, MotionKind::Affine}) {
        MotionFitOptions opt;
        opt.kind = kind;
        opt.inlierDistance = 1.5f;
        MotionModel m;
        std::vector<std::uint8_t> in(n);
        const int count =
            vision::fitMotionRobust(p.from.data(), p.to.data(), n, c, opt, m, in.data());
        EXPECT_EQ(count, n - bad);
        for (int i = 0; i < n; ++i)
            EXPECT_EQ(in[i], i < n - bad ? 1 : 0) << i;
        EXPECT_NEAR(m.scale(), 0.92f, 0.01f);
        EXPECT_NEAR(m.roll() * 180.f / kPi, -25.f, 0.5f);
        EXPECT_NEAR(m.b1, -6.f, 0.2f);
        EXPECT_NEAR(m.b2, 4.f, 0.2f);
    }
    // Plain least squares is pulled away by the same outliers.
    MotionModel ls;
    ASSERT_TRUE(vision::fitMotionLeastSquares(p.from.data(), p.to.data(), n, nullptr, c,
                                              MotionKind::Similarity, ls));
    EXPECT_GT(std::fabs(ls.b1 + 6.f) + std::fabs(ls.b2 - 4.f), 2.f);
}

TEST(MotionModel, TranslationRansacAndDeterminism)
{
    const Point2f c{50.f, 50.f};
    Pairs p = makePairs(c, 1.f, 0.f, 2.f, 1.f, 100, 0.2f, 30);
    MotionFitOptions opt;
    opt.kind = MotionKind::Translation;
    MotionModel a, b;
    const int ca = vision::fitMotionRobust(p.from.data(), p.to.data(), 100, c, opt, a);
    opt.kind = MotionKind::Similarity;  // many pairs: sampled hypotheses, same answer twice
    MotionModel s1, s2;
    const int c1 = vision::fitMotionRobust(p.from.data(), p.to.data(), 100, c, opt, s1);
    const int c2 = vision::fitMotionRobust(p.from.data(), p.to.data(), 100, c, opt, s2);
    EXPECT_EQ(ca, 70);
    EXPECT_NEAR(a.b1, 2.f, 0.1f);
    EXPECT_NEAR(a.b2, 1.f, 0.1f);
    EXPECT_EQ(c1, 70);
    EXPECT_EQ(c1, c2);
    EXPECT_EQ(s1.a11, s2.a11);
    EXPECT_EQ(s1.b1, s2.b1);
}

TEST(MotionModel, DegenerateInputFails)
{
    const Point2f same[3] = {{5, 5}, {5, 5}, {5, 5}};
    const Point2f moved[3] = {{6, 5}, {6, 5}, {6, 5}};
    MotionModel m;
    EXPECT_FALSE(
        vision::fitMotionLeastSquares(same, moved, 3, nullptr, {0, 0}, MotionKind::Similarity, m));
    EXPECT_FALSE(
        vision::fitMotionLeastSquares(same, moved, 0, nullptr, {0, 0}, MotionKind::Translation, m));
    EXPECT_TRUE(
        vision::fitMotionLeastSquares(same, moved, 3, nullptr, {0, 0}, MotionKind::Translation, m));
    EXPECT_EQ(vision::fitMotionRobust(same, moved, 3, {0, 0}, {}, m), 0);
}

TEST(MotionModel, FitsDoNotAllocate)
{
    const Point2f c{200.f, 150.f};
    Pairs p = makePairs(c, 1.05f, 0.1f, 1.f, 2.f, 60, 0.3f, 10);
    MotionModel m;
    std::uint8_t in[60];
    testing_support::AllocationScope scope;
    for (MotionKind kind : {MotionKind::Translation, MotionKind::Similarity, MotionKind::Affine}) {
        MotionFitOptions opt;
        opt.kind = kind;
        EXPECT_GT(vision::fitMotionRobust(p.from.data(), p.to.data(), 60, c, opt, m, in), 0);
    }
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}
