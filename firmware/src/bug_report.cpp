// The bug report's writer: the files in a temporary folder, then `tar`. Runs off the frame loop
// (BugReportWorker's thread, or `mirror --bug-report` before any loop runs).
#include "bug_report.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <vector>

extern char** environ;

namespace firmware {

namespace {

namespace fs = std::filesystem;

void writeText(const fs::path& path, std::string_view text)
{
    std::ofstream out(path, std::ios::binary);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out)
        throw std::runtime_error("cannot write " + path.string());
}

/// Runs `argv` (no shell) with standard output into `outPath` (or /dev/null) and standard error
/// beside it, killed after `timeoutS`. Returns its exit status, or -1 when it could not start.
int runTool(const std::vector<std::string>& argv, const std::string& outPath, int timeoutS)
{
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, outPath.empty() ? "/dev/null" : outPath.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0640);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> args;
    for (const std::string& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    const int r = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (r != 0)
        return -1;
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeoutS);
    for (;;) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid)
            break;
        if (done < 0 && errno != EINTR)
            return -1;
        if (std::chrono::steady_clock::now() > deadline) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            return -1;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string readSmallFile(const fs::path& path)
{
    std::ifstream in(path);
    std::string text;
    std::getline(in, text);
    return text;
}

/// The devices besides the cameras: DRM connectors and their state, GPIO chips, serial ports.
std::string otherDevices()
{
    std::string text = "DRM connectors (/sys/class/drm):\n";
    std::error_code ec;
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator("/sys/class/drm", ec))
        if (fs::exists(entry.path() / "status", ec))
            names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    for (const std::string& name : names)
        text += "    " + name + ": " + readSmallFile(fs::path("/sys/class/drm") / name / "status") +
                "\n";
    if (names.empty())
        text += "    none\n";
    text += "device nodes:\n";
    std::vector<std::string> nodes;
    for (const auto& entry : fs::directory_iterator("/dev", ec)) {
        const std::string name = entry.path().filename().string();
        for (const char* prefix :
             {"gpiochip", "ttyS", "ttyAMA", "ttyUSB", "ttyACM", "video", "media"})
            if (name.rfind(prefix, 0) == 0)
                nodes.push_back(entry.path().string());
    }
    for (const auto& entry : fs::directory_iterator("/dev/dri", ec))
        nodes.push_back(entry.path().string());
    std::sort(nodes.begin(), nodes.end());
    for (const std::string& node : nodes)
        text +=
            "    " + node + (::access(node.c_str(), R_OK | W_OK) == 0 ? "" : " (no access)") + "\n";
    return text;
}

}  // namespace

std::string defaultBugReportPath(const std::string& dir)
{
    char name[64];
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    ::localtime_r(&now, &tm);
    std::strftime(name, sizeof name, "bug-report-%Y%m%d-%H%M%S.tar.gz", &tm);
    return (fs::path(dir.empty() ? "." : dir) / name).string();
}

std::string writeBugReport(std::span<const BugReportFile> files, const std::string& snapshotPath,
                           const std::string& outPath, const std::string& mirror)
{
    std::string tmpl = (fs::temp_directory_path() / "mirror-bug-report-XXXXXX").string();
    if (!::mkdtemp(tmpl.data()))
        return std::string("cannot make a temporary folder: ") + std::strerror(errno);
    const fs::path dir = tmpl;
    std::string error;
    try {
        std::vector<std::string> names;
        for (const BugReportFile& file : files) {
            writeText(dir / file.name, file.text);
            names.push_back(file.name);
        }
        // The cameras from a new process: this one may own libcamera's only CameraManager.
        const std::string devices = (dir / "devices.txt").string();
        if (mirror.empty())
            writeText(devices, "cameras: not listed (no mirror executable given)\n");
        else if (runTool({mirror, "--list-cameras"}, devices, 20) < 0)
            writeText(devices, "mirror --list-cameras did not finish\n");
        std::ofstream(devices, std::ios::app) << "\n" << otherDevices();
        names.push_back("devices.txt");
        const std::string journal = (dir / "journal.txt").string();
        const int journalStatus = runTool({"journalctl", "-u", "mirror.service", "-b", "--no-pager",
                                           "-n", "5000", "-o", "short-monotonic"},
                                          journal, 20);
        if (journalStatus != 0)
            std::ofstream(journal, std::ios::app)
                << "\n(journalctl -u mirror.service: "
                << (journalStatus < 0 ? "not available" : "exit " + std::to_string(journalStatus))
                << ")\n";
        names.push_back("journal.txt");
        std::error_code ec;
        if (!snapshotPath.empty() && fs::copy_file(snapshotPath, dir / "snapshot.png", ec))
            names.push_back("snapshot.png");
        std::vector<std::string> tar = {"tar", "-czf", outPath, "-C", dir.string()};
        tar.insert(tar.end(), names.begin(), names.end());
        const int status = runTool(tar, "", 60);
        if (status != 0)
            error =
                "tar " + std::string(status < 0 ? "did not run" : "failed") + " writing " + outPath;
    } catch (const std::exception& e) {
        error = e.what();
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
    return error;
}

// --- BugReportWorker --------------------------------------------------------------------------

BugReportWorker::BugReportWorker() : thread_([this] { run(); }) {}

BugReportWorker::~BugReportWorker()
{
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
    }
    wake_.notify_one();
    thread_.join();
}

bool BugReportWorker::start(std::span<const BugReportFile> files, std::string_view snapshot,
                            std::string_view path) noexcept
{
    if (busy() || files.size() > kFiles)
        return false;
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        std::copy(files.begin(), files.end(), files_.begin());
        fileCount_ = files.size();
        std::snprintf(path_, sizeof path_, "%.*s", static_cast<int>(path.size()), path.data());
        std::snprintf(snapshot_, sizeof snapshot_, "%.*s", static_cast<int>(snapshot.size()),
                      snapshot.data());
        state_ = State::Queued;
    }
    wake_.notify_one();
    return true;
}

bool BugReportWorker::poll(char* message, std::size_t size) noexcept
{
    if (state_.load() != State::Done)
        return false;
    const std::lock_guard<std::mutex> lock(mutex_);
    std::snprintf(message, size, "%s", result_);
    state_ = State::Idle;
    return true;
}

void BugReportWorker::run()
{
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        wake_.wait(lock, [this] { return quit_ || state_.load() == State::Queued; });
        if (quit_)
            return;
        state_ = State::Writing;
        const std::span<const BugReportFile> files(files_.data(), fileCount_);
        const std::string path = path_;
        const std::string snapshot = snapshot_;
        lock.unlock();
        std::string error;
        try {
            error = writeBugReport(files, snapshot, path, program_);
        } catch (const std::exception& e) {
            error = e.what();
        }
        lock.lock();
        if (error.empty()) {
            std::error_code ec;
            const auto bytes = fs::file_size(path, ec);
            std::snprintf(result_, sizeof result_, "bug-report: wrote %.400s (%llu KB)\n",
                          path.c_str(), static_cast<unsigned long long>(ec ? 0 : bytes / 1024));
        } else {
            std::snprintf(result_, sizeof result_, "bug-report: failed: %.480s\n", error.c_str());
        }
        state_ = State::Done;
    }
}

}  // namespace firmware
