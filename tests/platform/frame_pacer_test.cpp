// FramePacer: deadline arithmetic with a fake clock (no real time, no timing assertions).

#include "platform/frame_pacer.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <vector>

namespace {

using platform::FramePacer;
using platform::PaceSchedule;

/// A clock that only moves when told to, or when slept on.
class FakeClock final : public platform::PacerClock {
public:
    std::int64_t now = 1'000'000'000;
    std::vector<std::int64_t> sleeps;  ///< deadlines asked for

    std::int64_t nowNs() noexcept override { return now; }
    void sleepUntilNs(std::int64_t deadline) noexcept override
    {
        sleeps.push_back(deadline);
        if (deadline > now)
            now = deadline;
    }
};

TEST(PaceSchedule, UnpacedIsAlwaysDueNow)
{
    for (double fps : {0.0, -5.0, std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity()}) {
        PaceSchedule s(fps);
        EXPECT_FALSE(s.paced());
        EXPECT_EQ(s.next(100), 100);
        EXPECT_EQ(s.next(100), 100);
        EXPECT_EQ(s.next(250), 250);
    }
}

TEST(PaceSchedule, DeadlinesAreAbsoluteFromTheAnchor)
{
    PaceSchedule s(30.0);
    ASSERT_TRUE(s.paced());
    EXPECT_EQ(s.next(5000), 5000);  // first frame anchors and is due at once
    // Each deadline is anchor + round(k * 1e9 / 30), never the sum of rounded periods.
    for (std::int64_t k = 1; k <= 3000; ++k) {
        const std::int64_t expected = 5000 + (k * 1'000'000'000 + 15) / 30;
        // The caller arrives a little early each time; the deadline does not depend on it.
        EXPECT_EQ(s.next(expected - 1000), expected) << "frame " << k;
    }
    EXPECT_EQ(s.reanchors(), 0u);
}

TEST(PaceSchedule, SlightlyLateFramesCatchUpWithoutReanchoring)
{
    PaceSchedule s(10.0);  // 100 ms period
    s.next(0);
    // Late by 60 ms for frame 1: due in the past, deliver at once, keep the schedule.
    EXPECT_EQ(s.next(160'000'000), 100'000'000);
    EXPECT_EQ(s.next(170'000'000), 200'000'000);
    EXPECT_EQ(s.reanchors(), 0u);
}

TEST(PaceSchedule, LateByMoreThanOnePeriodReanchorsInsteadOfBursting)
{
    PaceSchedule s(10.0);
    s.next(0);
    EXPECT_EQ(s.next(100'000'000), 100'000'000);
    // A 550 ms stall: frame 2 was due at 200 ms, we are at 750 ms.
    EXPECT_EQ(s.next(750'000'000), 750'000'000);
    EXPECT_EQ(s.reanchors(), 1u);
    // The schedule continues from the new anchor, one period at a time (no burst of 5 frames).
    EXPECT_EQ(s.next(750'000'001), 850'000'000);
    EXPECT_EQ(s.next(850'000'000), 950'000'000);
}

TEST(PaceSchedule, RestartAnchorsAnew)
{
    PaceSchedule s(25.0);
    s.next(0);
    s.next(0);
    s.restart();
    EXPECT_EQ(s.next(123), 123);
    EXPECT_EQ(s.next(123), 123 + 40'000'000);
}

TEST(FramePacer, SleepsUntilEachDeadlineAndReturnsTheWakeTime)
{
    FakeClock clock;
    FramePacer pacer(50.0, clock);  // 20 ms
    const std::int64_t start = clock.now;
    EXPECT_EQ(pacer.wait(), start);
    EXPECT_TRUE(clock.sleeps.empty());
    for (int k = 1; k <= 5; ++k) {
        clock.now += 3'000'000;  // 3 ms of work per frame
        EXPECT_EQ(pacer.wait(), start + k * 20'000'000);
    }
    EXPECT_EQ(clock.sleeps.size(), 5u);
}

TEST(FramePacer, DoesNotSleepWhenLateOrUnpaced)
{
    FakeClock clock;
    FramePacer paced(50.0, clock);
    paced.wait();
    clock.now += 25'000'000;  // 5 ms late
    EXPECT_EQ(paced.wait(), clock.now);
    EXPECT_TRUE(clock.sleeps.empty());

    FramePacer max(0.0, clock);
    EXPECT_FALSE(max.paced());
    for (int k = 0; k < 10; ++k)
        EXPECT_EQ(max.wait(), clock.now);
    EXPECT_TRUE(clock.sleeps.empty());
}

TEST(FramePacer, ReportsHowLongTheLastWaitSlept)
{
    FakeClock clock;
    FramePacer pacer(10.0, clock);  // 100 ms period
    pacer.wait();                   // anchors: due at once
    EXPECT_EQ(pacer.lastSleepNs(), 0);
    clock.now += 30'000'000;  // 30 ms of work, then 70 ms of idle until the next frame
    pacer.wait();
    EXPECT_EQ(pacer.lastSleepNs(), 70'000'000);
    clock.now += 150'000'000;  // late: no sleep
    pacer.wait();
    EXPECT_EQ(pacer.lastSleepNs(), 0);
}

TEST(FramePacer, RealClockWaitIsMonotonic)
{
    // Only order is asserted, never durations.
    FramePacer pacer(1000.0);
    std::int64_t last = pacer.wait();
    for (int k = 0; k < 5; ++k) {
        const std::int64_t now = pacer.wait();
        EXPECT_GE(now, last);
        last = now;
    }
}

TEST(FramePacer, WaitDoesNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting unavailable in this build";
    FakeClock clock;
    clock.sleeps.reserve(100);
    FramePacer pacer(60.0, clock);
    testing_support::AllocationScope scope;
    for (int k = 0; k < 50; ++k)
        pacer.wait();
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}

}  // namespace
