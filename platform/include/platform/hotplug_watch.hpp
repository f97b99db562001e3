#pragma once
// HotplugWatch: udev's device events (added, removed, changed) for a few subsystems, so the mirror
// can look again for a camera ("video4linux") or a panel ("drm": a connector plugged in or a TV
// switched on) the moment one comes, instead of scanning the devices over and over.

#include <memory>

namespace platform {

/// \class HotplugWatch
/// Listens to udev's netlink events (libsystemd's sd_device_monitor) for the given subsystems.
/// The constructor never throws: where it cannot listen (no netlink, a sandbox) listening() is
/// false and lastError() says why; the caller then checks at a slow pace instead. changed()
/// never blocks. The events are udev's, sent after its rules ran, so a device announced here
/// already has the permissions the mirror's groups need.
class HotplugWatch {
public:
    /// `subsystems`: null-terminated list, e.g. {"video4linux", "drm", nullptr}.
    explicit HotplugWatch(const char* const* subsystems) noexcept;
    ~HotplugWatch();
    HotplugWatch(const HotplugWatch&) = delete;
    HotplugWatch& operator=(const HotplugWatch&) = delete;

    bool listening() const noexcept;
    /// Takes every event that arrived since the last call; true when there was one.
    bool changed() noexcept;
    const char* lastError() const noexcept;

private:
    struct Monitor;
    std::unique_ptr<Monitor> m_;
};

}  // namespace platform
