#include "platform/frame_pacer.hpp"

#include <cerrno>
#include <cmath>
#include <ctime>

namespace platform {

namespace {

constexpr std::int64_t kNsPerSecond = 1'000'000'000;

class MonotonicPacerClock final : public PacerClock {
public:
    std::int64_t nowNs() noexcept override
    {
        timespec ts{};
        clock_gettime(CLOCK_MONOTONIC, &ts);
        return static_cast<std::int64_t>(ts.tv_sec) * kNsPerSecond + ts.tv_nsec;
    }

    void sleepUntilNs(std::int64_t deadlineNs) noexcept override
    {
        timespec ts{};
        ts.tv_sec = static_cast<time_t>(deadlineNs / kNsPerSecond);
        ts.tv_nsec = static_cast<long>(deadlineNs % kNsPerSecond);
        // Absolute deadline: a signal only shortens one call, the retry sleeps to the same time.
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
        }
    }
};

}  // namespace

PacerClock& monotonicPacerClock() noexcept
{
    static MonotonicPacerClock clock;
    return clock;
}

PaceSchedule::PaceSchedule(double fps) noexcept
{
    if (std::isfinite(fps) && fps > 0.0) {
        fps_ = fps;
        periodNs_ = 1e9 / fps;
    }
}

std::int64_t PaceSchedule::next(std::int64_t nowNs) noexcept
{
    if (!paced())
        return nowNs;
    if (!anchored_) {
        anchored_ = true;
        anchorNs_ = nowNs;
        framesSinceAnchor_ = 0;
        return nowNs;
    }
    ++framesSinceAnchor_;
    const auto offset = static_cast<std::int64_t>(
        std::llround(static_cast<double>(framesSinceAnchor_) * periodNs_));
    const std::int64_t deadline = anchorNs_ + offset;
    if (static_cast<double>(nowNs - deadline) > periodNs_) {
        ++reanchors_;
        anchorNs_ = nowNs;
        framesSinceAnchor_ = 0;
        return nowNs;
    }
    return deadline;
}

std::int64_t FramePacer::wait() noexcept
{
    const std::int64_t now = clock_->nowNs();
    lastSleepNs_ = 0;
    if (!schedule_.paced())
        return now;
    const std::int64_t deadline = schedule_.next(now);
    if (deadline <= now)
        return now;
    clock_->sleepUntilNs(deadline);
    const std::int64_t woke = clock_->nowNs();
    lastSleepNs_ = woke - now;
    return woke;
}

}  // namespace platform
