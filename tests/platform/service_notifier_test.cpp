#include "platform/service_notifier.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <alloc_counter.hpp>
#include <cerrno>
#include <cstring>
#include <fake_systemd.hpp>
#include <string>
#include <test_paths.hpp>
#include <vector>

using platform::ServiceNotifier;
using testing_support::FakeSystemd;

namespace {

constexpr std::int64_t kSecond = 1000000000;

}  // namespace

TEST(ServiceNotifier, OutsideSystemdEverythingIsANoOp)
{
    ::unsetenv("NOTIFY_SOCKET");
    ::unsetenv("WATCHDOG_USEC");
    ServiceNotifier notifier;
    EXPECT_FALSE(notifier.underSystemd());
    EXPECT_EQ(notifier.watchdogUsec(), 0u);
    notifier.ready("first frame shown");
    notifier.status("running");
    EXPECT_FALSE(notifier.pingWatchdog());
    EXPECT_EQ(notifier.failures(), 0u);
}

TEST(ServiceNotifier, SendsReadyOnceAndStatus)
{
    FakeSystemd systemd(nullptr);
    ServiceNotifier notifier;
    EXPECT_TRUE(notifier.underSystemd());
    EXPECT_EQ(notifier.watchdogUsec(), 0u);
    notifier.ready("first frame shown");
    notifier.ready("again");
    notifier.status("30.0 fps");
    notifier.stopping();
    const auto messages = systemd.messages();
    ASSERT_EQ(messages.size(), 3u);
    EXPECT_EQ(messages[0], "READY=1\nSTATUS=first frame shown");
    EXPECT_EQ(messages[1], "STATUS=30.0 fps");
    EXPECT_EQ(messages[2], "STOPPING=1");
}

TEST(ServiceNotifier, PingsTheWatchdogEveryHalfIntervalWithoutAllocating)
{
    FakeSystemd systemd("2000000");  // WatchdogSec=2
    ServiceNotifier notifier;
    ASSERT_EQ(notifier.watchdogUsec(), 2000000u);
    const std::int64_t t0 = 100 * kSecond;
    int sent = 0;
    testing_support::AllocationCounts counts;
    {
        testing_support::AllocationScope scope;
        // Three seconds of frames at 30 fps.
        for (int frame = 0; frame < 90; ++frame)
            sent += notifier.pingWatchdog(t0 + frame * kSecond / 30) ? 1 : 0;
        counts = scope.counts();
    }
    EXPECT_EQ(sent, 3);  // at 0 s, 1 s and 2 s
    EXPECT_EQ(systemd.messages(), std::vector<std::string>(3, "WATCHDOG=1"));
    if (testing_support::allocationCountingAvailable()) {
        EXPECT_EQ(counts.cxxNew, 0);
        EXPECT_EQ(counts.ownMalloc, 0);
        EXPECT_EQ(counts.foreignMalloc, 0);
    }
}

TEST(ServiceNotifier, WatchdogMeantForAnotherProcessIsOff)
{
    FakeSystemd systemd("2000000", ::getpid() + 1);
    ServiceNotifier notifier;
    EXPECT_TRUE(notifier.underSystemd());
    EXPECT_EQ(notifier.watchdogUsec(), 0u);
    EXPECT_FALSE(notifier.pingWatchdog());
}
