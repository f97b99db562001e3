#include "firmware/button_actions.hpp"

#include <stdexcept>

namespace firmware {

namespace {

struct Word {
    ButtonAction action;
    const char* word;
};

constexpr Word kWords[] = {
    {ButtonAction::None, "none"},
    {ButtonAction::NextOverlay, "next"},
    {ButtonAction::PrevOverlay, "prev"},
    {ButtonAction::OverlayOff, "off"},
    {ButtonAction::TrainCard, "train-card"},
    {ButtonAction::ToggleDebugHud, "toggle-debug"},
    {ButtonAction::Snapshot, "snapshot"},
    {ButtonAction::EnrolGuest, "enrol-guest"},
};

void fill(std::array<ButtonAction, ButtonActions::kMaxButtons>& out,
          std::span<const std::string> words, const char* kind)
{
    if (words.size() > out.size())
        throw std::invalid_argument(std::string("buttons: ") + kind + " actions for " +
                                    std::to_string(words.size()) + " buttons, at most " +
                                    std::to_string(out.size()));
    out.fill(ButtonAction::None);
    for (std::size_t i = 0; i < words.size(); ++i) {
        if (!parseButtonAction(words[i], out[i]))
            throw std::invalid_argument(std::string("buttons: ") + kind + " action of button " +
                                        std::to_string(i + 1) + ": unknown action '" + words[i] +
                                        "' (allowed: " + buttonActionWords() + ")");
    }
}

}  // namespace

const char* toString(ButtonAction action) noexcept
{
    for (const Word& w : kWords) {
        if (w.action == action)
            return w.word;
    }
    return "none";
}

bool parseButtonAction(std::string_view word, ButtonAction& out) noexcept
{
    for (const Word& w : kWords) {
        if (word == w.word) {
            out = w.action;
            return true;
        }
    }
    return false;
}

const char* buttonActionWords() noexcept
{
    return "none, next, prev, off, train-card, toggle-debug, snapshot, enrol-guest";
}

std::vector<std::string> ButtonActions::defaultShort()
{
    return {"next", "prev"};
}

std::vector<std::string> ButtonActions::defaultLong()
{
    return {"train-card", "toggle-debug", "enrol-guest"};
}

ButtonActions::ButtonActions() : ButtonActions(defaultShort(), defaultLong()) {}

ButtonActions::ButtonActions(std::span<const std::string> shortPress,
                             std::span<const std::string> longPress)
{
    fill(short_, shortPress, "short-press");
    fill(long_, longPress, "long-press");
}

ButtonAction ButtonActions::actionFor(int button, platform::ButtonEvent::Kind kind) const noexcept
{
    if (button < 1 || button > kMaxButtons)
        return ButtonAction::None;
    const auto& map = kind == platform::ButtonEvent::Long ? long_ : short_;
    return map[static_cast<std::size_t>(button - 1)];
}

ButtonAction ButtonActions::actionFor(const platform::ButtonEvent& event) const noexcept
{
    return actionFor(event.button, event.kind);
}

}  // namespace firmware
