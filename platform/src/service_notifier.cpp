#include "platform/service_notifier.hpp"

#include <systemd/sd-daemon.h>
#include <time.h>

#include <cstdio>
#include <cstdlib>

namespace platform {

ServiceNotifier::ServiceNotifier() noexcept
{
    const char* socket = std::getenv("NOTIFY_SOCKET");
    underSystemd_ = socket != nullptr && socket[0] != '\0';
    // > 0 only when WATCHDOG_USEC is set and WATCHDOG_PID (if set) is this process.
    uint64_t usec = 0;
    if (underSystemd_ && sd_watchdog_enabled(0, &usec) > 0)
        watchdogUsec_ = usec;
}

void ServiceNotifier::send(const char* message) noexcept
{
    if (!underSystemd_)
        return;
    if (sd_notify(0, message) <= 0)
        ++failures_;
}

void ServiceNotifier::ready(const char* status) noexcept
{
    if (readySent_ || !underSystemd_)
        return;
    readySent_ = true;
    std::snprintf(message_, sizeof message_, "READY=1\nSTATUS=%.200s", status ? status : "");
    send(message_);
}

void ServiceNotifier::status(const char* text) noexcept
{
    if (!underSystemd_)
        return;
    std::snprintf(message_, sizeof message_, "STATUS=%.200s", text ? text : "");
    send(message_);
}

bool ServiceNotifier::pingWatchdog(std::int64_t monotonicNs) noexcept
{
    if (watchdogUsec_ == 0)
        return false;
    const auto halfIntervalNs = static_cast<std::int64_t>(watchdogUsec_) * 500;
    if (pinged_ && monotonicNs - lastPingNs_ < halfIntervalNs)
        return false;
    pinged_ = true;
    lastPingNs_ = monotonicNs;
    send("WATCHDOG=1");
    return true;
}

bool ServiceNotifier::pingWatchdog() noexcept
{
    if (watchdogUsec_ == 0)
        return false;
    timespec now{};
    ::clock_gettime(CLOCK_MONOTONIC, &now);
    return pingWatchdog(static_cast<std::int64_t>(now.tv_sec) * 1000000000 + now.tv_nsec);
}

void ServiceNotifier::stopping() noexcept
{
    send("STOPPING=1");
}

}  // namespace platform
