#include "firmware/device_wait.hpp"

#include <algorithm>

namespace firmware {

DeviceWait::DeviceWait(bool camera, bool panel, DeviceProbes probes,
                       std::unique_ptr<platform::HotplugWatch> watch, DeviceWaitOptions options)
    : camera_(camera),
      panel_(panel),
      probes_(std::move(probes)),
      watch_(std::move(watch)),
      options_(options)
{
}

bool DeviceWait::poll(std::int64_t nowNs) noexcept
{
    if (nextCheckNs_ == 0)
        nextCheckNs_ = nowNs + options_.slowCheckNs;
    if (watch_ && watch_->changed())
        nextCheckNs_ = std::min(nextCheckNs_, nowNs + options_.settleNs);
    if (nowNs < nextCheckNs_)
        return false;
    nextCheckNs_ = nowNs + options_.slowCheckNs;
    return look();
}

bool DeviceWait::look() noexcept
{
    try {
        if (camera_ && probes_.camera && probes_.camera()) {
            found_ = "camera";
            return true;
        }
        if (panel_ && probes_.panel && probes_.panel()) {
            found_ = "panel";
            return true;
        }
    } catch (...) {
        // A probe that failed found nothing; the next check tries again.
    }
    return false;
}

const char* DeviceWait::awaited() const noexcept
{
    return camera_ && panel_ ? "camera and panel" : camera_ ? "camera" : panel_ ? "panel" : "";
}

}  // namespace firmware
