#pragma once
// ButtonInput: the push buttons on the mirror's frame (GPIO lines through libgpiod; tests feed
// scripted edges), delivered as debounced short and long presses.

#include <cstdint>

namespace platform {

/// One debounced press of one button.
struct ButtonEvent {
    enum Kind : std::uint8_t {
        Short,  ///< released before the long-press threshold; timeNs is the release
        Long,   ///< held for the long-press threshold; timeNs is when the threshold passed
    };
    /// 1-based: button n is the n-th line of `[buttons] lines`, as the wiring docs and the action
    /// map count them.
    int button = 0;
    Kind kind = Short;
    std::int64_t timeNs = 0;  ///< CLOCK_MONOTONIC
};

/// Buttons that the frame loop polls once per frame. Opened in the constructor of an
/// implementation, which throws std::runtime_error with one line when the device is missing or
/// busy (the firmware turns that into a warning and runs without buttons). poll() never blocks,
/// never throws and never allocates.
class ButtonInput {
public:
    virtual ~ButtonInput() = default;
    ButtonInput() = default;
    ButtonInput(const ButtonInput&) = delete;
    ButtonInput& operator=(const ButtonInput&) = delete;

    /// What this input is, for status and logs, e.g. "gpio:gpiochip0 lines 17,27 (active low)".
    virtual const char* description() const noexcept = 0;
    /// Number of buttons (ButtonEvent::button runs from 1 to buttonCount()).
    virtual int buttonCount() const noexcept = 0;
    /// Takes the presses completed since the last call, oldest first, at most `capacity`; the rest
    /// wait for the next call. Returns how many were written, or -1 when the device failed
    /// (lastError() says why; the input then stays silent, the caller may log it once).
    /// A long press is reported while the button is still held, so this must be called
    /// regularly (every frame) for long presses to fire on time.
    virtual int poll(ButtonEvent* out, int capacity) noexcept = 0;
    /// Reads whether each button is pressed now (out[0] is button 1). Returns the number of
    /// buttons read, or -1 on failure. For `selftest` ("GPIO lines readable").
    virtual int readPressed(bool* out, int capacity) noexcept = 0;
    /// A descriptor that becomes readable when edges are waiting (for a poll()-based loop), or -1.
    /// Long presses fire without any edge, so a loop waiting on it still needs a timeout.
    virtual int fd() const noexcept { return -1; }
    /// Reason for the last failure; "" when none.
    virtual const char* lastError() const noexcept { return ""; }
};

}  // namespace platform
