#include "firmware/log.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <mutex>

namespace firmware {

namespace {

std::atomic<LogLevel> gLevel{LogLevel::Info};
std::atomic<int> gFd{2};

/// Whether `fd` is the stream systemd connected to the journal: JOURNAL_STREAM holds its
/// "device:inode" (systemd.exec(5)), so a redirected standard error is not mistaken for it.
bool isJournalStream(int fd) noexcept
{
    const char* stream = std::getenv("JOURNAL_STREAM");
    struct stat st {};
    unsigned long long device = 0;
    unsigned long long inode = 0;
    if (!stream || std::sscanf(stream, "%llu:%llu", &device, &inode) != 2 || ::fstat(fd, &st) != 0)
        return false;
    return st.st_dev == device && st.st_ino == inode;
}

/// On the journal each line starts with its syslog priority, "<4>" for a warning, which journald
/// takes as the line's priority (SyslogLevelPrefix=yes, systemd's default), so
/// `journalctl -u mirror -p warning` shows the warnings and errors only.
std::atomic<bool> gJournal{isJournalStream(2)};

int syslogPriority(LogLevel level) noexcept
{
    switch (level) {
        case LogLevel::Error:
            return 3;  // LOG_ERR
        case LogLevel::Warn:
            return 4;  // LOG_WARNING
        case LogLevel::Info:
            return 6;  // LOG_INFO
        case LogLevel::Debug:
            return 7;  // LOG_DEBUG
    }
    return 6;
}

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
    LogLevel levels[kLogRingLines] = {};
    int next = 0;   // slot of the next line
    int count = 0;  // lines kept (<= kLogRingLines)
};
LogRing gRing;

void keep(LogLevel level, const char* line, std::size_t n) noexcept
{
    const std::lock_guard<std::mutex> lock(gRing.mutex);
    gRing.levels[gRing.next] = level;
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
    gJournal = isJournalStream(fd);
}
bool logsToJournal() noexcept
{
    return gJournal;
}
double uptimeSeconds() noexcept
{
    return monotonicSeconds() - gStart;
}

void logf(LogLevel level, const char* format, ...) noexcept
{
    if (static_cast<int>(level) > static_cast<int>(gLevel.load()))
        return;
    // "<N>" (the journal's priority prefix), then the line as the ring keeps it.
    char buffer[4 + kRingLineBytes];
    const int prefix = std::snprintf(buffer, 4, "<%d>", syslogPriority(level));
    char* line = buffer + prefix;
    const int size = static_cast<int>(kRingLineBytes);
    int n =
        std::snprintf(line, kRingLineBytes, "[%10.3f] %c ", uptimeSeconds(), levelLetter(level));
    va_list args;
    va_start(args, format);
    const int m =
        std::vsnprintf(line + n, kRingLineBytes - static_cast<std::size_t>(n), format, args);
    va_end(args);
    n = m < 0 ? n : std::min(n + m, size - 2);
    line[n++] = '\n';
    keep(level, line, static_cast<std::size_t>(n));
    // One write per line so lines from the loop and the console never interleave mid-line.
    const bool journal = gJournal;
    [[maybe_unused]] const ssize_t w =
        ::write(gFd, journal ? buffer : line, static_cast<std::size_t>(n + (journal ? prefix : 0)));
}

int forEachRecentLogLine(int maxLines, void (*emit)(const char* line, void* context), void* context,
                         LogLevel atLeast) noexcept
{
    const std::lock_guard<std::mutex> lock(gRing.mutex);
    auto slotOf = [](int age) { return (gRing.next - 1 - age + kLogRingLines) % kLogRingLines; };
    auto wanted = [&](int slot) {
        return static_cast<int>(gRing.levels[slot]) <= static_cast<int>(atLeast);
    };
    // Back from the newest line to the oldest of the last `maxLines` that pass, then forward.
    int oldest = -1;
    int found = 0;
    for (int age = 0; age < gRing.count && found < maxLines; ++age)
        if (wanted(slotOf(age))) {
            oldest = age;
            ++found;
        }
    for (int age = oldest; age >= 0; --age)
        if (wanted(slotOf(age)))
            emit(gRing.lines[slotOf(age)], context);
    return found;
}

}  // namespace firmware
