// The calendar and the weather through the frame loop: on a configured special day the talking
// face wears the day's overlay, with a forecast (a file another service writes) the weather's,
// a button press still changes what the face wears, and `status` says which rule chose it and
// when the forecast was fetched.
#include "fake_console.hpp"
#include "firmware/day_calendar.hpp"
#include "firmware/device_factory.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "overlay_loop_config.hpp"
#include "preloaded_face_source.hpp"
#include "test_paths.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace {

firmware::Config testConfig(const std::string& name)
{
    firmware::Config config = overlayLoopConfig(name, "glasses");
    config.state.dir = testing_support::freshOutputDir(name + "_state");
    return config;
}

int shownFace(const firmware::FrameLoop& loop)
{
    for (const vision::TrackedFace& f : loop.lastFrameState().faces)
        if (f.shown())
            return f.id;
    return 0;
}

class OverlayDaysWeather : public ::testing::Test {
protected:
    /// A frame loop on the talking face with `config`, the console attached.
    struct Mirror {
        explicit Mirror(const firmware::Config& config)
            : loop(config, std::make_unique<PreloadedFaceSource>(30),
                   firmware::makeDisplay(config.display))
        {
            loop.attachConsole(&console);
        }
        /// `status` as the console prints it now.
        std::string status()
        {
            console.type("status\n");
            EXPECT_TRUE(loop.step());
            return std::string(console.output());
        }
        firmware::FrameLoop loop;
        FakeConsole console;
    };

    void SetUp() override
    {
        devNull_ = ::open("/dev/null", O_WRONLY);
        firmware::setLogFd(devNull_);
    }
    void TearDown() override
    {
        firmware::setLogFd(2);
        ::close(devNull_);
    }
    int devNull_ = -1;
};

TEST_F(OverlayDaysWeather, OnASpecialDayTheFaceWearsTheDaysOverlayUntilAButtonSaysOtherwise)
{
    firmware::Config config = testConfig("overlay_day");
    // A past day, today's (as a range of one day), and today's again naming an overlay the
    // catalogue lacks (a warning at start-up, left out).
    config.days.dates = {"2001-01-01 top_hat",
                         todayMonthDay() + ".." + todayMonthDay() + " graduation_cap",
                         todayMonthDay() + " no_such_hat"};
    Mirror mirror(config);
    firmware::FrameLoop& loop = mirror.loop;
    ASSERT_NE(loop.overlaySelection(), nullptr);
    const firmware::OverlaySelection& selection = *loop.overlaySelection();
    for (int i = 0; i < 25; ++i)
        ASSERT_TRUE(loop.step());
    const int face = shownFace(loop);
    ASSERT_NE(face, 0);
    EXPECT_STREQ(selection.name(selection.choiceFor(face).overlay), "graduation_cap");
    EXPECT_EQ(selection.ruleFor(face), firmware::OverlayRule::Day);

    const std::string status = mirror.status();
    EXPECT_NE(status.find("day: graduation_cap (" + todayMonthDay() + ".." + todayMonthDay() +
                          " graduation_cap)"),
              std::string::npos)
        << status;
    EXPECT_NE(status.find("face " + std::to_string(face) + ": graduation_cap alpha 1.00 by day"),
              std::string::npos)
        << status;
    EXPECT_NE(status.find("weather: none (no [weather] source)"), std::string::npos) << status;

    mirror.console.type("overlay sunglasses\n");
    for (int i = 0; i < 3; ++i)
        ASSERT_TRUE(loop.step());
    EXPECT_STREQ(selection.name(selection.choiceFor(face).overlay), "sunglasses");
    EXPECT_EQ(selection.ruleFor(face), firmware::OverlayRule::Person);
}

TEST_F(OverlayDaysWeather, TheForecastPutsItsHatOnAndStatusSaysWhenItWasFetched)
{
    firmware::Config config = testConfig("overlay_weather");
    const std::string forecast = config.state.dir + "/../overlay_weather_forecast.json";
    std::ofstream(forecast) << R"({"current":{"weather_code":63}})";
    config.weather.source = "file:" + forecast;
    Mirror mirror(config);
    firmware::FrameLoop& loop = mirror.loop;
    ASSERT_NE(loop.overlaySelection(), nullptr);
    const firmware::OverlaySelection& selection = *loop.overlaySelection();
    // The forecast is read by another thread; the wall clock decides once a second.
    for (int i = 0; i < 400 && selection.automatic(firmware::OverlayRule::Weather) < 0; ++i) {
        ASSERT_TRUE(loop.step());
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    for (int i = 0; i < 25; ++i)
        ASSERT_TRUE(loop.step());
    const int face = shownFace(loop);
    ASSERT_NE(face, 0);
    EXPECT_STREQ(selection.name(selection.choiceFor(face).overlay), "rain_hat");
    EXPECT_EQ(selection.ruleFor(face), firmware::OverlayRule::Weather);
    const std::string status = mirror.status();
    EXPECT_NE(status.find("weather: rain_hat: rain (code 63) fetched 0 min ago from file:"),
              std::string::npos)
        << status;
    EXPECT_NE(status.find("by weather"), std::string::npos) << status;
    EXPECT_TRUE(std::filesystem::exists(config.state.dir + "/weather.json"))
        << "the forecast is kept for a restart without network";
}

}  // namespace
