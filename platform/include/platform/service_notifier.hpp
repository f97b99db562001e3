#pragma once
// ServiceNotifier: tells systemd the mirror's state (ready, alive, status) when run as a service.

#include <cstdint>

namespace platform {

/// The sd_notify(3) protocol of a Type=notify unit, through libsystemd.
///
/// Under systemd (NOTIFY_SOCKET set) it sends READY=1 once the first frame is shown, STATUS=...
/// lines, and WATCHDOG=1 keep-alives when the unit has WatchdogSec= (WATCHDOG_USEC, read once at
/// construction with sd_watchdog_enabled). Anywhere else every call is a cheap no-op.
///
/// pingWatchdog() is meant to be called once per frame: it sends at most one keep-alive per half
/// watchdog interval (what sd_watchdog_enabled(3) recommends), so a loop that stalls for longer
/// than WatchdogSec is killed and restarted by systemd while a running one costs one clock
/// comparison per frame. No call allocates; messages are formatted into a fixed buffer.
class ServiceNotifier {
public:
    /// Reads the environment systemd sets; never throws.
    ServiceNotifier() noexcept;

    /// True when started by systemd with a notification socket.
    bool underSystemd() const noexcept { return underSystemd_; }
    /// The unit's watchdog interval in microseconds; 0 when the watchdog is off.
    std::uint64_t watchdogUsec() const noexcept { return watchdogUsec_; }

    /// READY=1 (once; later calls do nothing) with a status line.
    void ready(const char* status) noexcept;
    /// STATUS=text (one line, shown by `systemctl status`; cut at 200 characters).
    void status(const char* text) noexcept;
    /// WATCHDOG=1 when half the interval has passed since the last one. `monotonicNs` is
    /// CLOCK_MONOTONIC in nanoseconds. True when a keep-alive was sent.
    bool pingWatchdog(std::int64_t monotonicNs) noexcept;
    /// The same with the current CLOCK_MONOTONIC time.
    bool pingWatchdog() noexcept;
    /// STOPPING=1, before a clean exit.
    void stopping() noexcept;

    /// Messages that could not be sent (the socket went away); for the status command.
    unsigned failures() const noexcept { return failures_; }

private:
    void send(const char* message) noexcept;

    bool underSystemd_ = false;
    bool readySent_ = false;
    std::uint64_t watchdogUsec_ = 0;
    std::int64_t lastPingNs_ = 0;
    bool pinged_ = false;
    unsigned failures_ = 0;
    char message_[224] = "";
};

}  // namespace platform
