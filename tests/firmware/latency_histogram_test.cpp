#include "firmware/latency_histogram.hpp"

#include <gtest/gtest.h>

namespace {

using firmware::LatencyHistogram;

TEST(LatencyHistogram, EmptyReportsZero)
{
    LatencyHistogram h;
    EXPECT_EQ(h.count(), 0u);
    EXPECT_EQ(h.percentileMs(0.5), 0.0);
    EXPECT_EQ(h.meanMs(), 0.0);
}

TEST(LatencyHistogram, PercentilesWithinOneBin)
{
    LatencyHistogram h;
    // 99 samples of 2 ms and one of 50 ms: p50 ~ 2 ms, p99 ~ 2 ms, p100 = 50 ms.
    for (int i = 0; i < 99; ++i)
        h.record(2'000'000);
    h.record(50'000'000);
    EXPECT_NEAR(h.percentileMs(0.5), 2.0, 2.0 * 0.07);
    EXPECT_NEAR(h.percentileMs(0.99), 2.0, 2.0 * 0.07);
    EXPECT_NEAR(h.percentileMs(1.0), 50.0, 50.0 * 0.07);
    EXPECT_NEAR(h.meanMs(), (99 * 2.0 + 50.0) / 100, 1e-9);
    EXPECT_DOUBLE_EQ(h.maxMs(), 50.0);
}

TEST(LatencyHistogram, NeverReportsMoreThanTheMaximumSeen)
{
    LatencyHistogram h;
    h.record(1'234'567);
    EXPECT_LE(h.percentileMs(0.5), 1.234567 + 1e-12);
}

TEST(LatencyHistogram, ExtremesClampIntoTheEndBins)
{
    EXPECT_EQ(LatencyHistogram::binOf(-5), 0);
    EXPECT_EQ(LatencyHistogram::binOf(0), 0);
    EXPECT_EQ(LatencyHistogram::binOf(1'000'000'000'000), LatencyHistogram::kBins - 1);
    for (int b = 1; b < LatencyHistogram::kBins; ++b)
        EXPECT_GT(LatencyHistogram::binUpperNs(b), LatencyHistogram::binUpperNs(b - 1));
}

TEST(LatencyHistogram, BinsAreMonotonicAndConsistentWithEdges)
{
    for (std::int64_t ns = 500; ns < 20'000'000'000; ns = ns * 11 / 10 + 1) {
        const int b = LatencyHistogram::binOf(ns);
        if (b < LatencyHistogram::kBins - 1) {
            EXPECT_LE(static_cast<double>(ns), LatencyHistogram::binUpperNs(b) * (1 + 1e-9)) << ns;
        }
    }
}

TEST(LatencyHistogram, ResetForgetsEverything)
{
    LatencyHistogram h;
    h.record(5'000'000);
    h.reset();
    EXPECT_EQ(h.count(), 0u);
    EXPECT_EQ(h.maxMs(), 0.0);
}

}  // namespace
