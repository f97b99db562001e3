#pragma once
// GpiodButtonInput: push buttons on GPIO lines through libgpiod (Debian 12: 1.6), debounced and
// classified by ButtonPressClassifier.

#include "platform/button_input.hpp"
#include "platform/button_press_classifier.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace platform {

namespace detail {
class GpiodLines;
}

/// The line's internal resistor, as set when the lines are requested (kernel 5.5 or later).
enum class GpioBias : std::uint8_t {
    AsIs,      ///< leave whatever the board or device tree set
    Disable,   ///< no resistor (external pull resistors on the board)
    PullUp,    ///< for a switch to ground, read active-low (the usual wiring)
    PullDown,  ///< for a switch to 3.3 V, read active-high
};

struct GpiodButtonOptions {
    std::string chip = "gpiochip0";  ///< name, number, label or path (gpiod_chip_open_lookup)
    std::vector<unsigned> lines;     ///< line offsets on the chip; button n is lines[n-1]
    GpioBias bias = GpioBias::PullUp;
    ButtonPressOptions press;         ///< debounce, long press, active-low (here, not the kernel)
    std::string consumer = "mirror";  ///< shown as the lines' user by `gpioinfo`
};

/// Buttons on the lines of one GPIO chip, with edge events on both edges.
///
/// The lines are requested as inputs with edge events and the configured bias, but without the
/// kernel's active-low flag: the edges arrive as physical levels and the classifier applies
/// active-low, so the kernel's reading of the flag (which differs between uAPI versions) never
/// matters. The event descriptors are made non-blocking and gathered in one epoll descriptor
/// (fd()); poll() reads what is waiting, feeds each edge to the classifier, lets it see the time
/// (for long presses) and returns the presses.
///
/// Timestamps: the kernel stamps events with CLOCK_MONOTONIC since Linux 5.7 and with the wall
/// clock before; edgeStampToMonotonicNs() puts either on CLOCK_MONOTONIC, so a press keeps its
/// length however late the frame loop reads it.
///
/// The constructor throws std::runtime_error with one line ("gpio: ...: why") when the chip is
/// missing, a line does not exist or is used by someone else, or the kernel refuses the bias.
/// Everything libgpiod is behind detail::GpiodLines (src/gpiod_lines.hpp); a libgpiod 2.x port
/// replaces only that file's implementation (see the notes there).
class GpiodButtonInput final : public ButtonInput {
public:
    explicit GpiodButtonInput(const GpiodButtonOptions& options);
    ~GpiodButtonInput() override;

    const char* description() const noexcept override { return description_; }
    int buttonCount() const noexcept override { return classifier_.buttonCount(); }
    int poll(ButtonEvent* out, int capacity) noexcept override;
    int readPressed(bool* out, int capacity) noexcept override;
    int fd() const noexcept override { return epollFd_; }
    const char* lastError() const noexcept override { return error_; }

    /// Counters of the debouncer (filtered bounces, dropped events), for `status`.
    const ButtonPressClassifier& classifier() const noexcept { return classifier_; }

private:
    std::unique_ptr<detail::GpiodLines> lines_;
    ButtonPressClassifier classifier_;
    std::array<ButtonEdge, 64> edges_{};
    int epollFd_ = -1;
    bool failed_ = false;
    char description_[160] = "";
    char error_[160] = "";
};

/// An edge event's kernel stamp on CLOCK_MONOTONIC, given both clocks read just now: a stamp
/// nearer the wall clock than the monotonic clock (a kernel before 5.7) is moved by the clocks'
/// offset; none is later than now.
std::int64_t edgeStampToMonotonicNs(std::int64_t stampNs, std::int64_t monotonicNowNs,
                                    std::int64_t realtimeNowNs) noexcept;

/// Parses "as-is", "disable", "pull-up", "pull-down" (the config's words); false if none.
bool parseGpioBias(const std::string& text, GpioBias& out) noexcept;
const char* toString(GpioBias bias) noexcept;

}  // namespace platform
