// FrameLoop's console: the commands the diagnostics shell serves on stdin and the serial port,
// each on the same paths as the buttons; `status` here, `selftest` in self_test.cpp.
#include "card_control.hpp"
#include "face_control.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "overlay_control.hpp"
#include "monotonic_clock.hpp"
#include "people_control.hpp"

#include <algorithm>
#include <charconv>
#include <system_error>

namespace firmware {

namespace {

/// `log [error|warn|info|debug] [N]`: the last N lines (default 20) at that level or worse.
void logCommand(const Args& args, Reply& reply) noexcept
{
    long n = 20;
    LogLevel atLeast = LogLevel::Debug;
    std::size_t i = 1;
    if (const int level = args.choice(i, {"error", "warn", "info", "debug"}); level >= 0) {
        atLeast = static_cast<LogLevel>(level);
        ++i;
    }
    if (i < args.size() && !args.number(i, 1, kLogRingLines, n)) {
        reply.usageError("N must be 1..%d, got '%.*s'", kLogRingLines, Args::shown(args[i]),
                         args[i].data());
        return;
    }
    if (i + 1 < args.size()) {
        reply.usageError("unexpected '%.*s'", Args::shown(args[i + 1]), args[i + 1].data());
        return;
    }
    const int count = forEachRecentLogLine(
        static_cast<int>(n),
        [](const char* line, void* context) { static_cast<Reply*>(context)->append(line); }, &reply,
        atLeast);
    if (count == 0)
        reply.line("log: no lines at that level");
}

/// `text` as a JSON string: quotes, backslashes and control characters escaped.
void jsonString(Reply& reply, const char* text) noexcept
{
    reply.append("\"");
    for (const char* c = text; *c; ++c) {
        if (*c == '"' || *c == '\\')
            reply.printf("\\%c", *c);
        else if (static_cast<unsigned char>(*c) < 0x20 || *c == 0x7f)
            reply.printf("\\u%04x", static_cast<unsigned char>(*c));
        else
            reply.append({c, 1});
    }
    reply.append("\"");
}

}  // namespace

void FrameLoop::registerCommands()
{
    shell_.add("status", "status [--json]",
               "uptime, frames, fps, per-stage p50/p99 ms, source, display; --json for tools",
               [this](const Args& args, Reply& reply) noexcept {
                   if (args.size() == 1)
                       formatStatus(reply);
                   else if (args[1] == "--json")
                       formatStatusJson(reply);
                   else
                       reply.usageError("unknown option '%.*s'", Args::shown(args[1]),
                                        args[1].data());
               });
    shell_.add("snapshot", "snapshot", "write a PNG of the next frame shown; says its path",
               [this](const Args&, Reply& reply) noexcept { snapshotCommand(reply); });
    shell_.add("config", "config", "print the effective configuration (TOML)",
               [this](const Args&, Reply& reply) noexcept {
                   reply.printf("# from %s\n", config_.origin.c_str());
                   reply.append(configToml_);
               });
    if (card_)
        shell_.add(
            "card", "card [train|reset|forget]",
            "the colour card: state and colour; train on the centre of the next frame (refused "
            "unless it is one saturated colour); forget the track; forget the trained colour",
            [this](const Args& args, Reply& reply) noexcept { card_->command(args, reply); });
    if (faces_) {
        shell_.add("faces", "faces",
                   "tracked faces: id, state, centre, size, roll, confidence, age",
                   [this](const Args&, Reply& reply) noexcept {
                       faces_->format(reply);
                       if (people_)
                           people_->formatFaces(state_.faces, reply);
                   });
        shell_.add("debug", "debug [on|off]",
                   "show or hide the face debug HUD (boxes, corners, roll)",
                   [this](const Args& args, Reply& reply) noexcept {
                       if (args.size() == 2) {
                           const int on = args.choice(1, {"off", "on"});
                           if (on < 0) {
                               reply.usageError("expected on or off, got '%.*s'",
                                                Args::shown(args[1]), args[1].data());
                               return;
                           }
                           setDebugHud(on == 1);
                       }
                       reply.printf("debug: %s\n", debugHud() ? "on" : "off");
                   });
    }
    shell_.add("overlay", "overlay [next|prev|off|list|NAME|N|mode global|per_face]",
               "what the faces wear: show, change (by name or by the number `overlay list` "
               "prints), list the catalogue, one choice for all or one per face",
               [this](const Args& args, Reply& reply) noexcept {
                   overlays_->command(args, state_.faces, reply);
               });
    if (people_)
        shell_.add("person",
                   "person [list|add NAME|rename OLD NEW|forget NAME|--all|birthday NAME MM-DD]",
                   "the people the mirror knows: list, enrol the one face in view, rename, "
                   "forget (one or --all: files too), birthday (MM-DD or none)",
                   [this](const Args& args, Reply& reply) noexcept {
                       people_->command(args, state_.faces, state_.fits, monotonicNs(), reply);
                   });
    shell_.add("buttons", "buttons", "the GPIO buttons: device and which are pressed now",
               [this](const Args&, Reply& reply) noexcept { buttonsCommand(reply); });
    shell_.add("selftest", "selftest",
               "check camera, display, inputs, state folder and vision assets: PASS/FAIL each",
               [this](const Args&, Reply& reply) noexcept {
                   const int failed = selfTest(reply);
                   reply.printf("selftest: %s\n", failed == 0 ? "all PASS" : "FAILED");
               });
    shell_.add("log", "log [error|warn|info|debug] [N]",
               "the last N log lines (default 20) from memory, or only those at a level or worse",
               logCommand);
    shell_.add("bug-report", "bug-report [PATH]",
               "write a tarball for a developer: version, status, selftest, config, log, "
               "devices, a snapshot, the journal (default: in the state folder)",
               [this](const Args& args, Reply& reply) noexcept { bugReportCommand(args, reply); });
    shell_.add("version", "version", "firmware version and build",
               [](const Args&, Reply& reply) noexcept {
                   reply.printf("mirror %s (built %s %s, %s)\n", MIRROR_VERSION, __DATE__, __TIME__,
                                MIRROR_BUILD_TYPE);
               });
    shell_.add("reboot-mirror", "reboot-mirror",
               "restart the mirror's pipeline (source, vision, display), not the machine",
               [this](const Args&, Reply& reply) noexcept {
                   reply.printf("reboot-mirror: restarting the pipeline\n");
                   restart_ = true;
                   requestStop();
               });
    shell_.add("quit", "quit", "stop the mirror (the service manager may restart it)",
               [this](const Args&, Reply& reply) noexcept {
                   reply.printf("bye\n");
                   requestStop();
               });
}

void FrameLoop::snapshotCommand(Reply& reply) noexcept
{
    if (!display_->requestSnapshot()) {
        reply.printf("error: this display cannot take snapshots\n");
        return;
    }
    snapshotReplyPending_ = true;
    // The display names the file when it writes it (its frame number): say where it will go now,
    // and the whole path once the next frame shown is written.
    const char* dir = display_->outputDir();
    const char* last = display_->lastSnapshot();
    if (*dir)
        reply.printf("snapshot: writing the next frame shown to %s/snapshot-NNNNNN.png\n", dir);
    else if (*last)
        reply.printf("snapshot: writing the next frame shown beside %s\n", last);
    else
        reply.printf("snapshot: writing the next frame shown\n");
}

void FrameLoop::formatStatus(Reply& reply) const noexcept
{
    reply.printf("uptime %.1f s, frames %llu, fps %.1f, bad frames %llu\n", uptimeSeconds(),
                 static_cast<unsigned long long>(framesShown_), fps_,
                 static_cast<unsigned long long>(badFrames_));
    reply.printf("source: %s%s\n", source_->description(), sourceLost_ ? " [LOST]" : "");
    reply.printf("display: %s%s\n", display_->description(), displayDown_ ? " [UNAVAILABLE]" : "");
    if (card_)
        reply.printf("card: %s\n", vision::cardStateName(card_->state()));
    if (faces_)
        reply.printf("faces: %d shown\n", faces_->shown());
    if (overlays_)
        overlays_->formatStatus(state_.faces, reply);
    if (people_)
        people_->formatStatus(state_.faces, reply);
    reply.printf("%-14s %8s %8s %8s\n", "stage", "p50 ms", "p99 ms", "mean ms");
    for (std::size_t i = 0; i < stepCount_; ++i) {
        const LatencyHistogram& h = timings_[i].total;
        reply.printf("%-14s %8.2f %8.2f %8.2f\n", timings_[i].name, h.percentileMs(0.5),
                     h.percentileMs(0.99), h.meanMs());
    }
}

void FrameLoop::formatStatusJson(Reply& reply) const noexcept
{
    // One line, keys in a fixed order; times in seconds and milliseconds as the text says.
    reply.printf(
        "{\"version\":\"%s\",\"uptime_s\":%.1f,\"frames\":%llu,\"fps\":%.1f,"
        "\"bad_frames\":%llu,\"source\":{\"description\":",
        MIRROR_VERSION, uptimeSeconds(), static_cast<unsigned long long>(framesShown_), fps_,
        static_cast<unsigned long long>(badFrames_));
    jsonString(reply, source_->description());
    reply.printf(",\"lost\":%s,\"error\":", sourceLost_ ? "true" : "false");
    jsonString(reply, sourceLost_ ? source_->lastError() : "");
    reply.append("},\"display\":{\"description\":");
    jsonString(reply, display_->description());
    reply.printf(",\"width\":%d,\"height\":%d,\"unavailable\":%s,\"error\":", display_->width(),
                 display_->height(), displayDown_ ? "true" : "false");
    jsonString(reply, displayDown_ ? display_->lastError() : "");
    reply.append("}");
    if (card_)
        reply.printf(",\"card\":{\"state\":\"%s\",\"confidence\":%.2f}",
                     vision::cardStateName(card_->state()),
                     static_cast<double>(card_->confidence()));
    if (faces_)
        reply.printf(",\"faces\":{\"shown\":%d}", faces_->shown());
    if (people_)
        people_->formatJson(state_.faces, reply);
    reply.append(",\"stages\":[");
    for (std::size_t i = 0; i < stepCount_; ++i) {
        const LatencyHistogram& h = timings_[i].total;
        reply.printf("%s{\"name\":\"%s\",\"p50_ms\":%.3f,\"p99_ms\":%.3f,\"mean_ms\":%.3f}",
                     i ? "," : "", timings_[i].name, h.percentileMs(0.5), h.percentileMs(0.99),
                     h.meanMs());
    }
    reply.append("]}\n");
}

void FrameLoop::buttonsCommand(Reply& reply) noexcept
{
    if (!buttons_) {
        reply.printf(
            "buttons: none (disabled, or the GPIO chip was unavailable "
            "at start: see `log`)\n");
        return;
    }
    bool pressed[16] = {};
    const int n = buttons_->readPressed(pressed, 16);
    reply.printf("buttons: %s%s\n", buttons_->description(), buttonsFailed_ ? " [FAILED]" : "");
    for (int i = 0; i < n; ++i)
        reply.printf("button %d: %s\n", i + 1, pressed[i] ? "pressed" : "up");
    if (n < 0)
        reply.printf("error: %s\n", buttons_->lastError());
}

}  // namespace firmware
