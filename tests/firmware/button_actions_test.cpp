#include "firmware/button_actions.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace {

using firmware::ButtonAction;
using firmware::ButtonActions;
using platform::ButtonEvent;

TEST(ButtonActions, TheDefaultMapIsTheIssuesMap)
{
    const ButtonActions map;
    EXPECT_EQ(map.actionFor(1, ButtonEvent::Short), ButtonAction::NextOverlay);
    EXPECT_EQ(map.actionFor(2, ButtonEvent::Short), ButtonAction::PrevOverlay);
    EXPECT_EQ(map.actionFor(1, ButtonEvent::Long), ButtonAction::TrainCard);
    EXPECT_EQ(map.actionFor(2, ButtonEvent::Long), ButtonAction::ToggleDebugHud);
    EXPECT_EQ(map.actionFor(ButtonEvent{2, ButtonEvent::Long, 123}), ButtonAction::ToggleDebugHud);
}

TEST(ButtonActions, ButtonsBeyondTheListsDoNothing)
{
    const ButtonActions map;
    EXPECT_EQ(map.actionFor(3, ButtonEvent::Short), ButtonAction::None);
    EXPECT_EQ(map.actionFor(0, ButtonEvent::Short), ButtonAction::None);
    EXPECT_EQ(map.actionFor(-4, ButtonEvent::Long), ButtonAction::None);
    EXPECT_EQ(map.actionFor(99, ButtonEvent::Long), ButtonAction::None);
}

TEST(ButtonActions, ACustomMap)
{
    const std::vector<std::string> shortPress{"prev", "next", "snapshot"};
    const std::vector<std::string> longPress{"off"};
    const ButtonActions map(shortPress, longPress);
    EXPECT_EQ(map.actionFor(1, ButtonEvent::Short), ButtonAction::PrevOverlay);
    EXPECT_EQ(map.actionFor(3, ButtonEvent::Short), ButtonAction::Snapshot);
    EXPECT_EQ(map.actionFor(1, ButtonEvent::Long), ButtonAction::OverlayOff);
    EXPECT_EQ(map.actionFor(2, ButtonEvent::Long), ButtonAction::None);
}

TEST(ButtonActions, UnknownWordsAreOneClearLine)
{
    const std::vector<std::string> shortPress{"next", "jump"};
    try {
        ButtonActions map(shortPress, {});
        FAIL() << "expected a throw";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("button 2"), std::string::npos) << what;
        EXPECT_NE(what.find("'jump'"), std::string::npos) << what;
        EXPECT_NE(what.find("train-card"), std::string::npos) << "lists the allowed: " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    const std::vector<std::string> tooMany(ButtonActions::kMaxButtons + 1, "none");
    EXPECT_THROW(ButtonActions(tooMany, {}), std::invalid_argument);
}

TEST(ButtonActions, WordsRoundTrip)
{
    for (ButtonAction a : {ButtonAction::None, ButtonAction::NextOverlay, ButtonAction::PrevOverlay,
                           ButtonAction::OverlayOff, ButtonAction::TrainCard,
                           ButtonAction::ToggleDebugHud, ButtonAction::Snapshot}) {
        ButtonAction back = ButtonAction::None;
        ASSERT_TRUE(firmware::parseButtonAction(firmware::toString(a), back));
        EXPECT_EQ(back, a);
        EXPECT_NE(std::string(firmware::buttonActionWords()).find(firmware::toString(a)),
                  std::string::npos);
    }
    ButtonAction out = ButtonAction::Snapshot;
    EXPECT_FALSE(firmware::parseButtonAction("Next", out));
    EXPECT_EQ(out, ButtonAction::Snapshot);
}

}  // namespace
