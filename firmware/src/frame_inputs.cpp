// FrameLoop, step 4's inputs: the buttons on the frame and a display's own keyboard (the desktop
// window) run their actions through the same paths as the console commands.
#include "card_control.hpp"
#include "face_control.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "overlay_control.hpp"
#include "people_control.hpp"
#include "monotonic_clock.hpp"

#include <string_view>

namespace firmware {

namespace {

/// What an overlay button does to who wears what (as `overlay next|prev|off`).
void changeOverlay(OverlaySelection& selection, ButtonAction action) noexcept
{
    if (action == ButtonAction::NextOverlay)
        selection.next();
    else if (action == ButtonAction::PrevOverlay)
        selection.prev();
    else
        selection.off();
}

}  // namespace

void FrameLoop::pollButtons() noexcept
{
    if (!buttons_ || buttonsFailed_)
        return;
    platform::ButtonEvent events[8];
    const int n = buttons_->poll(events, 8);
    if (n < 0) {
        MIRROR_LOG_WARN("buttons: %s; ignoring them from now on", buttons_->lastError());
        buttonsFailed_ = true;
        return;
    }
    for (int i = 0; i < n; ++i) {
        const ButtonAction action = buttonActions_.actionFor(events[i]);
        MIRROR_LOG_INFO("button %d %s press: %s", events[i].button,
                        events[i].kind == platform::ButtonEvent::Long ? "long" : "short",
                        toString(action));
        runButtonAction(action);
    }
}

void FrameLoop::pollKeys() noexcept
{
    // A display with a keyboard (the desktop window, for development): the keys do what the
    // buttons and the console do.
    if (display_->closeRequested()) {
        MIRROR_LOG_INFO("window closed: stopping");
        requestStop();
        return;
    }
    platform::KeyEvent key;
    while (display_->nextKey(key)) {
        const std::string_view k = key.name;
        if (k == "n" || k == "Right")
            runButtonAction(ButtonAction::NextOverlay);
        else if (k == "p" || k == "Left")
            runButtonAction(ButtonAction::PrevOverlay);
        else if (k == "o")
            runButtonAction(ButtonAction::OverlayOff);
        else if (k == "t")
            runButtonAction(ButtonAction::TrainCard);
        else if (k == "d")
            runButtonAction(ButtonAction::ToggleDebugHud);
        else if (k == "s")
            runButtonAction(ButtonAction::Snapshot);
        else if (k == "h")
            renderer_->setHudVisible(!renderer_->hudVisible());
        else if (k == "q" || k == "Escape")
            requestStop();
    }
}

void FrameLoop::runButtonAction(ButtonAction action) noexcept
{
    // The same paths as the console commands.
    switch (action) {
        case ButtonAction::None:
            break;
        case ButtonAction::NextOverlay:
        case ButtonAction::PrevOverlay:
        case ButtonAction::OverlayOff:
            if (OverlaySelection* selection = overlays_->selection())
                changeOverlay(*selection, action);
            break;
        case ButtonAction::TrainCard:
            requestCardTraining();
            break;
        case ButtonAction::ToggleDebugHud:
            setDebugHud(!debugHud());
            break;
        case ButtonAction::Snapshot:
            display_->requestSnapshot();
            break;
        case ButtonAction::EnrolGuest:
            if (people_) {
                const char* what = people_->enrolGuest(state_.faces, state_.fits, monotonicNs());
                MIRROR_LOG_INFO("%s", what);
            }
            break;
    }
}

void FrameLoop::requestCardTraining() noexcept
{
    if (card_)
        card_->requestTraining();
}

void FrameLoop::setDebugHud(bool on) noexcept
{
    if (faces_)
        faces_->setDebugHud(on);
}

}  // namespace firmware
