#pragma once
// Logging for the firmware: one line per event, "[   12.345] W source: camera lost: ...", to
// stderr, filtered by level. Formatting uses a fixed buffer and one write(2): safe in the frame
// loop (no allocation, no locks beyond the kernel's). Platform and render code do not log; they
// return states and the firmware logs what changed.

#include "firmware/config.hpp"

namespace firmware {

void setLogLevel(LogLevel level) noexcept;
LogLevel logLevel() noexcept;
/// Redirects log output (tests); default is standard error (fd 2).
void setLogFd(int fd) noexcept;
/// True when the log's fd is the journal stream systemd gave the service (JOURNAL_STREAM): each
/// line then starts with its syslog priority ("<3>" error, "<4>" warning, "<6>" info, "<7>"
/// debug), so `journalctl -u mirror -p warning` filters by level.
bool logsToJournal() noexcept;

void logf(LogLevel level, const char* format, ...) noexcept __attribute__((format(printf, 2, 3)));

/// The last kLogRingLines lines (any level that was logged) are kept in memory for the console's
/// `log` command: a technician on the serial port sees what happened before they plugged in.
inline constexpr int kLogRingLines = 200;
/// Calls `emit` for each of the last `maxLines` kept lines at level `atLeast` or more severe
/// (Warn: warnings and errors), oldest first (each ends with '\n'). Returns how many were
/// emitted. No allocation.
int forEachRecentLogLine(int maxLines, void (*emit)(const char* line, void* context), void* context,
                         LogLevel atLeast = LogLevel::Debug) noexcept;

/// Seconds since the process started, for log stamps and uptime.
double uptimeSeconds() noexcept;

}  // namespace firmware

#define MIRROR_LOG_ERROR(...) ::firmware::logf(::firmware::LogLevel::Error, __VA_ARGS__)
#define MIRROR_LOG_WARN(...) ::firmware::logf(::firmware::LogLevel::Warn, __VA_ARGS__)
#define MIRROR_LOG_INFO(...) ::firmware::logf(::firmware::LogLevel::Info, __VA_ARGS__)
#define MIRROR_LOG_DEBUG(...) ::firmware::logf(::firmware::LogLevel::Debug, __VA_ARGS__)
