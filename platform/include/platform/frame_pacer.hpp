#pragma once
// FramePacer: delivers frames at a steady rate against absolute CLOCK_MONOTONIC deadlines.

#include <cstdint>

namespace platform {

/// Where a FramePacer reads the time and how it sleeps. The default is CLOCK_MONOTONIC with an
/// absolute clock_nanosleep; tests inject a fake one so pacing is checked without real time.
class PacerClock {
public:
    virtual ~PacerClock() = default;
    PacerClock() = default;
    PacerClock(const PacerClock&) = delete;
    PacerClock& operator=(const PacerClock&) = delete;

    virtual std::int64_t nowNs() noexcept = 0;
    /// Returns at or after `deadlineNs` (immediately when it is already past).
    virtual void sleepUntilNs(std::int64_t deadlineNs) noexcept = 0;
};

/// The real clock: CLOCK_MONOTONIC, clock_nanosleep(TIMER_ABSTIME), restarted on EINTR.
PacerClock& monotonicPacerClock() noexcept;

/// The deadline arithmetic of FramePacer, without any clock: pure and testable.
///
/// Frame k after the anchor is due at anchor + k * period, computed from the anchor each time (not
/// by adding periods), so rounding never accumulates into drift. A frame that is late by less than
/// one period is delivered at once and the schedule is kept, so the following frames catch up. When
/// the caller is late by more than one period (a stall, a debugger, a slow decode), the schedule is
/// re-anchored at `now` instead of bursting out the missed frames back to back.
class PaceSchedule {
public:
    /// `fps` <= 0 or not finite: unpaced, every frame is due at once ("max").
    explicit PaceSchedule(double fps) noexcept;

    bool paced() const noexcept { return periodNs_ > 0.0; }
    double fps() const noexcept { return fps_; }
    double periodNs() const noexcept { return periodNs_; }

    /// Deadline of the next frame, given the time now. The caller sleeps until the returned time
    /// when it lies in the future, otherwise delivers at once. The first call anchors at `nowNs`.
    std::int64_t next(std::int64_t nowNs) noexcept;
    /// Forget the schedule: the next call anchors anew.
    void restart() noexcept { anchored_ = false; }
    /// How often the schedule was re-anchored because the caller was more than one period late.
    std::uint64_t reanchors() const noexcept { return reanchors_; }

private:
    double fps_ = 0.0;
    double periodNs_ = 0.0;  ///< 0 = unpaced
    bool anchored_ = false;
    std::int64_t anchorNs_ = 0;
    std::uint64_t framesSinceAnchor_ = 0;
    std::uint64_t reanchors_ = 0;
};

/// Paces a frame source: wait() returns when the next frame is due. noexcept, allocation-free.
///
/// With fps <= 0 ("max") wait() never sleeps and only reads the clock for the frame's timestamp.
class FramePacer {
public:
    explicit FramePacer(double fps, PacerClock& clock = monotonicPacerClock()) noexcept
        : schedule_(fps), clock_(&clock)
    {
    }

    /// Sleeps until the next frame is due; returns the clock's time after waking (the timestamp of
    /// the frame, CLOCK_MONOTONIC ns for the real clock).
    std::int64_t wait() noexcept;
    void restart() noexcept { schedule_.restart(); }

    bool paced() const noexcept { return schedule_.paced(); }
    double fps() const noexcept { return schedule_.fps(); }
    std::uint64_t reanchors() const noexcept { return schedule_.reanchors(); }
    /// How long the last wait() slept (0 when the frame was already due).
    std::int64_t lastSleepNs() const noexcept { return lastSleepNs_; }

private:
    PaceSchedule schedule_;
    PacerClock* clock_;
    std::int64_t lastSleepNs_ = 0;
};

}  // namespace platform
