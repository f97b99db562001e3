#pragma once
// The loop's clock: CLOCK_MONOTONIC in nanoseconds (what sources, the log and systemd use).

#include <cstdint>
#include <ctime>

namespace firmware {

inline std::int64_t monotonicNs() noexcept
{
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

}  // namespace firmware
