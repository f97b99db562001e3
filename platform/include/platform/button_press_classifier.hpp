#pragma once
// ButtonPressClassifier: raw, bouncing edges of button lines in, debounced short and long presses
// out. Pure logic on timestamps: the libgpiod input and the tests feed it the same way.

#include "platform/button_input.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace platform {

struct ButtonPressOptions {
    std::int64_t debounceNs = 30'000'000;    ///< a level counts once it lasts this long unchanged
    std::int64_t longPressNs = 800'000'000;  ///< held this long: a long press, reported at once
    bool activeLow = true;  ///< pressed reads low (a switch to ground with a pull-up, the usual)
};

/// One raw edge of one line, as the GPIO driver reports it: the physical level after the edge
/// (rising: the line reads high now). Bounce may deliver several edges in a row, even two in the
/// same direction when the driver missed one in between.
struct ButtonEdge {
    int button = 0;  ///< 1-based, like ButtonEvent::button
    bool rising = false;
    std::int64_t timeNs = 0;  ///< same clock as tick()
};

/// Debounces and classifies the edges of up to kMaxButtons buttons.
///
/// Debounce is by stability: a new level is accepted once it has lasted `debounceNs` with no
/// further edge, and dated from its first moment (the edge that began the stable run), so the
/// press and release times, and thus short versus long, do not depend on how often tick() runs.
/// A bounce back to the accepted level within `debounceNs` is dropped (counted in
/// filteredEdges()). A noise spike shorter than `debounceNs` never becomes a press.
///
/// Presses: a button accepted as pressed and then released before `longPressNs` is a Short press
/// (dated at the release); one held for `longPressNs` is a Long press, fired by tick() or the next
/// edge as soon as the threshold has passed while still held (dated at the threshold), and its
/// release then reports nothing. A button that is already pressed when its level is first set
/// (setLevel(), e.g. held at start-up or stuck) reports nothing until it has been released.
///
/// Events wait in a fixed queue (kQueueCapacity) until take(); when it is full, newer events are
/// dropped and counted. Nothing allocates; every call is noexcept.
class ButtonPressClassifier {
public:
    static constexpr int kMaxButtons = 16;
    static constexpr int kQueueCapacity = 32;

    /// Throws std::invalid_argument for a count outside 1..kMaxButtons or negative times.
    ButtonPressClassifier(int buttonCount, const ButtonPressOptions& options);

    int buttonCount() const noexcept { return count_; }
    const ButtonPressOptions& options() const noexcept { return options_; }

    /// The physical level of a button as read at `timeNs` (start-up), accepted without debounce.
    void setLevel(int button, bool high, std::int64_t timeNs) noexcept;
    /// One raw edge. Edges of one button must come in time order (an earlier time is taken as
    /// the last one seen); edges of an unknown button are ignored and counted.
    void feedEdge(const ButtonEdge& edge) noexcept;
    /// Lets time pass with no edge: accepts levels that have become stable and fires long
    /// presses whose threshold has passed. `nowNs` on the clock of the edges.
    void tick(std::int64_t nowNs) noexcept;
    /// Moves up to `capacity` queued events to `out` in the order they were recognised (in time
    /// order for each button); returns how many.
    int take(ButtonEvent* out, int capacity) noexcept;
    /// feedEdge() for each edge, tick(nowNs), take(): what an input does once per poll.
    int process(std::span<const ButtonEdge> edges, std::int64_t nowNs, ButtonEvent* out,
                int capacity) noexcept;

    /// The debounced state of a button (false for an unknown one).
    bool pressed(int button) const noexcept;
    /// Edges that bounced back before their level was accepted.
    long filteredEdges() const noexcept { return filtered_; }
    /// Edges for a button number outside 1..buttonCount().
    long ignoredEdges() const noexcept { return ignored_; }
    /// Events lost because the queue was full.
    long droppedEvents() const noexcept { return dropped_; }

private:
    struct Button {
        bool stable = false;  ///< accepted (debounced) level: pressed
        bool raw = false;     ///< level after the last edge: pressed
        bool armed = true;    ///< false while a button held since setLevel() waits for release
        bool longFired = false;
        std::int64_t rawSinceNs = 0;   ///< time of the edge that set `raw`
        std::int64_t pressedAtNs = 0;  ///< start of the accepted press
        std::int64_t lastNs = 0;       ///< latest time seen for this button
    };

    void settle(Button& b, int button, std::int64_t nowNs) noexcept;
    void push(int button, ButtonEvent::Kind kind, std::int64_t timeNs) noexcept;

    ButtonPressOptions options_;
    int count_ = 0;
    std::array<Button, kMaxButtons> buttons_{};
    std::array<ButtonEvent, kQueueCapacity> queue_{};
    int head_ = 0;
    int size_ = 0;
    long filtered_ = 0;
    long ignored_ = 0;
    long dropped_ = 0;
};

}  // namespace platform
