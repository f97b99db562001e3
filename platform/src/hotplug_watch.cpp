#include "platform/hotplug_watch.hpp"

#include <systemd/sd-device.h>
#include <systemd/sd-event.h>

#include <cstdio>
#include <cstring>

namespace platform {

struct HotplugWatch::Monitor {
    sd_event* event = nullptr;
    sd_device_monitor* monitor = nullptr;
    bool listening = false;
    bool changed = false;
    char error[160] = "";

    ~Monitor()
    {
        if (monitor) {
            sd_device_monitor_stop(monitor);
            sd_device_monitor_unref(monitor);
        }
        if (event)
            sd_event_unref(event);
    }
    bool fail(const char* what, int r) noexcept
    {
        std::snprintf(error, sizeof error, "udev monitor: %s: %s", what, std::strerror(-r));
        return false;
    }
    bool start(const char* const* subsystems) noexcept
    {
        int r = sd_event_new(&event);
        if (r < 0)
            return fail("sd_event_new", r);
        r = sd_device_monitor_new(&monitor);
        if (r < 0)
            return fail("sd_device_monitor_new", r);
        for (const char* const* s = subsystems; s && *s; ++s)
            if ((r = sd_device_monitor_filter_add_match_subsystem_devtype(monitor, *s, nullptr)) <
                0)
                return fail("filter", r);
        if ((r = sd_device_monitor_attach_event(monitor, event)) < 0)
            return fail("attach", r);
        if ((r = sd_device_monitor_start(monitor, &Monitor::onEvent, this)) < 0)
            return fail("start", r);
        return true;
    }
    static int onEvent(sd_device_monitor*, sd_device*, void* self) noexcept
    {
        static_cast<Monitor*>(self)->changed = true;
        return 0;
    }
};

HotplugWatch::HotplugWatch(const char* const* subsystems) noexcept
{
    try {
        m_ = std::make_unique<Monitor>();
    } catch (...) {
        return;
    }
    m_->listening = m_->start(subsystems);
}

HotplugWatch::~HotplugWatch() = default;

bool HotplugWatch::listening() const noexcept
{
    return m_ && m_->listening;
}

bool HotplugWatch::changed() noexcept
{
    if (!listening())
        return false;
    // Dispatch whatever is queued without waiting; each event sets `changed`.
    while (sd_event_run(m_->event, 0) > 0) {
    }
    const bool changed = m_->changed;
    m_->changed = false;
    return changed;
}

const char* HotplugWatch::lastError() const noexcept
{
    return m_ ? m_->error : "udev monitor: out of memory";
}

}  // namespace platform
