// An appliance started without its camera or panel: `auto` shows the calm screen and keeps looking
// (never the demo, never a picture every second on the SD card), READY is sent, and when the
// device comes the loop stops for the pipeline to be rebuilt on it.
#include "firmware/device_wait.hpp"

#include "fake_systemd.hpp"
#include "firmware/device_factory.hpp"
#include "firmware/frame_loop.hpp"
#include "platform/synthetic_source.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <memory>
#include <string>

namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

int countPngs(const std::string& dir)
{
    int n = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        n += entry.path().extension() == ".png";
    return n;
}

/// The service's environment: systemd's notification socket, its state folder, no desktop.
struct ApplianceEnvironment {
    explicit ApplianceEnvironment(const std::string& stateDir) : systemd(nullptr)
    {
        ::setenv("STATE_DIRECTORY", stateDir.c_str(), 1);
        ::unsetenv("DISPLAY");
    }
    ~ApplianceEnvironment() { ::unsetenv("STATE_DIRECTORY"); }
    testing_support::FakeSystemd systemd;
};

firmware::Config smallConfig(const std::string& name)
{
    firmware::Config config;
    config.display.width = 160;
    config.display.height = 120;
    config.source.width = 160;
    config.source.height = 120;
    config.card.enabled = false;
    config.faces.enabled = false;
    config.log.summaryIntervalS = 0;
    config.state.dir = testing_support::freshOutputDir(name + "_state");
    return config;
}

}  // namespace

TEST(DeviceWait, LooksAfterAnEventSettlesAndAtTheSlowPace)
{
    bool camera = false;
    firmware::DeviceProbes probes;
    probes.camera = [&] { return camera; };
    firmware::DeviceWait wait(true, false, probes, nullptr, {kSecond, 10 * kSecond});
    EXPECT_STREQ(wait.awaited(), "camera");
    const std::int64_t t0 = 100 * kSecond;
    EXPECT_FALSE(wait.poll(t0));
    camera = true;
    EXPECT_FALSE(wait.poll(t0 + 5 * kSecond)) << "no event: only at the slow pace";
    EXPECT_TRUE(wait.poll(t0 + 10 * kSecond));
    EXPECT_STREQ(wait.found(), "camera");
}

TEST(DeviceWait, TheLoopStopsForARebuildWhenTheCameraComes)
{
    const std::string out = testing_support::freshOutputDir("device_wait_loop");
    firmware::Config config = smallConfig("device_wait_loop");
    config.display.spec = "headless:" + out;
    config.display.snapshotEvery = 0;
    config.source.spec = "synthetic";
    bool camera = false;
    firmware::DeviceProbes probes;
    probes.camera = [&] { return camera; };
    firmware::FrameLoop loop(config, firmware::makeSource(config.source),
                             firmware::makeDisplay(config.display));
    loop.attachDeviceWait(std::make_unique<firmware::DeviceWait>(
        true, false, probes, nullptr, firmware::DeviceWaitOptions{1, 1}));
    for (int i = 0; i < 3; ++i)
        ASSERT_TRUE(loop.step());
    EXPECT_FALSE(loop.restartRequested());
    camera = true;
    ASSERT_TRUE(loop.step());
    EXPECT_TRUE(loop.restartRequested());
}

// On the appliance (under systemd) `auto` with no camera is the calm screen and a wait, with no
// panel an off-screen display that writes no snapshots on its own; READY is sent all the same.
TEST(DeviceWait, ApplianceWithNoCameraAndNoPanelWaitsCalmlyWithBoundedOutput)
{
    const std::string state = testing_support::freshOutputDir("device_wait_appliance");
    ApplianceEnvironment environment(state);
    firmware::Config config = smallConfig("device_wait_appliance");
    auto source = firmware::makeSource(config.source);
    EXPECT_NE(std::string(source->description()).find("no camera"), std::string::npos)
        << source->description();
    vision::Frame frame;
    EXPECT_EQ(source->next(frame), platform::SourceStatus::Lost);
    auto display = firmware::makeDisplay(config.display, config.state.dir);
    auto wait = firmware::makeDeviceWait(config, *source, *display);
    ASSERT_NE(wait, nullptr);
    EXPECT_STREQ(wait->awaited(), "camera and panel");

    // Real frames on the auto display: no PNG piles up in the state folder.
    firmware::Config synthetic = config;
    synthetic.source.spec = "synthetic";
    synthetic.source.rate.kind = firmware::Rate::Kind::Max;
    firmware::FrameLoop loop(synthetic, firmware::makeSource(synthetic.source), std::move(display));
    EXPECT_EQ(loop.run(65), 0);
    EXPECT_EQ(countPngs(state + "/display"), 0);
    std::string messages;
    for (const std::string& m : environment.systemd.messages())
        messages += m + "|";
    EXPECT_NE(messages.find("READY=1"), std::string::npos) << messages;
}

// A developer's run (no systemd) keeps the demo scene for `auto` without a camera.
TEST(DeviceWait, DeveloperRunWithoutCameraPlaysTheDemo)
{
    ::unsetenv("NOTIFY_SOCKET");
    firmware::Config config = smallConfig("device_wait_developer");
    auto source = firmware::makeSource(config.source);
    EXPECT_EQ(std::string(source->description()).find("no camera"), std::string::npos)
        << source->description();
    vision::Frame frame;
    EXPECT_EQ(source->next(frame), platform::SourceStatus::Ok);
}
