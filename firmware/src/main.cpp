// mirror: the smart mirror appliance firmware. Parses the command line and the config, opens the
// source and the display, and runs the frame loop. Every start-up failure is caught here, once,
// and printed as one line with a distinct exit code (firmware/exit_codes.hpp).

#include "bug_report.hpp"
#include "firmware/config.hpp"
#include "firmware/device_factory.hpp"
#include "firmware/exit_codes.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "firmware/startup_error.hpp"
#include "platform/camera_list.hpp"
#include "platform/serial_console.hpp"
#include "platform/stdin_console.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <charconv>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace {

/// The running loop, for the stop signals; lock-free, so the handler may read it.
std::atomic<firmware::FrameLoop*> gLoop{nullptr};
static_assert(std::atomic<firmware::FrameLoop*>::is_always_lock_free);

/// A TOML basic string holding `text` (for turning --source/--display into --set overrides).
std::string tomlQuote(const std::string& text)
{
    std::string out = "\"";
    for (const unsigned char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += static_cast<char>(c);
        } else if (c < 0x20 || c == 0x7f) {
            char esc[8];
            std::snprintf(esc, sizeof esc, "\\u%04x", c);
            out += esc;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out + "\"";
}

/// Makes sure fds 0, 1 and 2 are open (on /dev/null if need be) before any device is opened, so a
/// device can never land on fd 0 and be read as the console.
void ensureStandardFds()
{
    for (int fd = 0; fd <= 2; ++fd)
        if (::fcntl(fd, F_GETFD) < 0) {
            const int opened = ::open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
            if (opened >= 0 && opened != fd) {
                ::dup2(opened, fd);
                ::close(opened);
            }
        }
}

/// The most --frames accepts: over a thousand years at 30 fps, and far from any wrap-around.
constexpr std::uint64_t kMaxFrames = 1'000'000'000'000;

/// --frames N as a whole number 0..kMaxFrames: CLI11 alone would take -1 as 2^64-1 and saturate
/// 1e23 to the largest integer.
CLI::Validator frameCount()
{
    return CLI::Validator(
        [](std::string& text) -> std::string {
            std::uint64_t value = 0;
            const char* end = text.data() + text.size();
            const auto [ptr, ec] = std::from_chars(text.data(), end, value);
            if (text.empty() || ec != std::errc() || ptr != end || value > kMaxFrames) {
                std::string shown = text.substr(0, 32);
                for (char& c : shown)
                    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
                        c = '?';  // the message stays one line, no escape reaches the terminal
                return "expected a whole number of frames 0.." + std::to_string(kMaxFrames) +
                       ", got \"" + shown + (text.size() > 32 ? "...\"" : "\"");
            }
            return {};
        },
        "N");
}

/// Where a line that ends the process goes: standard error, as an error on the journal (its "<3>"
/// priority prefix) so that `journalctl -u mirror -p err` shows why the service stopped.
std::ostream& fatal()
{
    return std::cerr << (firmware::logsToJournal() ? "<3>" : "");
}

/// How long `mirror --bug-report` runs the mirror before it writes the report: the camera has
/// delivered and the selftest has something to say.
constexpr double kBugReportRunS = 3.0;

/// This executable's path, for running it again (the bug report's camera list).
std::string programPath()
{
    char path[4096];
    const ssize_t n = ::readlink("/proc/self/exe", path, sizeof path - 1);
    return n > 0 ? std::string(path, static_cast<std::size_t>(n)) : std::string();
}

/// `mirror --bug-report` when the mirror could not start (a camera in use by the running service,
/// no display): the report holds what there is, the start-up error first.
int startupBugReport(const std::string& path, const firmware::Config& config, const char* error)
{
    const std::string version =
        "mirror " MIRROR_VERSION "\nstart-up failed: " + std::string(error) +
        "\n(no status, selftest or snapshot: the mirror did not run; if "
        "the service holds the devices, use the console's bug-report)\n";
    std::string log;
    firmware::forEachRecentLogLine(
        firmware::kLogRingLines,
        [](const char* line, void* context) { static_cast<std::string*>(context)->append(line); },
        &log);
    const std::string toml = "# from " + config.origin + "\n" + firmware::toToml(config);
    const firmware::BugReportFile files[] = {
        {"status.txt", version}, {"config.toml", toml}, {"log.txt", log}};
    const std::string problem = firmware::writeBugReport(files, "", path, programPath());
    if (!problem.empty()) {
        std::cerr << "mirror: bug report: " << problem << '\n';
        return firmware::kExitInternal;
    }
    std::cerr << "mirror: wrote the bug report " << path << " (without a running mirror)\n";
    return firmware::kExitOk;
}

extern "C" void onStopSignal(int signal)
{
    if (firmware::FrameLoop* loop = gLoop.load()) {
        loop->requestStop();  // the loop finishes its frame and saves what it must
        return;
    }
    // Starting up (or rebuilding for reboot-mirror) there is nothing to finish: a stop then ends
    // the process as the signal would, however long a device or file takes to open.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

const char* const kFooter = R"(
Sources (--source, [source] spec):
  auto          a libcamera camera, else a V4L2 capture device; with neither, the appliance
                (under systemd) shows "camera unavailable" and switches to a camera when one
                is plugged in (udev), a developer's run plays the demo scene
  demo          Debian's opencv-doc sample video Megamind.avi with a synthetic coloured card moving
                over it; the fully synthetic scene when the video is not installed
  synthetic     a procedural scene (no files needed)
  file:PATH     a video file, a folder of PNG/JPEG frames, or a glob ("file:/data/f*.png");
                [source] loop and rate ("native", "max" or an fps number) control replay
  libcamera[:ID] a camera through libcamera (index or id as `cam -l` lists it); [source] width,
                height, fps
  v4l2:DEVICE   a V4L2 capture device (/dev/videoN): YUYV, RGB24, or MJPEG decoded
  A camera missing at boot, unplugged or stalled shows "camera unavailable" and is retried with
  back-off (0.5 s doubling to 8 s) until it is back.

Displays (--display, [display] spec):
  auto          the panel (DRM/KMS) when a connected one exists, else a desktop window when a
                display server is there, else headless in $STATE_DIRECTORY or /var/lib/mirror
                (/display: snapshots on request only) until a panel is connected (udev)
  drm[:CARD]    the panel through DRM/KMS (GBM + EGL, page flips on vsync); [display] mode
                "preferred", "WxH" or "WxH@Hz"; `snapshot` PNGs in [display] snapshot_dir
  window        an X11 window for development; keys: n/p next/previous overlay, o off, t train
                the card, d debug HUD, h HUD, s snapshot, q quit
  headless:DIR  EGL without a window system (Mesa's software renderer when no GPU); PNG snapshots
                in DIR every [display] snapshot_every frames and on the console's `snapshot`, and a
                one-line summary per second in DIR/summary.log

Diagnostics console (on standard input when [console] stdin = true, and on the serial port
[console] serial, e.g. /dev/ttyS0 at 115200 8N1):
  help [COMMAND], status [--json], selftest, log [error|warn|info|debug] [N], version,
  snapshot, config, faces, debug [on|off], overlay [next|prev|off|list|NAME|N|mode
  global|per_face], buttons, card [train|reset|forget], bug-report [PATH], reboot-mirror (rebuilds the
  pipeline, not the machine), quit. Long replies are streamed whole, never cut.

Field tools:
  mirror --list-cameras        the cameras (libcamera, V4L2) with their formats and sizes
  mirror --bug-report FILE     runs the mirror for 3 s and writes a tarball for a developer;
                               the console's bug-report does the same in a running mirror
  Under systemd the log lines carry journald priorities: journalctl -u mirror -p warning

Overlays ([overlay]): hats and glasses from the catalogue (default: the installed
  /usr/share/mirror/overlays/catalogue.toml, or assets/overlays/ of the source tree). Each entry
  names its OBJ meshes, material, anchor on the head and scale (assets/overlays/FORMAT.md): adding
  a hat is adding files. mode "global" (one for everyone) or "per_face" (buttons change the
  nearest face). The last choice is kept in [state] dir/overlay.toml.

Buttons ([buttons], libgpiod): chip = "gpiochip0", lines = [17, 27, 22] (button 1, 2, 3),
  active_low, bias = "pull-up", debounce_ms, long_press_ms, short_press = ["next", "prev"],
  long_press = ["train-card", "toggle-debug", "enrol-guest"]. Raspberry Pi header: button 1
  between pin 11 (BCM17) and pin 9 (GND), button 2 between pin 13 (BCM27) and pin 14 (GND),
  button 3 (the guest button) between pin 15 (BCM22) and pin 20 (GND); no resistors (the
  internal pull-ups are used). A missing or busy chip is one warning; the mirror runs on.

Config: TOML, validated strictly; every problem is printed as FILE:LINE:COL: key: what is wrong.
  The schema with every key is in config/SCHEMA.md; --print-config shows the effective values.

Exit codes:
  0 stopped as asked   2 bad command line or config   3 source failed   4 display failed
  5 pipeline or renderer failed   1 internal error
)";

}  // namespace

int main(int argc, char** argv)
{
    ensureStandardFds();
    CLI::App app{
        "mirror: smart mirror appliance firmware (shows you mirrored, tracks faces and a "
        "coloured card, draws overlays)",
        "mirror"};
    app.footer(kFooter);
    app.set_version_flag("--version", "mirror " MIRROR_VERSION);

    std::string configPath;
    bool printConfig = false;
    std::string source;
    std::string display;
    std::uint64_t frames = 0;
    std::vector<std::string> sets;
    bool listCameras = false;
    std::string bugReport;
    app.add_option("-c,--config", configPath,
                   std::string("config file (default ") + firmware::kDefaultConfigPath +
                       "; built-in defaults when that is absent)");
    app.add_flag("--print-config", printConfig, "print the effective config as TOML and exit");
    app.add_option("-s,--source", source, "frame source SPEC (overrides [source] spec)");
    app.add_option("-d,--display", display, "display SPEC (overrides [display] spec)");
    app.add_option("-n,--frames", frames, "stop after N frames (0 = run until stopped)")
        ->check(frameCount());
    app.add_option("--set", sets, "override one config key: --set display.hud=false (TOML value)");
    app.add_flag("--list-cameras", listCameras,
                 "list the cameras (libcamera and V4L2) with their formats and sizes, and exit");
    app.add_option("--bug-report", bugReport,
                   "run the mirror for a few seconds, write a bug report tarball to FILE (version, "
                   "status, selftest, config, log, devices, a snapshot, the journal) and exit");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? firmware::kExitOk : firmware::kExitConfig;
    }

    if (listCameras) {
        if (platform::listCameras(stdout) == 0)
            std::printf("no cameras found\n");
        return firmware::kExitOk;
    }

    firmware::ConfigRequest request;
    request.path = configPath;
    request.pathExplicit = !configPath.empty();
    request.sets = sets;
    if (!source.empty())
        request.sets.push_back("source.spec = " + tomlQuote(source));
    if (!display.empty())
        request.sets.push_back("display.spec = " + tomlQuote(display));

    firmware::Config config;
    try {
        config = firmware::loadConfig(request);
    } catch (const firmware::ConfigError& e) {
        for (const auto& problem : e.problems())
            fatal() << problem.format() << '\n';
        return firmware::kExitConfig;
    }
    if (printConfig) {
        std::cout << "# effective configuration (from " << config.origin << ")\n"
                  << firmware::toToml(config);
        return firmware::kExitOk;
    }

    firmware::setLogLevel(config.log.level);
    // Under systemd the working directory is /: a relative folder is rarely what was meant.
    if (!config.state.dir.empty() && config.state.dir.front() != '/')
        MIRROR_LOG_WARN(
            "state: state.dir \"%s\" is relative, so it is under the working "
            "directory; an installed mirror wants an absolute path",
            config.state.dir.c_str());
    std::signal(SIGPIPE, SIG_IGN);
    try {
        std::unique_ptr<platform::StdinConsole> console;
        if (config.console.stdinEnabled)
            console = std::make_unique<platform::StdinConsole>();
        // The technician's serial port: missing or unusable is one warning, the mirror runs on.
        std::unique_ptr<platform::SerialConsole> serial;
        if (!config.console.serial.empty()) {
            try {
                platform::SerialConsoleOptions o;
                o.baud = config.console.baud;
                o.maxLineLength = static_cast<std::size_t>(config.console.maxLineLength);
                serial = std::make_unique<platform::SerialConsole>(config.console.serial, o);
                MIRROR_LOG_INFO("console: %s", serial->description());
            } catch (const std::exception& e) {
                MIRROR_LOG_WARN("console: %s; no serial console", e.what());
            }
        }
        std::signal(SIGINT, onStopSignal);
        std::signal(SIGTERM, onStopSignal);
        // `reboot-mirror` rebuilds the pipeline (source, display, stages, renderer) in this
        // process: everything of the old one is released before the new one opens the devices.
        for (;;) {
            auto frameSource = firmware::makeSource(config.source);
            auto frameDisplay = firmware::makeDisplay(config.display, config.state.dir);
            auto deviceWait = firmware::makeDeviceWait(config, *frameSource, *frameDisplay);
            firmware::FrameLoop loop(config, std::move(frameSource), std::move(frameDisplay));
            loop.attachDeviceWait(std::move(deviceWait));
            if (console)
                loop.attachConsole(console.get(), ::isatty(0) == 1);
            if (serial)
                loop.attachSerialConsole(serial.get());
            loop.attachButtons(firmware::makeButtons(config.buttons));
            loop.setProgramPath(programPath());
            if (!bugReport.empty())
                loop.scheduleBugReport(bugReport, kBugReportRunS);
            gLoop = &loop;
            const int code = loop.run(frames);
            gLoop = nullptr;
            if (!bugReport.empty())
                return loop.bugReportFailed() ? firmware::kExitInternal : code;
            // A process whose camera libcamera had to park must not run static destructors
            // while the parked camera's thread still runs (docs/DEVICES.md): leave at once.
            if (loop.processRestartRequired())
                std::_Exit(code);
            if (!loop.restartRequested())
                return code;
            MIRROR_LOG_INFO("rebuilding the pipeline");
        }
    } catch (const firmware::StartupError& e) {
        fatal() << "mirror: " << e.what() << '\n';
        if (!bugReport.empty())
            return startupBugReport(bugReport, config, e.what());
        return e.exitCode();
    } catch (const std::exception& e) {
        fatal() << "mirror: " << e.what() << '\n';
        if (!bugReport.empty())
            return startupBugReport(bugReport, config, e.what());
        return firmware::kExitPipeline;
    }
}
