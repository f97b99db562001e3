#pragma once
// GpiodLines: the only code in the project that calls libgpiod. GpiodButtonInput uses nothing
// else, so moving to the libgpiod 2.x API replaces the implementation behind this interface and
// nothing more.
//
// gpiod_lines_v1.cpp implements it on libgpiod 1.x (Debian 12 ships 1.6.3) and compiles only
// when <gpiod.h> is the 1.x header (it defines GPIOD_LINE_BULK_MAX_LINES; 2.x does not, and has
// no version macro). A 2.x port is a gpiod_lines_v2.cpp compiled in the opposite case:
//  - open: 2.x has only gpiod_chip_open(path); map "gpiochipN" and "N" to /dev/gpiochipN and
//    find a label by gpiod_chip_get_info() + gpiod_chip_info_get_label() over the /dev entries
//    that gpiod_is_gpiochip_device() accepts; line count from gpiod_chip_info_get_num_lines();
//    on EBUSY the holder from gpiod_chip_get_line_info() + gpiod_line_info_get_consumer();
//  - request: gpiod_line_settings_new() with set_direction(INPUT), set_edge_detection(BOTH),
//    set_bias(PULL_UP/PULL_DOWN/DISABLED/AS_IS), set_event_clock(MONOTONIC) and no active-low;
//    gpiod_line_config_add_line_settings(offsets); gpiod_request_config_set_consumer();
//    gpiod_chip_request_lines() gives one request with one fd (fdCount() == 1);
//  - readEdges: a gpiod_edge_event_buffer allocated in the constructor;
//    gpiod_line_request_read_edge_events() only after gpiod_line_request_wait_edge_events(req, 0)
//    said events wait (it blocks otherwise); per event get_line_offset (-> button), get_event_type
//    (GPIOD_EDGE_EVENT_RISING_EDGE), get_timestamp_ns;
//  - readLevel: gpiod_line_request_get_value() (ACTIVE = high, as no active-low is set).

#include "platform/button_press_classifier.hpp"
#include "platform/gpiod_button_input.hpp"

#include <memory>
#include <span>
#include <string>

namespace platform::detail {

class GpiodLines {
public:
    /// Opens `chip` and requests `offsets` as inputs with edge events on both edges and `bias`.
    /// Throws std::runtime_error with one line ("gpio: CHIP ...: why") on any failure.
    GpiodLines(const std::string& chip, std::span<const unsigned> offsets, GpioBias bias,
               const std::string& consumer);
    ~GpiodLines();
    GpiodLines(const GpiodLines&) = delete;
    GpiodLines& operator=(const GpiodLines&) = delete;

    /// The chip's name as the kernel knows it, e.g. "gpiochip0".
    const std::string& chipName() const noexcept { return chipName_; }
    int lineCount() const noexcept { return count_; }
    /// Descriptors that become readable when events wait (1.x: one per line).
    int fdCount() const noexcept;
    int fd(int index) const noexcept;
    /// Reads the waiting edges of every line without blocking, at most `capacity`; button n is
    /// the n-th offset. Returns how many, or -1 with errno set.
    int readEdges(ButtonEdge* out, int capacity) noexcept;
    /// The physical level of line `index` (0-based): 1 high, 0 low, -1 with errno set.
    int readLevel(int index) noexcept;

private:
    struct Handles;
    std::unique_ptr<Handles> handles_;  // the library's objects; they depend on the API version
    std::string chipName_;
    int count_ = 0;
};

}  // namespace platform::detail
