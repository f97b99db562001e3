#include "platform/gpiod_button_input.hpp"

#include "gpiod_lines.hpp"

#include <sys/epoll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <span>
#include <stdexcept>

namespace platform {

namespace {

std::int64_t clockNowNs(clockid_t clock) noexcept
{
    timespec ts{};
    ::clock_gettime(clock, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::int64_t monotonicNowNs() noexcept
{
    return clockNowNs(CLOCK_MONOTONIC);
}

std::int64_t distanceNs(std::int64_t a, std::int64_t b) noexcept
{
    return a > b ? a - b : b - a;
}

}  // namespace

std::int64_t edgeStampToMonotonicNs(std::int64_t stampNs, std::int64_t monotonicNowNs,
                                    std::int64_t realtimeNowNs) noexcept
{
    // Which clock stamped it is told by which it is nearer: the two are decades apart on a
    // machine with a set clock, and where they are not (a board that booted at the epoch) the
    // offset is as small as the choice is unsure. The stamp is moved, never replaced by the time
    // it was read: a press read late (a frame loop stalled for seconds) keeps its length, where
    // dating both edges "now" would make it a zero-length bounce and lose it.
    std::int64_t t = stampNs;
    if (distanceNs(stampNs, realtimeNowNs) < distanceNs(stampNs, monotonicNowNs))
        t = stampNs - (realtimeNowNs - monotonicNowNs);
    return std::min(t, monotonicNowNs);
}

bool parseGpioBias(const std::string& text, GpioBias& out) noexcept
{
    static constexpr GpioBias kAll[] = {GpioBias::AsIs, GpioBias::Disable, GpioBias::PullUp,
                                        GpioBias::PullDown};
    for (GpioBias bias : kAll) {
        if (text == toString(bias)) {
            out = bias;
            return true;
        }
    }
    return false;
}

const char* toString(GpioBias bias) noexcept
{
    switch (bias) {
        case GpioBias::AsIs:
            return "as-is";
        case GpioBias::Disable:
            return "disable";
        case GpioBias::PullUp:
            return "pull-up";
        case GpioBias::PullDown:
            return "pull-down";
    }
    return "?";
}

namespace {

/// The number of buttons, checked before the classifier sees it (it would throw
/// std::invalid_argument; this constructor promises std::runtime_error).
int buttonCountOf(const GpiodButtonOptions& options)
{
    const std::size_t n = options.lines.size();
    if (n < 1 || n > static_cast<std::size_t>(ButtonPressClassifier::kMaxButtons))
        throw std::runtime_error("gpio: " + std::to_string(n) + " buttons given (lines), 1.." +
                                 std::to_string(ButtonPressClassifier::kMaxButtons) + " supported");
    if (options.press.debounceNs < 0 || options.press.longPressNs < 0)
        throw std::runtime_error("gpio: debounce and long-press times cannot be negative");
    return static_cast<int>(n);
}

}  // namespace

GpiodButtonInput::GpiodButtonInput(const GpiodButtonOptions& options)
    // The classifier first: a bad button count is refused before any line is requested.
    : classifier_(buttonCountOf(options), options.press)
{
    lines_ = std::make_unique<detail::GpiodLines>(options.chip, options.lines, options.bias,
                                                  options.consumer);

    epollFd_ = ::epoll_create1(EPOLL_CLOEXEC);
    if (epollFd_ < 0)
        throw std::runtime_error(std::string("gpio: epoll: ") + std::strerror(errno));
    for (int i = 0; i < lines_->fdCount(); ++i) {
        epoll_event ev{};
        ev.events = EPOLLIN;
        ev.data.u32 = static_cast<std::uint32_t>(i);
        if (::epoll_ctl(epollFd_, EPOLL_CTL_ADD, lines_->fd(i), &ev) != 0) {
            const int error = errno;
            ::close(epollFd_);
            throw std::runtime_error("gpio: " + lines_->chipName() +
                                     ": epoll: " + std::strerror(error));
        }
    }

    // Start from the levels as they are, so a button held at start-up (or stuck) is ignored
    // until released instead of firing at once.
    const std::int64_t now = monotonicNowNs();
    for (int i = 0; i < lines_->lineCount(); ++i) {
        const int level = lines_->readLevel(i);
        if (level < 0) {
            const int error = errno;
            ::close(epollFd_);
            throw std::runtime_error("gpio: " + lines_->chipName() + " line " +
                                     std::to_string(options.lines[static_cast<std::size_t>(i)]) +
                                     ": cannot read: " + std::strerror(error));
        }
        classifier_.setLevel(i + 1, level == 1, now);
    }

    int n = std::snprintf(description_, sizeof description_, "gpio:%s lines ",
                          lines_->chipName().c_str());
    for (std::size_t i = 0;
         i < options.lines.size() && n > 0 && static_cast<std::size_t>(n) < sizeof description_;
         ++i)
        n += std::snprintf(description_ + n, sizeof description_ - static_cast<std::size_t>(n),
                           "%s%u", i ? "," : "", options.lines[i]);
    if (n > 0 && static_cast<std::size_t>(n) < sizeof description_)
        std::snprintf(description_ + n, sizeof description_ - static_cast<std::size_t>(n),
                      " (%s, %s)", options.press.activeLow ? "active low" : "active high",
                      toString(options.bias));
}

GpiodButtonInput::~GpiodButtonInput()
{
    if (epollFd_ >= 0)
        ::close(epollFd_);
}

int GpiodButtonInput::poll(ButtonEvent* out, int capacity) noexcept
{
    if (failed_)
        return -1;
    // One syscall per frame when no button moved (the usual case), instead of a read per line.
    epoll_event ready[1];
    int waiting;
    do {
        waiting = ::epoll_wait(epollFd_, ready, 1, 0);
    } while (waiting < 0 && errno == EINTR);
    const int n =
        waiting == 0 ? 0 : lines_->readEdges(edges_.data(), static_cast<int>(edges_.size()));
    if (n < 0) {
        std::snprintf(error_, sizeof error_, "gpio: %s: reading events: %s",
                      lines_->chipName().c_str(), std::strerror(errno));
        failed_ = true;
        return -1;
    }
    const std::int64_t now = monotonicNowNs();
    const std::int64_t wallNow = n > 0 ? clockNowNs(CLOCK_REALTIME) : 0;
    for (int i = 0; i < n; ++i) {
        std::int64_t& t = edges_[static_cast<std::size_t>(i)].timeNs;
        t = edgeStampToMonotonicNs(t, now, wallNow);
    }
    return classifier_.process(
        std::span<const ButtonEdge>(edges_.data(), static_cast<std::size_t>(n)), now, out,
        capacity);
}

int GpiodButtonInput::readPressed(bool* out, int capacity) noexcept
{
    const int count = std::min(capacity, lines_->lineCount());
    for (int i = 0; i < count; ++i) {
        const int level = lines_->readLevel(i);
        if (level < 0) {
            std::snprintf(error_, sizeof error_, "gpio: %s: reading button %d: %s",
                          lines_->chipName().c_str(), i + 1, std::strerror(errno));
            return -1;
        }
        out[i] = (level == 1) != classifier_.options().activeLow;
    }
    return count;
}

}  // namespace platform
