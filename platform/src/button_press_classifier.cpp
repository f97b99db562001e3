#include "platform/button_press_classifier.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace platform {

ButtonPressClassifier::ButtonPressClassifier(int buttonCount, const ButtonPressOptions& options)
    : options_(options), count_(buttonCount)
{
    if (buttonCount < 1 || buttonCount > kMaxButtons)
        throw std::invalid_argument("buttons: " + std::to_string(buttonCount) +
                                    " buttons given, 1.." + std::to_string(kMaxButtons) +
                                    " supported");
    if (options.debounceNs < 0 || options.longPressNs < 0)
        throw std::invalid_argument("buttons: debounce and long-press times cannot be negative");
}

void ButtonPressClassifier::push(int button, ButtonEvent::Kind kind, std::int64_t timeNs) noexcept
{
    if (size_ == kQueueCapacity) {
        ++dropped_;
        return;
    }
    queue_[static_cast<std::size_t>((head_ + size_) % kQueueCapacity)] = {button, kind, timeNs};
    ++size_;
}

void ButtonPressClassifier::settle(Button& b, int button, std::int64_t nowNs) noexcept
{
    // A pending level that has lasted the debounce time is accepted, dated from its first edge.
    // Contacts of the usual tactile switches bounce for 1-10 ms; the default 30 ms filters that
    // and still feels instant.
    if (b.raw != b.stable && nowNs - b.rawSinceNs >= options_.debounceNs) {
        b.stable = b.raw;
        if (b.stable) {
            b.pressedAtNs = b.rawSinceNs;
            b.longFired = false;
        } else {
            const std::int64_t held = b.rawSinceNs - b.pressedAtNs;
            if (b.armed && !b.longFired) {
                // Long already when released, but no tick() saw the threshold pass.
                if (held >= options_.longPressNs)
                    push(button, ButtonEvent::Long, b.pressedAtNs + options_.longPressNs);
                else
                    push(button, ButtonEvent::Short, b.rawSinceNs);
            }
            b.armed = true;
        }
    }
    // Long press: held past the threshold. A release that is still being debounced stops it
    // only if it began before the threshold (if it is real, the press was short).
    if (b.stable && b.armed && !b.longFired) {
        const std::int64_t threshold = b.pressedAtNs + options_.longPressNs;
        if (nowNs >= threshold && (b.raw || b.rawSinceNs >= threshold)) {
            push(button, ButtonEvent::Long, threshold);
            b.longFired = true;
        }
    }
}

void ButtonPressClassifier::setLevel(int button, bool high, std::int64_t timeNs) noexcept
{
    if (button < 1 || button > count_) {
        ++ignored_;
        return;
    }
    Button& b = buttons_[static_cast<std::size_t>(button - 1)];
    const bool pressedNow = high != options_.activeLow;
    b = Button{};
    b.stable = b.raw = pressedNow;
    b.armed = !pressedNow;
    b.rawSinceNs = b.pressedAtNs = b.lastNs = timeNs;
}

void ButtonPressClassifier::feedEdge(const ButtonEdge& edge) noexcept
{
    if (edge.button < 1 || edge.button > count_) {
        ++ignored_;
        return;
    }
    Button& b = buttons_[static_cast<std::size_t>(edge.button - 1)];
    const std::int64_t t = std::max(edge.timeNs, b.lastNs);
    b.lastNs = t;
    settle(b, edge.button, t);  // whatever became stable before this edge counts first

    const bool pressedNow = edge.rising != options_.activeLow;
    if (pressedNow == b.stable) {
        // Back to the accepted level (a bounce), or a repeat of it (an edge missed in between).
        if (b.raw != b.stable)
            ++filtered_;
        b.raw = b.stable;
    } else {
        // Away from the accepted level: (re)start the stability timer.
        b.raw = pressedNow;
        b.rawSinceNs = t;
    }
    settle(b, edge.button, t);  // a zero debounce accepts the edge at once
}

void ButtonPressClassifier::tick(std::int64_t nowNs) noexcept
{
    for (int i = 0; i < count_; ++i) {
        Button& b = buttons_[static_cast<std::size_t>(i)];
        const std::int64_t t = std::max(nowNs, b.lastNs);
        b.lastNs = t;
        settle(b, i + 1, t);
    }
}

int ButtonPressClassifier::take(ButtonEvent* out, int capacity) noexcept
{
    const int n = std::min(std::max(capacity, 0), size_);
    for (int i = 0; i < n; ++i) {
        out[i] = queue_[static_cast<std::size_t>(head_)];
        head_ = (head_ + 1) % kQueueCapacity;
    }
    size_ -= n;
    return n;
}

int ButtonPressClassifier::process(std::span<const ButtonEdge> edges, std::int64_t nowNs,
                                   ButtonEvent* out, int capacity) noexcept
{
    for (const ButtonEdge& edge : edges)
        feedEdge(edge);
    tick(nowNs);
    return take(out, capacity);
}

bool ButtonPressClassifier::pressed(int button) const noexcept
{
    if (button < 1 || button > count_)
        return false;
    return buttons_[static_cast<std::size_t>(button - 1)].stable;
}

}  // namespace platform
