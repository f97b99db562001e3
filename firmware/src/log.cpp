#include "firmware/log.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <mutex>

namespace firmware {

namespace {

std::atomic<LogLevel> gLevel{LogLevel::Info};
std::atomic<int> gFd{2};

double monotonicSeconds() noexcept
{
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

const double gStart = monotonicSeconds();

// The in-memory ring of recent lines (static storage: nothing allocated).
constexpr std::size_t kRingLineBytes = 512;
struct LogRing {
    std::mutex mutex;
    char lines[kLogRingLines][kRingLineBytes] = {};
    int next = 0;   // slot of the next line
    int count = 0;  // lines kept (<= kLogRingLines)
};
LogRing gRing;

void keep(const char* line, std::size_t n) noexcept
{
    const std::lock_guard<std::mutex> lock(gRing.mutex);
    char* slot = gRing.lines[gRing.next];
    const std::size_t m = std::min(n, kRingLineBytes - 1);
    std::memcpy(slot, line, m);
    slot[m] = '\0';
    gRing.next = (gRing.next + 1) % kLogRingLines;
    gRing.count = std::min(gRing.count + 1, kLogRingLines);
}

char levelLetter(LogLevel l) noexcept
{
    switch (l) {
        case LogLevel::Error:
            return 'E';
        case LogLevel::Warn:
            return 'W';
        case LogLevel::Info:
            return 'I';
        case LogLevel::Debug:
            return 'D';
    }
    return '?';
}

}  // namespace

void setLogLevel(LogLevel level) noexcept
{
    gLevel = level;
}
LogLevel logLevel() noexcept
{
    return gLevel;
}
void setLogFd(int fd) noexcept
{
    gFd = fd;
}
double uptimeSeconds() noexcept
{
    return monotonicSeconds() - gStart;
}

void logf(LogLevel level, const char* format, ...) noexcept
{
    if (static_cast<int>(level) > static_cast<int>(gLevel.load()))
        return;
    char line[512];
    int n = std::snprintf(line, sizeof line, "[%10.3f] %c ", uptimeSeconds(), levelLetter(level));
    va_list args;
    va_start(args, format);
    const int m = std::vsnprintf(line + n, sizeof line - static_cast<std::size_t>(n), format, args);
    va_end(args);
    n = m < 0 ? n : std::min<int>(n + m, static_cast<int>(sizeof line) - 2);
    line[n++] = '\n';
    keep(line, static_cast<std::size_t>(n));
    // One write per line so lines from the loop and the console never interleave mid-line.
    [[maybe_unused]] const ssize_t w = ::write(gFd, line, static_cast<std::size_t>(n));
}

int forEachRecentLogLine(int maxLines, void (*emit)(const char* line, void* context),
                         void* context) noexcept
{
    const std::lock_guard<std::mutex> lock(gRing.mutex);
    const int n = std::clamp(maxLines, 0, gRing.count);
    for (int i = 0; i < n; ++i) {
        const int slot = (gRing.next - n + i + kLogRingLines) % kLogRingLines;
        emit(gRing.lines[slot], context);
    }
    return n;
}

}  // namespace firmware
