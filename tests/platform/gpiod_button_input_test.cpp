// GpiodButtonInput. On any machine: opening what is not there fails with one clear line. On a
// machine with a gpio-sim chip (the HIL guest; MIRROR_TEST_GPIO_SIM, see below): real presses
// through the kernel's edge events. The debounce and press logic itself is tested with timed
// edges in button_press_classifier_test (through process(), the call poll() makes).

#include "platform/gpiod_button_input.hpp"

#include <gtest/gtest.h>
#include <poll.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using platform::ButtonEvent;
using platform::GpiodButtonInput;
using platform::GpiodButtonOptions;

std::string openError(const GpiodButtonOptions& options)
{
    // std::runtime_error is the promise the firmware relies on (it turns it into a warning).
    try {
        GpiodButtonInput input(options);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return {};
}

void expectOneLine(const std::string& message)
{
    EXPECT_FALSE(message.empty()) << "expected the constructor to throw";
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_LT(message.size(), 200u) << message;
}

TEST(GpiodButtonInput, AMissingChipPathIsOneClearLine)
{
    GpiodButtonOptions options;
    options.chip = "/nonexistent/gpiochip7";
    options.lines = {17, 27};
    const std::string message = openError(options);
    expectOneLine(message);
    EXPECT_EQ(message.rfind("gpio: ", 0), 0u) << message;
    EXPECT_NE(message.find("/nonexistent/gpiochip7"), std::string::npos) << message;
    EXPECT_NE(message.find("cannot open"), std::string::npos) << message;
}

TEST(GpiodButtonInput, AMissingChipNameIsOneClearLine)
{
    // A name no machine has; on a board without any GPIO (this host) gpiochip0 fails the same way.
    GpiodButtonOptions options;
    options.chip = "gpiochip987";
    options.lines = {5};
    const std::string message = openError(options);
    expectOneLine(message);
    EXPECT_NE(message.find("gpiochip987"), std::string::npos) << message;
}

TEST(GpiodButtonInput, ADeviceThatIsNotAGpioChipIsRefused)
{
    ASSERT_TRUE(std::filesystem::exists("/dev/null"));
    GpiodButtonOptions options;
    options.chip = "/dev/null";
    options.lines = {0};
    const std::string message = openError(options);
    expectOneLine(message);
    EXPECT_NE(message.find("/dev/null"), std::string::npos) << message;
}

TEST(GpiodButtonInput, ABadButtonCountIsRefusedBeforeTheChipIsOpened)
{
    GpiodButtonOptions options;
    options.chip = "/nonexistent/gpiochip7";
    options.lines = {};
    const std::string message = openError(options);
    expectOneLine(message);
    EXPECT_NE(message.find("0 buttons"), std::string::npos) << message;
}

TEST(GpiodButtonInput, BiasWordsRoundTrip)
{
    for (const char* word : {"as-is", "disable", "pull-up", "pull-down"}) {
        platform::GpioBias bias{};
        ASSERT_TRUE(platform::parseGpioBias(word, bias)) << word;
        EXPECT_STREQ(platform::toString(bias), word);
    }
    platform::GpioBias bias{};
    EXPECT_FALSE(platform::parseGpioBias("pullup", bias));
}

// The kernel's stamps on the monotonic clock, however late the frame loop reads them: a frame
// loop stalled for seconds (a busy machine) must still see a 150 ms press as a 150 ms press.
constexpr std::int64_t kSecond = 1'000'000'000;
constexpr std::int64_t kMonotonicNow = 500 * kSecond;               // 500 s since boot
constexpr std::int64_t kWallNow = 1'796'000'000LL * kSecond;        // late 2026

TEST(GpiodButtonInput, AMonotonicStampReadLateKeepsItsTime)
{
    for (const std::int64_t late : {std::int64_t{0}, kSecond / 10, 3 * kSecond, 60 * kSecond}) {
        const std::int64_t stamp = kMonotonicNow - late;
        EXPECT_EQ(platform::edgeStampToMonotonicNs(stamp, kMonotonicNow, kWallNow), stamp) << late;
    }
}

TEST(GpiodButtonInput, AWallClockStampOfAnOlderKernelIsMovedOntoTheMonotonicClock)
{
    const std::int64_t late = 3 * kSecond;
    EXPECT_EQ(platform::edgeStampToMonotonicNs(kWallNow - late, kMonotonicNow, kWallNow),
              kMonotonicNow - late);
    // A board whose clock was never set (the epoch plus its uptime): the clocks nearly agree,
    // and either reading is off by no more than their offset (here 2 ms).
    const std::int64_t offset = 2'000'000;
    EXPECT_NEAR(platform::edgeStampToMonotonicNs(kMonotonicNow + offset - late, kMonotonicNow,
                                                  kMonotonicNow + offset),
                kMonotonicNow - late, offset);
    // Never later than now, whichever clock it was.
    EXPECT_EQ(platform::edgeStampToMonotonicNs(kMonotonicNow + kSecond, kMonotonicNow, kWallNow),
              kMonotonicNow);
}

TEST(GpiodButtonInput, AShortPressReadSecondsLateIsStillAShortPress)
{
    // The two edges of a 150 ms press, read together 3 s after the release.
    platform::ButtonPressOptions press;
    press.longPressNs = 2 * kSecond;
    platform::ButtonPressClassifier classifier(1, press);
    const std::int64_t down = kMonotonicNow - 3 * kSecond - kSecond * 15 / 100;
    const std::int64_t up = kMonotonicNow - 3 * kSecond;
    classifier.setLevel(1, true, down - kSecond);  // released (active low: high)
    const platform::ButtonEdge edges[] = {
        {1, false, platform::edgeStampToMonotonicNs(down, kMonotonicNow, kWallNow)},
        {1, true, platform::edgeStampToMonotonicNs(up, kMonotonicNow, kWallNow)}};
    ButtonEvent out[4];
    const int n = classifier.process(edges, kMonotonicNow, out, 4);
    ASSERT_EQ(n, 1);
    EXPECT_EQ(out[0].button, 1);
    EXPECT_EQ(out[0].kind, ButtonEvent::Short);
}

/// A gpio-sim chip with at least two lines, given as "CHIP SYSFS_DIR": the chip (path or name)
/// and the folder holding its sim_gpio0/, sim_gpio1/ (e.g. "/dev/gpiochip1
/// /sys/devices/platform/gpio-sim.0/gpiochip1"). Lines 0 and 1 are the buttons; a press is
/// simulated by pulling the line down (buttons to ground, active low, pull-up bias).
class GpioSimChip : public testing::Test {
protected:
    void SetUp() override
    {
        const char* spec = std::getenv("MIRROR_TEST_GPIO_SIM");
        if (!spec || !*spec)
            GTEST_SKIP() << "no gpio-sim chip: set MIRROR_TEST_GPIO_SIM=\"CHIP SYSFS_DIR\" "
                            "(the HIL guest does)";
        std::istringstream in(spec);
        in >> chip_ >> sysfs_;
        ASSERT_TRUE(std::filesystem::exists(sysfs_ + "/sim_gpio1/pull")) << spec;
        options_.chip = chip_;
        options_.lines = {0, 1};
        options_.bias = platform::GpioBias::PullUp;
        options_.press.longPressNs = 800'000'000;
    }

    void pull(int line, bool down)
    {
        std::ofstream(sysfs_ + "/sim_gpio" + std::to_string(line) + "/pull")
            << (down ? "pull-down" : "pull-up");
    }

    /// Polls like the frame loop (every 10 ms) for `seconds`, collecting presses.
    static std::vector<ButtonEvent> pollFor(GpiodButtonInput& input, double seconds)
    {
        std::vector<ButtonEvent> all;
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (std::chrono::steady_clock::now() < end) {
            ButtonEvent events[8];
            const int n = input.poll(events, 8);
            EXPECT_GE(n, 0) << input.lastError();
            all.insert(all.end(), events, events + std::max(n, 0));
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return all;
    }

    std::string chip_;
    std::string sysfs_;
    platform::GpiodButtonOptions options_;
};

TEST_F(GpioSimChip, ShortAndLongPressesAndBounce)
{
    pull(0, false);
    pull(1, false);
    GpiodButtonInput input(options_);
    EXPECT_NE(std::string(input.description()).find("lines 0,1"), std::string::npos)
        << input.description();
    bool pressed[2] = {true, true};
    ASSERT_EQ(input.readPressed(pressed, 2), 2) << input.lastError();
    EXPECT_FALSE(pressed[0]);
    EXPECT_FALSE(pressed[1]);
    EXPECT_TRUE(pollFor(input, 0.1).empty());

    // Button 1: a short press (well under the long threshold, well over the debounce).
    pull(0, true);
    auto events = pollFor(input, 0.2);
    EXPECT_TRUE(events.empty());
    ASSERT_EQ(input.readPressed(pressed, 2), 2);
    EXPECT_TRUE(pressed[0]);
    pull(0, false);
    events = pollFor(input, 0.3);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].button, 1);
    EXPECT_EQ(events[0].kind, ButtonEvent::Short);

    // Button 2: held well past the threshold; the long press comes while it is still held.
    pull(1, true);
    events = pollFor(input, 1.6);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].button, 2);
    EXPECT_EQ(events[0].kind, ButtonEvent::Long);
    pull(1, false);
    EXPECT_TRUE(pollFor(input, 0.3).empty()) << "the release of a long press is silent";

    // Button 1 bouncing: level changes in quick succession, then held and released.
    for (int i = 0; i < 3; ++i) {
        pull(0, true);
        pull(0, false);
    }
    pull(0, true);
    pollFor(input, 0.2);
    pull(0, false);
    events = pollFor(input, 0.3);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].button, 1);
    EXPECT_EQ(events[0].kind, ButtonEvent::Short);
}

TEST_F(GpioSimChip, TheEpollDescriptorWakesOnAnEdge)
{
    pull(0, false);
    GpiodButtonInput input(options_);
    ASSERT_GE(input.fd(), 0);
    pollfd p{input.fd(), POLLIN, 0};
    EXPECT_EQ(::poll(&p, 1, 0), 0) << "nothing waiting yet";
    pull(0, true);
    EXPECT_EQ(::poll(&p, 1, 2000), 1);
    pull(0, false);
    pollFor(input, 0.1);
}

TEST_F(GpioSimChip, BusyLinesAreOneClearLineNamingTheUser)
{
    GpiodButtonInput first(options_);
    const std::string message = openError(options_);
    expectOneLine(message);
    EXPECT_NE(message.find("busy"), std::string::npos) << message;
    EXPECT_NE(message.find("'mirror'"), std::string::npos) << message;
}

TEST_F(GpioSimChip, ALineBeyondTheChipIsOneClearLine)
{
    options_.lines = {0, 4000};
    const std::string message = openError(options_);
    expectOneLine(message);
    EXPECT_NE(message.find("no line 4000"), std::string::npos) << message;
}

}  // namespace
