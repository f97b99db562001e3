#include "vision/one_euro_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

using vision::OneEuroFilter;

TEST(OneEuroFilter, ConstantInputWithNoiseConvergesAndJitterIsSmall)
{
    OneEuroFilter f(1.f, 0.05f, 1.f);
    std::uint32_t seed = 3;
    float minOut = 1e9f, maxOut = -1e9f;
    for (int i = 0; i < 200; ++i) {
        seed = seed * 1664525u + 1013904223u;
        const float noise = (float((seed >> 16) % 1000) / 1000.f - 0.5f) * 1.0f;  // +-0.5 px
        const float y = f.filter(100.f + noise, 1.f / 30.f);
        if (i >= 100) {
            minOut = std::min(minOut, y);
            maxOut = std::max(maxOut, y);
        }
    }
    EXPECT_NEAR(f.value(), 100.f, 0.3f);
    EXPECT_LT(maxOut - minOut, 0.5f);  // +-0.5 px input noise -> well under a pixel
    OneEuroFilter g;
    for (int i = 0; i < 10; ++i)
        EXPECT_FLOAT_EQ(g.filter(42.f, 1.f / 30.f), 42.f);
}

TEST(OneEuroFilter, FollowsAStepWithinAFewFrames)
{
    // A fast move: the speed-dependent cutoff must let the output catch up quickly.
    OneEuroFilter f(1.f, 0.5f, 8.f);
    for (int i = 0; i < 30; ++i)
        f.filter(0.f, 1.f / 30.f);
    float y = 0.f;
    for (int i = 0; i < 5; ++i)
        y = f.filter(100.f, 1.f / 30.f);
    EXPECT_GT(y, 97.f);
}

TEST(OneEuroFilter, FollowsARampWithLittleLag)
{
    OneEuroFilter f(1.f, 0.5f, 8.f);
    float y = 0.f, x = 0.f;
    for (int i = 0; i < 60; ++i) {
        x = 10.f * float(i);  // 300 px/s
        y = f.filter(x, 1.f / 30.f);
    }
    EXPECT_LT(x - y, 2.f);
}

TEST(OneEuroFilter, ResetPassesTheNextSampleThrough)
{
    OneEuroFilter f;
    f.filter(1.f, 0.1f);
    f.filter(2.f, 0.1f);
    f.reset();
    EXPECT_FLOAT_EQ(f.filter(50.f, 0.1f), 50.f);
    EXPECT_FLOAT_EQ(f.filter(std::nanf(""), 0.1f), 50.f);
}
