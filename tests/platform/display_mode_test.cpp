// Display mode parsing ("WxH[@Hz]") and the choice among a connector's modes.

#include "platform/display_mode.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using platform::DisplayModeCandidate;
using platform::DisplayModeRequest;

TEST(DisplayMode, Parses)
{
    DisplayModeRequest r;
    std::string error;
    ASSERT_TRUE(platform::parseDisplayMode("", r, error));
    EXPECT_TRUE(r.preferred());
    ASSERT_TRUE(platform::parseDisplayMode("preferred", r, error));
    EXPECT_TRUE(r.preferred());
    ASSERT_TRUE(platform::parseDisplayMode("1280x720", r, error));
    EXPECT_EQ(r.width, 1280);
    EXPECT_EQ(r.height, 720);
    EXPECT_EQ(r.refreshHz, 0.0);
    ASSERT_TRUE(platform::parseDisplayMode("1920x1080@59.94", r, error));
    EXPECT_EQ(r.width, 1920);
    EXPECT_DOUBLE_EQ(r.refreshHz, 59.94);
    for (const char* bad : {"1280", "1280x", "x720", "1280x720@", "1280x720@fast", "-1x5",
                            "1280*720", "1280x720@0", "99999999x1"}) {
        EXPECT_FALSE(platform::parseDisplayMode(bad, r, error)) << bad;
        EXPECT_NE(error.find("display mode"), std::string::npos) << error;
        EXPECT_TRUE(r.preferred());
    }
}

TEST(DisplayMode, ChoosesPreferredOrRequested)
{
    // As vkms lists them: the preferred 1024x768 is not first.
    const std::vector<DisplayModeCandidate> modes = {
        {1920, 1080, 60.0, false, false}, {1920, 1080, 50.0, false, false},
        {1920, 1080, 60.0, false, true},  {1280, 720, 59.94, false, false},
        {1280, 720, 60.0, false, false},  {1024, 768, 60.0, true, false},
        {1024, 768, 75.0, false, false},
    };
    EXPECT_EQ(platform::chooseDisplayMode(modes, {}), 5);
    EXPECT_EQ(platform::chooseDisplayMode(modes, {1920, 1080, 0.0}), 0);  // fastest progressive
    EXPECT_EQ(platform::chooseDisplayMode(modes, {1920, 1080, 50.0}), 1);
    EXPECT_EQ(platform::chooseDisplayMode(modes, {1280, 720, 59.94}), 3);
    EXPECT_EQ(platform::chooseDisplayMode(modes, {1280, 720, 60.0}), 4);
    EXPECT_EQ(platform::chooseDisplayMode(modes, {1024, 768, 0.0}), 5);  // preferred of the size
    EXPECT_EQ(platform::chooseDisplayMode(modes, {1024, 768, 75.0}), 6);
    EXPECT_EQ(platform::chooseDisplayMode(modes, {1024, 768, 30.0}), -1);
    EXPECT_EQ(platform::chooseDisplayMode(modes, {800, 600, 0.0}), -1);

    const std::vector<DisplayModeCandidate> noPreferred = {{800, 600, 60.0, false, false},
                                                           {640, 480, 60.0, false, false}};
    EXPECT_EQ(platform::chooseDisplayMode(noPreferred, {}), 0);
    const std::vector<DisplayModeCandidate> none;
    EXPECT_EQ(platform::chooseDisplayMode(none, {}), -1);
    EXPECT_EQ(platform::displayModeName(modes[3]), "1280x720@59.94");
}

}  // namespace
