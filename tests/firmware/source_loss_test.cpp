// A camera that vanishes and comes back: the loop logs the loss once and the return once, shows a
// calm "camera unavailable" screen (never a frozen frame), answers the console meanwhile, and
// resumes tracking when frames come back, without allocating while it waits.
#include "alloc_counter.hpp"
#include "fake_console.hpp"
#include "fake_systemd.hpp"
#include "firmware/device_factory.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "test_paths.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>
#include <string>

namespace {

/// Grey frames with a moving bright bar; Lost while `lost` is set.
class FlakySource final : public platform::FrameSource {
public:
    FlakySource() : image_(160, 120, vision::PixelFormat::RGB24) {}
    const char* description() const noexcept override { return "flaky test camera"; }
    vision::Size size() const noexcept override { return {160, 120}; }
    vision::PixelFormat format() const noexcept override { return vision::PixelFormat::RGB24; }
    platform::SourceStatus next(vision::Frame& frame) noexcept override
    {
        if (lost)
            return platform::SourceStatus::Lost;
        const vision::ImageView v = image_.view();
        for (int y = 0; y < v.height; ++y)
            for (int x = 0; x < v.width * 3; ++x)
                v.row(y)[x] = static_cast<std::uint8_t>(
                    (x / 3 + static_cast<int>(sequence_)) % 40 < 8 ? 220 : 90);
        frame.image = image_.view();
        frame.sequence = sequence_++;
        return platform::SourceStatus::Ok;
    }
    const char* lastError() const noexcept override { return "test camera unplugged"; }
    bool lost = false;

private:
    vision::ImageBuffer image_;
    std::uint64_t sequence_ = 0;
};

/// A small headless mirror without card and faces, its output in a fresh folder `out`.
firmware::Config lossConfig(const std::string& name, const std::string& out, double summaryS)
{
    firmware::Config config;
    config.display.spec = "headless:" + out;
    config.display.width = 320;
    config.display.height = 240;
    config.display.snapshotEvery = 0;
    config.card.enabled = false;
    config.faces.enabled = false;
    config.log.summaryIntervalS = summaryS;
    config.state.dir = testing_support::freshOutputDir(name + "_state");
    return config;
}

TEST(SourceLoss, CalmScreenWhileLostOneLogLineEachWayAndBackToFrames)
{
    const std::string out = testing_support::freshOutputDir("source_loss");
    const firmware::Config config = lossConfig("source_loss", out, 0);
    const std::string logPath = out + "/log.txt";
    const int logFd = ::open(logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    firmware::setLogFd(logFd);

    auto source = std::make_unique<FlakySource>();
    FlakySource* camera = source.get();
    firmware::FrameLoop loop(config, std::move(source), firmware::makeDisplay(config.display));
    FakeConsole console;
    loop.attachConsole(&console);
    for (int i = 0; i < 5; ++i)
        ASSERT_TRUE(loop.step());

    camera->lost = true;
    console.type("snapshot\n");
    // The first calm screen is the text program's first draw in the state the frames leave, which
    // Mesa compiles then (hundreds of blocks, once per process). The loop's own steps are measured
    // from the second poll on, over a second: the calm screen is redrawn once within it.
    ASSERT_TRUE(loop.step());
    testing_support::AllocationCounts counts;
    {
        testing_support::AllocationScope scope;
        for (int i = 0; i < 22; ++i)
            ASSERT_TRUE(loop.step());  // each lost poll waits 50 ms
        counts = scope.counts();
    }
    console.type("status\nselftest\n");
    ASSERT_TRUE(loop.step());
    camera->lost = false;
    for (int i = 0; i < 5; ++i)
        ASSERT_TRUE(loop.step());
    firmware::setLogFd(2);
    ::close(logFd);

    const std::string log = testing_support::readFile(logPath);
    EXPECT_NE(log.find("source lost: test camera unplugged (retrying)"), std::string::npos) << log;
    EXPECT_EQ(log.find("source lost"), log.rfind("source lost")) << "logged once: " << log;
    EXPECT_NE(log.find("source is back"), std::string::npos) << log;
    EXPECT_EQ(loop.framesShown(), 10u);
    EXPECT_NE(console.output().find("[LOST]"), std::string_view::npos) << console.output();
    EXPECT_NE(console.output().find("FAIL camera: flaky test camera, test camera unplugged\n"),
              std::string_view::npos)
        << console.output();
    // The calm screen is shown: the display is not blamed for the camera.
    EXPECT_NE(console.output().find("PASS display: "), std::string_view::npos) << console.output();
    // The snapshot asked for names its folder at once and its file once written.
    EXPECT_NE(console.output().find("snapshot: writing the next frame shown to " + out +
                                    "/snapshot-NNNNNN.png\n"),
              std::string_view::npos)
        << console.output();
    if (testing_support::allocationCountingAvailable()) {
        EXPECT_EQ(counts.cxxNew, 0);
        EXPECT_EQ(counts.ownMalloc, 0);
    }
    // The snapshot asked for while the camera was away shows the calm screen: dark slate, no
    // stripes of the last frame.
    const std::string shot(loop.display().lastSnapshot());
    ASSERT_FALSE(shot.empty());
    EXPECT_NE(console.output().find("snapshot: wrote " + shot + "\n"), std::string_view::npos)
        << console.output();
    const cv::Mat image = cv::imread(shot, cv::IMREAD_COLOR);
    ASSERT_FALSE(image.empty()) << shot;
    const cv::Vec3b corner = image.at<cv::Vec3b>(5, image.cols - 5);
    EXPECT_NEAR(corner[0], 36, 3);  // B of (0.09, 0.11, 0.14)
    EXPECT_NEAR(corner[1], 28, 3);
    EXPECT_NEAR(corner[2], 23, 3);
}

TEST(SourceLoss, TheSummaryDoesNotPushTheCauseOutOfTheLog)
{
    // Twenty summaries' worth of time without a camera: the ring keeps the loss, not twenty
    // identical "frames=0" lines (one is logged; summary.log keeps every one).
    const std::string out = testing_support::freshOutputDir("source_loss_summary");
    const firmware::Config config = lossConfig("source_loss_summary", out, 0.05);
    const int logFd = ::open((out + "/log.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    firmware::setLogFd(logFd);
    auto source = std::make_unique<FlakySource>();
    source->lost = true;
    firmware::FrameLoop loop(config, std::move(source), firmware::makeDisplay(config.display));
    FakeConsole console;
    loop.attachConsole(&console);
    for (int i = 0; i < 20; ++i)
        ASSERT_TRUE(loop.step());  // 50 ms each
    console.type("log 5\nlog warn 1\n");
    ASSERT_TRUE(loop.step());
    firmware::setLogFd(2);
    ::close(logFd);

    const std::string log = testing_support::readFile(out + "/log.txt");
    std::size_t summaries = 0;
    for (std::size_t at = 0; (at = log.find(" I frames=0 ", at)) != std::string::npos; ++at)
        ++summaries;
    EXPECT_EQ(summaries, 1u) << log;
    const std::string replies(console.output());
    EXPECT_NE(replies.find("W source lost: test camera unplugged (retrying)\n"), std::string::npos)
        << replies;
    const std::size_t warn = replies.rfind("W source lost");
    EXPECT_NE(warn, replies.find("W source lost")) << "in `log 5` and in `log warn 1`: " << replies;
}

/// Under systemd (Type=notify) a camera missing at boot must not keep the unit "activating" until
/// its start timeout kills it: the calm screen shown is the mirror running, so it is READY.
TEST(SourceLoss, CameraMissingAtBootIsStillReadyOnceTheCalmScreenIsShown)
{
    firmware::Config config;
    const std::string out = testing_support::freshOutputDir("source_missing_ready");
    config.display.spec = "headless:" + out;
    config.display.width = 160;
    config.display.height = 120;
    config.display.snapshotEvery = 0;
    config.card.enabled = false;
    config.faces.enabled = false;
    config.log.summaryIntervalS = 0;
    config.state.dir = testing_support::freshOutputDir("source_missing_ready_state");
    testing_support::FakeSystemd systemd(nullptr);

    auto source = std::make_unique<FlakySource>();
    source->lost = true;
    firmware::FrameLoop loop(config, std::move(source), firmware::makeDisplay(config.display));
    for (int i = 0; i < 3; ++i)
        ASSERT_TRUE(loop.step());
    EXPECT_EQ(loop.framesShown(), 0u);
    std::string all;
    for (const std::string& m : systemd.messages())
        all += m + "|";
    EXPECT_NE(all.find("READY=1\nSTATUS=camera unavailable"), std::string::npos) << all;
}

}  // namespace
