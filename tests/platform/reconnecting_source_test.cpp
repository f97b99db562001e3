// ReconnectingSource: the camera state machine (missing at boot, vanishing mid-run, coming back),
// the back-off schedule, nothing left open across reconnects, no allocation per frame.

#include "platform/reconnecting_source.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace {

using platform::CameraState;
using platform::SourceStatus;

class FakeClock final : public platform::PacerClock {
public:
    std::int64_t nowNs() noexcept override { return now; }
    void sleepUntilNs(std::int64_t deadlineNs) noexcept override
    {
        now = std::max(now, deadlineNs);
    }
    std::int64_t now = 1'000'000'000;
};

/// The world a fake camera lives in: whether it is plugged in, and how many are open.
struct FakeWorld {
    bool present = true;
    int width = 64;
    int height = 48;
    int opens = 0;  ///< open attempts
    int alive = 0;  ///< FakeCamera objects not yet destroyed
    int nextSerial = 0;
};

/// A camera that delivers frames while the world says it is present and fails on purpose when
/// it is unplugged (as LibcameraSource does on its `disconnected` signal).
class FakeCamera final : public platform::FrameSource {
public:
    explicit FakeCamera(FakeWorld& world)
        : world_(world), buffer_(world.width, world.height, vision::PixelFormat::RGB24)
    {
        ++world_.alive;
        serial_ = world_.nextSerial++;
    }
    ~FakeCamera() override { --world_.alive; }

    const char* description() const noexcept override { return "fake camera"; }
    vision::Size size() const noexcept override { return {world_.width, world_.height}; }
    vision::PixelFormat format() const noexcept override { return vision::PixelFormat::RGB24; }
    SourceStatus next(vision::Frame& frame) noexcept override
    {
        if (!world_.present)
            return SourceStatus::Lost;
        frame.image = buffer_.view();
        frame.sequence = ownSequence_++;
        frame.timestampNs = 0;
        return SourceStatus::Ok;
    }
    const char* lastError() const noexcept override
    {
        return world_.present ? "" : "fake: camera disconnected";
    }
    int serial() const { return serial_; }

private:
    FakeWorld& world_;
    vision::ImageBuffer buffer_;
    std::uint64_t ownSequence_ = 0;
    int serial_ = 0;
};

platform::SourceOpener opener(FakeWorld& world)
{
    return [&world]() -> std::unique_ptr<platform::FrameSource> {
        ++world.opens;
        if (!world.present)
            throw std::runtime_error("fake:0: no camera found");
        return std::make_unique<FakeCamera>(world);
    };
}

constexpr std::int64_t kMs = 1'000'000;

TEST(ReconnectingSource, RunsWhenTheCameraIsThere)
{
    FakeWorld world;
    FakeClock clock;
    platform::ReconnectingSource source("fake:0", opener(world), {640, 480},
                                        vision::PixelFormat::BGR24, {}, clock);
    EXPECT_EQ(source.state(), CameraState::Running);
    EXPECT_EQ(source.transitions(), 0u);
    // The camera's size and format win over the expected ones.
    EXPECT_EQ(source.size(), (vision::Size{64, 48}));
    EXPECT_EQ(source.format(), vision::PixelFormat::RGB24);
    EXPECT_STREQ(source.description(), "fake camera");
    vision::Frame frame;
    for (std::uint64_t i = 0; i < 3; ++i) {
        ASSERT_EQ(source.next(frame), SourceStatus::Ok);
        EXPECT_EQ(frame.sequence, i);
    }
    EXPECT_STREQ(source.lastError(), "");
}

TEST(ReconnectingSource, MissingAtBootRetriesWithDoublingBackOff)
{
    FakeWorld world;
    world.present = false;
    FakeClock clock;
    platform::ReconnectingSource source("fake:0", opener(world), {64, 48},
                                        vision::PixelFormat::RGB24, {}, clock);
    EXPECT_EQ(source.state(), CameraState::Lost);
    EXPECT_FALSE(source.connected());
    EXPECT_STREQ(source.description(), "fake:0 (unavailable)");
    EXPECT_STREQ(source.lastError(), "fake:0: no camera found");
    EXPECT_EQ(world.opens, 1);
    EXPECT_EQ(source.size(), (vision::Size{64, 48}));

    // Waits between attempts: 0.5 s, then 1, 2, 4, 8, 8 s. Calls before a retry is due return
    // Lost without trying.
    vision::Frame frame;
    const std::vector<std::int64_t> waits = {500, 1000, 2000, 4000, 8000, 8000};
    int opens = world.opens;
    for (const std::int64_t waitMs : waits) {
        clock.now += waitMs * kMs - 1;
        EXPECT_EQ(source.next(frame), SourceStatus::Lost);
        EXPECT_EQ(world.opens, opens) << "retried before " << waitMs << " ms";
        clock.now += 1;
        EXPECT_EQ(source.next(frame), SourceStatus::Lost);
        EXPECT_EQ(world.opens, ++opens) << "no retry after " << waitMs << " ms";
        EXPECT_EQ(source.state(), CameraState::Retrying);
    }
    EXPECT_EQ(source.failedAttempts(), 6);
    EXPECT_EQ(source.transitions(), 1u);  // Lost -> Retrying, once

    world.present = true;
    clock.now += 8000 * kMs;
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_EQ(source.state(), CameraState::Running);
    EXPECT_EQ(source.transitions(), 2u);
    EXPECT_EQ(frame.sequence, 0u);
    EXPECT_EQ(source.reconnects(), 0u);  // the first open, late
    EXPECT_STREQ(source.lastError(), "");
    EXPECT_EQ(source.retryDelayNs(), 500 * kMs);
}

TEST(ReconnectingSource, CameraVanishesMidRunAndComesBack)
{
    FakeWorld world;
    FakeClock clock;
    platform::ReconnectingSource source("fake:0", opener(world), {64, 48},
                                        vision::PixelFormat::RGB24, {}, clock);
    vision::Frame frame;
    for (int i = 0; i < 5; ++i)
        ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_EQ(world.alive, 1);

    world.present = false;  // unplugged
    EXPECT_EQ(source.next(frame), SourceStatus::Lost);
    EXPECT_EQ(source.state(), CameraState::Lost);
    EXPECT_EQ(source.transitions(), 1u);
    EXPECT_STREQ(source.lastError(), "fake: camera disconnected");
    EXPECT_EQ(world.alive, 0) << "the failed camera must be closed at once";
    EXPECT_STREQ(source.description(), "fake:0 (unavailable)");

    clock.now += 500 * kMs;
    EXPECT_EQ(source.next(frame), SourceStatus::Lost);
    EXPECT_EQ(source.state(), CameraState::Retrying);
    EXPECT_EQ(source.transitions(), 2u);
    EXPECT_STREQ(source.lastError(), "fake:0: no camera found");

    world.present = true;  // plugged in again
    clock.now += 1000 * kMs;
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_EQ(source.state(), CameraState::Running);
    EXPECT_EQ(source.transitions(), 3u);
    EXPECT_EQ(frame.sequence, 5u) << "sequence numbers continue across reconnects";
    EXPECT_EQ(source.reconnects(), 1u);
    EXPECT_EQ(world.alive, 1);

    // Lost again: the back-off starts from the shortest delay, not where it was.
    world.present = false;
    EXPECT_EQ(source.next(frame), SourceStatus::Lost);
    const int opens = world.opens;
    clock.now += 500 * kMs;
    source.next(frame);
    EXPECT_EQ(world.opens, opens + 1);
}

TEST(ReconnectingSource, CameraBackWithAnotherSizeIsRefused)
{
    FakeWorld world;
    FakeClock clock;
    platform::ReconnectingSource source("fake:0", opener(world), {64, 48},
                                        vision::PixelFormat::RGB24, {}, clock);
    vision::Frame frame;
    world.present = false;
    EXPECT_EQ(source.next(frame), SourceStatus::Lost);
    world.present = true;
    world.width = 32;
    clock.now += 500 * kMs;
    EXPECT_EQ(source.next(frame), SourceStatus::Lost);
    EXPECT_EQ(source.state(), CameraState::Retrying);
    EXPECT_NE(std::string(source.lastError()).find("came back as 32x48 RGB24"), std::string::npos)
        << source.lastError();
    EXPECT_EQ(world.alive, 0);
    EXPECT_EQ(source.size(), (vision::Size{64, 48}));
    EXPECT_TRUE(source.needsPipelineRebuild());

    world.width = 64;  // back as it was
    clock.now += 1000 * kMs;
    EXPECT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_FALSE(source.needsPipelineRebuild());
}

TEST(ReconnectingSource, MissingAtBootKeepsTheConfiguredSize)
{
    // The pipeline is built for what the config asked; a camera that turns up later with the
    // size it adjusted to must not change size() under the running pipeline.
    FakeWorld world;
    world.present = false;
    FakeClock clock;
    platform::ReconnectingSource source("fake:0", opener(world), {640, 480},
                                        vision::PixelFormat::RGB24, {}, clock);
    world.present = true;
    clock.now += 500 * kMs;
    vision::Frame frame;
    EXPECT_EQ(source.next(frame), SourceStatus::Lost);
    EXPECT_EQ(source.size(), (vision::Size{640, 480}));
    EXPECT_TRUE(source.needsPipelineRebuild());
    EXPECT_NE(std::string(source.lastError())
                  .find("came back as 64x48 RGB24, the mirror runs "
                        "640x480 RGB24"),
              std::string::npos)
        << source.lastError();
}

TEST(ReconnectingSource, NoAllocationPerFrameWhileRunningOrWaiting)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";
    FakeWorld world;
    FakeClock clock;
    platform::ReconnectingSource source("fake:0", opener(world), {64, 48},
                                        vision::PixelFormat::RGB24, {}, clock);
    vision::Frame frame;
    testing_support::AllocationCounts running;
    {
        testing_support::AllocationScope scope;
        for (int i = 0; i < 200; ++i)
            source.next(frame);
        running = scope.counts();
    }
    EXPECT_EQ(running.cxxNew, 0);
    EXPECT_EQ(running.ownMalloc, 0);

    world.present = false;
    source.next(frame);  // closes the camera (frees, does not allocate)
    testing_support::AllocationCounts waiting;
    {
        testing_support::AllocationScope scope;
        for (int i = 0; i < 200; ++i) {
            clock.now += kMs;  // 200 ms in all: before the first retry
            source.next(frame);
        }
        waiting = scope.counts();
    }
    EXPECT_EQ(waiting.cxxNew, 0);
    EXPECT_EQ(waiting.ownMalloc, 0);
}

}  // namespace
