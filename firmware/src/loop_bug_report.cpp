// FrameLoop's bug report: `bug-report [PATH]` on the console and `mirror --bug-report FILE`. The
// loop gathers what only it knows (status, selftest, config, log ring) into buffers sized at
// start-up, asks the display for a snapshot, and hands the rest (device list, journal, tar) to
// the BugReportWorker's thread, so a frame never waits for any of it.
#include "bug_report.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "monotonic_clock.hpp"

#include <cstdio>
#include <cstring>
#include <ctime>

namespace firmware {

namespace {

/// A display that cannot write the asked-for snapshot within this time (it is down) is left out.
constexpr std::int64_t kSnapshotWaitNs = 3'000'000'000;

}  // namespace

void FrameLoop::setProgramPath(std::string path)
{
    bugReports_->setProgram(std::move(path));
}

void FrameLoop::scheduleBugReport(std::string path, double afterS)
{
    scheduledBugReport_ = std::move(path);
    bugReportDueNs_ = monotonicNs() + static_cast<std::int64_t>(afterS * 1e9);
}

void FrameLoop::bugReportCommand(const Args& args, Reply& reply) noexcept
{
    if (bugSnapshotWanted_ || bugReports_->busy()) {
        reply.printf("error: a bug report is being written; the consoles are told when it is\n");
        return;
    }
    if (args.size() == 2) {
        std::snprintf(bugReportPath_, sizeof bugReportPath_, "%.*s",
                      static_cast<int>(args[1].size()), args[1].data());
    } else {
        char name[64];
        const std::time_t now = std::time(nullptr);
        std::tm tm{};
        ::localtime_r(&now, &tm);
        std::strftime(name, sizeof name, "bug-report-%Y%m%d-%H%M%S.tar.gz", &tm);
        std::snprintf(bugReportPath_, sizeof bugReportPath_, "%s/%s",
                      config_.state.dir.empty() ? "." : config_.state.dir.c_str(), name);
    }
    gatherBugReport();
    reply.printf("bug-report: writing %s (the consoles are told when it is done)\n",
                 bugReportPath_);
}

/// The texts only the loop has, then a snapshot asked for (the report goes to the worker once
/// it is written, see afterPresent()) or, on a display without snapshots, the worker at once.
void FrameLoop::gatherBugReport() noexcept
{
    for (Reply& r : bugTexts_)
        r.clear();
    bugTexts_[0].printf("mirror %s (built %s %s, %s)\n", MIRROR_VERSION, __DATE__, __TIME__,
                        MIRROR_BUILD_TYPE);
    formatStatus(bugTexts_[0]);
    formatStatusJson(bugTexts_[1]);
    const int failed = selfTest(bugTexts_[2]);
    bugTexts_[2].printf("selftest: %s\n", failed == 0 ? "all PASS" : "FAILED");
    bugTexts_[3].printf("# from %s\n", config_.origin.c_str());
    bugTexts_[3].append(configToml_);
    forEachRecentLogLine(
        kLogRingLines,
        [](const char* line, void* context) { static_cast<Reply*>(context)->append(line); },
        &bugTexts_[4]);
    if (display_->requestSnapshot()) {
        bugSnapshotWanted_ = true;
        bugRequestedNs_ = monotonicNs();
    } else {
        startBugReport("");
    }
}

void FrameLoop::startBugReport(const char* snapshot) noexcept
{
    bugSnapshotWanted_ = false;
    const BugReportFile files[] = {{"status.txt", bugTexts_[0].text()},
                                   {"status.json", bugTexts_[1].text()},
                                   {"selftest.txt", bugTexts_[2].text()},
                                   {"config.toml", bugTexts_[3].text()},
                                   {"log.txt", bugTexts_[4].text()}};
    bugReports_->start(files, snapshot, bugReportPath_);
}

/// Once per iteration: a scheduled report due, a snapshot that never came, a report written.
void FrameLoop::serviceBugReport(std::int64_t nowNs) noexcept
{
    if (bugReportDueNs_ != 0 && nowNs >= bugReportDueNs_ && !bugReports_->busy()) {
        bugReportDueNs_ = 0;
        std::snprintf(bugReportPath_, sizeof bugReportPath_, "%s", scheduledBugReport_.c_str());
        gatherBugReport();
        stopAfterBugReport_ = true;
    }
    if (bugSnapshotWanted_ && nowNs - bugRequestedNs_ > kSnapshotWaitNs)
        startBugReport("");
    char message[512];
    if (!bugReports_->poll(message, sizeof message))
        return;
    tellConsoles(message);
    MIRROR_LOG_INFO("%.*s", static_cast<int>(std::strlen(message)) - 1, message);
    if (stopAfterBugReport_) {
        bugReportFailed_ = std::strncmp(message, "bug-report: failed", 18) == 0;
        requestStop();
    }
}

}  // namespace firmware
