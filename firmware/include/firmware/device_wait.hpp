#pragma once
// DeviceWait: an appliance started without its camera or its panel ("auto" found none) keeps
// looking for them while it shows the calm screen, and says when one came, so the loop rebuilds
// its pipeline on it. It looks when udev announces a camera or DRM device (after a short settle,
// for the device's other nodes to appear), and at a slow pace in any case (no udev, or an event
// missed).

#include "platform/hotplug_watch.hpp"

#include <cstdint>
#include <functional>
#include <memory>

namespace firmware {

/// How to tell that a device is there now (the factory's own tests, or fakes in tests).
struct DeviceProbes {
    std::function<bool()> camera;  ///< a camera "auto" would open is there
    std::function<bool()> panel;   ///< a connected panel "auto" would use is there
};

struct DeviceWaitOptions {
    std::int64_t settleNs = 1'000'000'000;      ///< after a udev event, before looking
    std::int64_t slowCheckNs = 10'000'000'000;  ///< look this often anyway
};

class DeviceWait {
public:
    /// Waits for a camera when `camera`, for a panel when `panel`. `watch` may be null.
    DeviceWait(bool camera, bool panel, DeviceProbes probes,
               std::unique_ptr<platform::HotplugWatch> watch, DeviceWaitOptions options = {});

    /// Once per frame: true when an awaited device is there now (found() says which). Looks only
    /// when an event settled or the slow check is due; then it may allocate and take a while
    /// (libcamera enumerates its cameras), otherwise it costs a clock comparison.
    bool poll(std::int64_t nowNs) noexcept;
    /// "camera", "panel", or "camera and panel": what is awaited.
    const char* awaited() const noexcept;
    /// What poll() found: "camera" or "panel" ("" before).
    const char* found() const noexcept { return found_; }

private:
    bool look() noexcept;

    bool camera_;
    bool panel_;
    DeviceProbes probes_;
    std::unique_ptr<platform::HotplugWatch> watch_;
    DeviceWaitOptions options_;
    std::int64_t nextCheckNs_ = 0;
    const char* found_ = "";
};

}  // namespace firmware
