#pragma once
// A bug report: one tarball with what a developer needs to understand a mirror in the field
// (like rpicam-apps' camera-bug-report): the version, status, selftest, config and log ring as
// the running mirror has them, its device list, a snapshot and the unit's journal.

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <thread>

namespace firmware {

/// One file of the report, as text.
struct BugReportFile {
    const char* name;
    std::string_view text;
};

/// Writes the tarball `outPath` (gzip-compressed tar) holding `files`, a copy of `snapshotPath`
/// (when not empty), devices.txt (`MIRROR --list-cameras` run as a new process, when `mirror` is
/// the path of the mirror executable; the DRM connectors, GPIO chips, serial ports) and
/// journal.txt (`journalctl -u mirror.service`, when there is a journal this user may read). The
/// tarball is made by Debian's `tar` (posix_spawn, no shell): ten small files need no archive
/// library. Blocks for seconds (journalctl, tar): never call it on the frame loop. Returns "" on
/// success, else one line saying what failed.
std::string writeBugReport(std::span<const BugReportFile> files, const std::string& snapshotPath,
                           const std::string& outPath, const std::string& mirror);

/// The default file name: bug-report-YYYYmmdd-HHMMSS.tar.gz in `dir`.
std::string defaultBugReportPath(const std::string& dir);

/// Runs writeBugReport() on its own thread, so the frame loop only hands it a job and later
/// asks whether it is done: start() and poll() take a mutex for a moment and never allocate.
class BugReportWorker {
public:
    static constexpr std::size_t kFiles = 6;

    BugReportWorker();
    ~BugReportWorker();
    BugReportWorker(const BugReportWorker&) = delete;
    BugReportWorker& operator=(const BugReportWorker&) = delete;

    /// Whether a report is being written (from start() to the poll() that returned its result).
    bool busy() const noexcept { return state_.load() != State::Idle; }
    /// The mirror executable, for the camera list (start-up only; empty: no camera list).
    void setProgram(std::string path) { program_ = std::move(path); }
    /// Hands over a job: the texts must stay untouched until poll() returned its result. `path`
    /// and `snapshot` are copied (up to 4095 bytes). False when busy.
    bool start(std::span<const BugReportFile> files, std::string_view snapshot,
               std::string_view path) noexcept;
    /// When the job is done: true, with `message` the line to tell the consoles.
    bool poll(char* message, std::size_t size) noexcept;

private:
    enum class State { Idle, Queued, Writing, Done };
    void run();

    std::mutex mutex_;
    std::condition_variable wake_;
    std::atomic<State> state_{State::Idle};
    bool quit_ = false;
    std::array<BugReportFile, kFiles> files_{};
    std::size_t fileCount_ = 0;
    char path_[4096] = "";
    char snapshot_[4096] = "";
    char result_[512] = "";
    std::string program_;
    std::thread thread_;
};

}  // namespace firmware
