#pragma once
// ButtonActions: what a button press does, per `[buttons.actions]` in the config. The frame loop
// polls the ButtonInput, asks actionFor() and executes the action (the same code paths as the
// console commands `overlay next|prev|off`, `card train`, `snapshot`, and the debug HUD switch).
//
// The map is two lists indexed by button (entry n-1 is button n, the n-th of `[buttons] lines`):
//   short = ["next", "prev"]                # default: button 1 next overlay, button 2 previous
//   long  = ["train-card", "toggle-debug", "enrol-guest"]
//                        # default: long 1 trains the card, long 2 flips the debug HUD (face
//                        # boxes, corners, roll), long 3 enrols the nearest face as a guest
// A button beyond a list's end does nothing for that kind of press.

#include "platform/button_input.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace firmware {

enum class ButtonAction : std::uint8_t {
    None,            ///< "none"
    NextOverlay,     ///< "next"
    PrevOverlay,     ///< "prev"
    OverlayOff,      ///< "off"
    TrainCard,       ///< "train-card": as the console's `card train`
    ToggleDebugHud,  ///< "toggle-debug": show or hide the debug HUD (`[display] debug`)
    Snapshot,        ///< "snapshot": as the console's `snapshot`
    EnrolGuest,      ///< "enrol-guest": the nearest face enrolled as the next "guest-N"
};

/// The config word of an action.
const char* toString(ButtonAction action) noexcept;
/// False for an unknown word (`out` unchanged).
bool parseButtonAction(std::string_view word, ButtonAction& out) noexcept;
/// Every config word, for messages: "none, next, prev, off, train-card, toggle-debug, snapshot,
/// enrol-guest".
const char* buttonActionWords() noexcept;

class ButtonActions {
public:
    static constexpr int kMaxButtons = 16;

    /// The default map (above).
    ButtonActions();
    /// Throws std::invalid_argument with one line for an unknown word or more than kMaxButtons
    /// entries in a list (the config validates the same with parseButtonAction()).
    ButtonActions(std::span<const std::string> shortPress, std::span<const std::string> longPress);

    ButtonAction actionFor(const platform::ButtonEvent& event) const noexcept;
    ButtonAction actionFor(int button, platform::ButtonEvent::Kind kind) const noexcept;

    /// The default lists as config words (for the embedded config and its tests).
    static std::vector<std::string> defaultShort();
    static std::vector<std::string> defaultLong();

private:
    std::array<ButtonAction, kMaxButtons> short_{};
    std::array<ButtonAction, kMaxButtons> long_{};
};

}  // namespace firmware
