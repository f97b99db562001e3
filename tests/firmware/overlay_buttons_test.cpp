// Buttons and the console change what the faces wear, through the frame loop: a short press of
// button 1 puts the first overlay on the talking face, the console switches by name, a long press
// of button 2 shows the debug HUD, and the choice comes back after a restart. The button input
// is scripted, but its presses take the loop's real path (poll -> ButtonActions -> selection).
#include "fake_console.hpp"
#include "firmware/device_factory.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "overlay_loop_config.hpp"
#include "preloaded_face_source.hpp"
#include "test_paths.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

/// Buttons whose presses the test schedules by frame (one poll per frame).
class ScriptedButtons final : public platform::ButtonInput {
public:
    const char* description() const noexcept override { return "scripted test buttons"; }
    int buttonCount() const noexcept override { return 2; }
    int poll(platform::ButtonEvent* out, int capacity) noexcept override
    {
        ++polls_;
        if (capacity < 1 || pending_.button == 0 || polls_ < dueAt_)
            return 0;
        out[0] = pending_;
        pending_ = {};
        return 1;
    }
    int readPressed(bool* out, int capacity) noexcept override
    {
        for (int i = 0; i < capacity && i < 2; ++i)
            out[i] = false;
        return 2;
    }
    /// Delivers `event` at the `afterPolls`-th poll from now.
    void press(int button, platform::ButtonEvent::Kind kind, int afterPolls)
    {
        pending_ = {button, kind, 0};
        dueAt_ = polls_ + afterPolls;
    }

private:
    platform::ButtonEvent pending_{};
    int polls_ = 0;
    int dueAt_ = 0;
};

firmware::Config testConfig(const std::string& name)
{
    // "none": the first press of button 1 then puts on the first overlay.
    return overlayLoopConfig(name, "none");
}

TEST(OverlayButtons, PressesAndCommandsChangeWhatTheFaceWearsAndItIsKept)
{
    const std::string name = "overlay_buttons";
    std::filesystem::remove_all(testing_support::binaryDir() + "/test-output/" + name + "_state");
    const firmware::Config config = testConfig(name);
    const int devNull = ::open("/dev/null", O_WRONLY);
    firmware::setLogFd(devNull);
    {
        firmware::FrameLoop loop(config, std::make_unique<PreloadedFaceSource>(30),
                                 firmware::makeDisplay(config.display));
        auto buttons = std::make_unique<ScriptedButtons>();
        ScriptedButtons* b = buttons.get();
        loop.attachButtons(std::move(buttons));
        FakeConsole console;
        loop.attachConsole(&console);
        ASSERT_NE(loop.overlaySelection(), nullptr) << "the catalogue should load";
        const firmware::OverlaySelection& selection = *loop.overlaySelection();
        EXPECT_EQ(selection.selected(), -1);

        b->press(1, platform::ButtonEvent::Short, 20);
        for (int i = 0; i < 30; ++i)
            ASSERT_TRUE(loop.step());
        EXPECT_EQ(selection.selected(), 0) << "button 1: next overlay, from none to the first";
        int faceId = 0;
        for (const vision::TrackedFace& f : loop.lastFrameState().faces)
            if (f.shown())
                faceId = f.id;
        ASSERT_NE(faceId, 0) << "the talking face should be shown by now";
        EXPECT_EQ(selection.choiceFor(faceId).overlay, 0);

        const std::string second = selection.name(1);
        const std::string command = "overlay " + second + "\n";
        console.type(command.c_str());
        b->press(2, platform::ButtonEvent::Long, 1);
        for (int i = 0; i < 15; ++i)
            ASSERT_TRUE(loop.step());
        console.type("overlay\n");
        ASSERT_TRUE(loop.step());
        EXPECT_EQ(selection.selected(), 1);
        EXPECT_NEAR(selection.choiceFor(faceId).alpha, 1.f, 1e-3f) << "fully shown";
        EXPECT_TRUE(loop.debugHud()) << "button 2 long: debug HUD on";
        EXPECT_NE(console.output().find("overlay: " + second), std::string_view::npos)
            << console.output();
        EXPECT_NE(console.output().find("face " + std::to_string(faceId) + ": " + second),
                  std::string_view::npos)
            << console.output();
    }
    {
        // A restart comes back wearing the last choice.
        firmware::FrameLoop loop(config, std::make_unique<PreloadedFaceSource>(5),
                                 firmware::makeDisplay(config.display));
        ASSERT_NE(loop.overlaySelection(), nullptr);
        EXPECT_EQ(loop.overlaySelection()->selected(), 1);
    }
    firmware::setLogFd(2);
    ::close(devNull);
}

TEST(OverlayButtons, ABrokenCatalogueIsOneErrorAndTheMirrorRunsWithoutOverlays)
{
    firmware::Config config = testConfig("overlay_broken");
    config.overlay.catalogue = testing_support::sourceDir() + "/tests/data/config/bad_binary.toml";
    const std::string logPath = testing_support::freshOutputDir("overlay_broken_log") + "/log.txt";
    const int logFd = ::open(logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    firmware::setLogFd(logFd);
    firmware::FrameLoop loop(config, std::make_unique<PreloadedFaceSource>(5),
                             firmware::makeDisplay(config.display));
    FakeConsole console;
    loop.attachConsole(&console);
    console.type("selftest\noverlay next\n");
    for (int i = 0; i < 5; ++i)
        ASSERT_TRUE(loop.step());
    firmware::setLogFd(2);
    ::close(logFd);
    EXPECT_EQ(loop.overlaySelection(), nullptr);
    std::ifstream in(logPath);
    std::stringstream log;
    log << in.rdbuf();
    EXPECT_NE(log.str().find("bad_binary.toml"), std::string::npos) << log.str();
    EXPECT_NE(log.str().find("running without overlays"), std::string::npos) << log.str();
    EXPECT_NE(console.output().find("FAIL overlays"), std::string_view::npos) << console.output();
    EXPECT_NE(console.output().find("overlay: none loaded"), std::string_view::npos)
        << console.output();
}

TEST(ConsoleCommands, EveryCommandTakesItsArgumentsOneWayWithTheUsageInEachError)
{
    firmware::Config config = testConfig("console_arguments");
    const int devNull = ::open("/dev/null", O_WRONLY);
    firmware::setLogFd(devNull);
    firmware::FrameLoop loop(config, std::make_unique<PreloadedFaceSource>(5),
                             firmware::makeDisplay(config.display));
    FakeConsole console;
    loop.attachConsole(&console);
    ASSERT_NE(loop.overlaySelection(), nullptr);
    console.type(
        "status now\nversion extra\nquit now\nlog 0\nlog -1\nlog warn 2 x\n"
        "overlay mode\noverlay 99\noverlay 3\nstatus --json\ndebug maybe\n");
    ASSERT_TRUE(loop.step()) << "quit now must not stop the mirror";
    firmware::setLogFd(2);
    ::close(devNull);
    const std::string out(console.output());
    const std::string overlayUsage =
        "usage: overlay [next|prev|off|list|NAME|N|mode global|per_face]";
    for (const std::string& expected :
         {std::string("error: unknown option 'now'; usage: status [--json]\n"),
          std::string("error: unexpected argument 'extra'; usage: version\n"),
          std::string("error: unexpected argument 'now'; usage: quit\n"),
          std::string("error: N must be 1..200, got '0'; usage: log [error|warn|info|debug] [N]\n"),
          std::string(
              "error: N must be 1..200, got '-1'; usage: log [error|warn|info|debug] [N]\n"),
          std::string("error: unexpected argument 'x'; usage: log [error|warn|info|debug] [N]\n"),
          "error: mode needs global or per_face; " + overlayUsage + "\n",
          "error: no overlay '99' (overlay list: names and numbers 1.." +
              std::to_string(loop.overlaySelection()->size()) + "); " + overlayUsage + "\n",
          "overlay: " + std::string(loop.overlaySelection()->name(2)) + "\n",
          std::string("{\"version\":\""),
          std::string("error: expected on or off, got 'maybe'; usage: debug [on|off]\n")})
        EXPECT_NE(out.find(expected), std::string::npos) << expected << "\nin:\n" << out;
    EXPECT_EQ(loop.overlaySelection()->selected(), 2) << "overlay 3: the third of `overlay list`";
    // Every line of the reply to each bad command starts with "error: " and names the usage.
    for (std::size_t at = 0; (at = out.find("error: ", at)) != std::string::npos; ++at)
        EXPECT_NE(out.substr(at, out.find('\n', at) - at).find("; usage: "), std::string::npos)
            << out.substr(at, out.find('\n', at) - at);
}

}  // namespace
