// GpiodLines on the libgpiod 1.x API (Debian 12: 1.6.3). See gpiod_lines.hpp for the 2.x notes.

#include "gpiod_lines.hpp"

#include <gpiod.h>

#if defined(GPIOD_LINE_BULK_MAX_LINES)  // only the 1.x header has the bulk API

#include <fcntl.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace platform::detail {

namespace {

std::string errorText(int error)
{
    return std::strerror(error);
}

int requestFlags(GpioBias bias)
{
    switch (bias) {
        case GpioBias::AsIs:
            return 0;
        case GpioBias::Disable:
            return GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
        case GpioBias::PullUp:
            return GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
        case GpioBias::PullDown:
            return GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
    }
    return 0;
}

std::string offsetList(std::span<const unsigned> offsets)
{
    std::string text;
    for (unsigned offset : offsets) {
        if (!text.empty())
            text += ',';
        text += std::to_string(offset);
    }
    return text;
}

}  // namespace

struct GpiodLines::Handles {
    gpiod_chip* chip = nullptr;
    gpiod_line_bulk bulk = GPIOD_LINE_BULK_INITIALIZER;
    bool requested = false;
    std::vector<int> fds;  // one event fd per line, in button order

    ~Handles()
    {
        if (requested)
            gpiod_line_release_bulk(&bulk);
        if (chip)
            gpiod_chip_close(chip);
    }
};

GpiodLines::GpiodLines(const std::string& chip, std::span<const unsigned> offsets, GpioBias bias,
                       const std::string& consumer)
    : handles_(std::make_unique<Handles>()), count_(static_cast<int>(offsets.size()))
{
    const std::string where = "gpio: chip '" + chip + "'";
    if (offsets.empty() || offsets.size() > GPIOD_LINE_BULK_MAX_LINES)
        throw std::runtime_error(where + ": " + std::to_string(offsets.size()) +
                                 " lines given, 1.." + std::to_string(GPIOD_LINE_BULK_MAX_LINES) +
                                 " supported");
    // `chip` is a name ("gpiochip0"), a number ("0"), a label ("pinctrl-bcm2711") or a path
    // ("/dev/gpiochip0").
    errno = 0;
    handles_->chip = gpiod_chip_open_lookup(chip.c_str());
    if (!handles_->chip) {
        // open_lookup tries path, name, label and number in turn; errno is from the last try.
        const int error = errno != 0 ? errno : ENOENT;
        const std::string why = error == ENOTTY || error == ENODEV
                                    ? std::string("not a GPIO character device")
                                    : errorText(error);
        throw std::runtime_error(where +
                                 ": cannot open (tried as path, name, label, number): " + why);
    }
    chipName_ = gpiod_chip_name(handles_->chip);
    const unsigned lineTotal = gpiod_chip_num_lines(handles_->chip);
    for (unsigned offset : offsets) {
        if (offset >= lineTotal)
            throw std::runtime_error("gpio: " + chipName_ + " has lines 0.." +
                                     std::to_string(lineTotal - 1) + ", no line " +
                                     std::to_string(offset));
    }
    for (std::size_t i = 0; i < offsets.size(); ++i) {
        for (std::size_t j = 0; j < i; ++j) {
            if (offsets[i] == offsets[j])
                throw std::runtime_error("gpio: " + chipName_ + ": line " +
                                         std::to_string(offsets[i]) + " is given twice");
        }
    }
    if (gpiod_chip_get_lines(handles_->chip, const_cast<unsigned*>(offsets.data()),
                             static_cast<unsigned>(offsets.size()), &handles_->bulk) != 0)
        throw std::runtime_error("gpio: " + chipName_ + " lines " + offsetList(offsets) + ": " +
                                 errorText(errno));

    if (gpiod_line_request_bulk_both_edges_events_flags(&handles_->bulk, consumer.c_str(),
                                                        requestFlags(bias)) != 0) {
        const int error = errno;
        std::string why = errorText(error);
        if (error == EBUSY) {
            // Name who holds them, the first thing a technician needs to know.
            for (unsigned i = 0; i < handles_->bulk.num_lines; ++i) {
                gpiod_line* line = handles_->bulk.lines[i];
                gpiod_line_update(line);
                if (gpiod_line_is_used(line)) {
                    const char* user = gpiod_line_consumer(line);
                    why += " (line " + std::to_string(gpiod_line_offset(line)) + " is used by '" +
                           std::string(user ? user : "the kernel") + "')";
                    break;
                }
            }
        } else if (error == EINVAL && bias != GpioBias::AsIs) {
            why += " (bias needs Linux 5.5 or later; try bias = \"as-is\")";
        }
        throw std::runtime_error("gpio: " + chipName_ + " lines " + offsetList(offsets) +
                                 ": cannot request edge events: " + why);
    }
    handles_->requested = true;

    for (unsigned i = 0; i < handles_->bulk.num_lines; ++i) {
        const int fd = gpiod_line_event_get_fd(handles_->bulk.lines[i]);
        // The fd is ours (the line request); non-blocking so a read never stalls the frame loop.
        const int flags = fd >= 0 ? ::fcntl(fd, F_GETFL) : -1;
        if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0)
            throw std::runtime_error("gpio: " + chipName_ + " line " + std::to_string(offsets[i]) +
                                     ": event descriptor: " + errorText(errno));
        handles_->fds.push_back(fd);
    }
}

GpiodLines::~GpiodLines() = default;

int GpiodLines::fdCount() const noexcept
{
    return static_cast<int>(handles_->fds.size());
}

int GpiodLines::fd(int index) const noexcept
{
    return index >= 0 && index < fdCount() ? handles_->fds[static_cast<std::size_t>(index)] : -1;
}

int GpiodLines::readEdges(ButtonEdge* out, int capacity) noexcept
{
    constexpr unsigned kBatch = 16;
    gpiod_line_event events[kBatch];
    int n = 0;
    for (int line = 0; line < count_ && n < capacity; ++line) {
        const int fd = handles_->fds[static_cast<std::size_t>(line)];
        while (n < capacity) {
            const unsigned want = static_cast<unsigned>(std::min<int>(kBatch, capacity - n));
            const int got = gpiod_line_event_read_fd_multiple(fd, events, want);
            if (got < 0) {
                if (errno == EINTR)
                    continue;
                if (errno == EAGAIN || errno == EWOULDBLOCK)
                    break;  // nothing (more) waiting on this line
                return -1;
            }
            for (int i = 0; i < got; ++i) {
                const timespec& ts = events[i].ts;
                out[n++] = {line + 1, events[i].event_type == GPIOD_LINE_EVENT_RISING_EDGE,
                            static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec};
            }
            if (static_cast<unsigned>(got) < want)
                break;
        }
    }
    return n;
}

int GpiodLines::readLevel(int index) noexcept
{
    if (index < 0 || index >= count_) {
        errno = EINVAL;
        return -1;
    }
    return gpiod_line_get_value(handles_->bulk.lines[index]);
}

}  // namespace platform::detail

#else
#error "libgpiod 2.x: add gpiod_lines_v2.cpp implementing gpiod_lines.hpp (notes in that header)"
#endif
