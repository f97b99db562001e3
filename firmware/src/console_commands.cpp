// FrameLoop's console: the commands the diagnostics shell serves on stdin and the serial port,
// each on the same paths as the buttons; `status` here, `selftest` in self_test.cpp.
#include "card_control.hpp"
#include "face_control.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "overlay_control.hpp"

#include <algorithm>
#include <charconv>
#include <system_error>

namespace firmware {

namespace {

void logCommand(const Args& args, Reply& reply) noexcept
{
    int n = 20;
    if (args.size() == 2) {
        int v = 0;
        const auto [end, ec] = std::from_chars(args[1].data(), args[1].data() + args[1].size(), v);
        if (ec != std::errc() || end != args[1].data() + args[1].size()) {
            reply.printf("error: usage: log [N]\n");
            return;
        }
        n = std::clamp(v, 1, kLogRingLines);
    } else if (args.size() > 2) {
        reply.printf("error: usage: log [N]\n");
        return;
    }
    forEachRecentLogLine(
        n, [](const char* line, void* context) { static_cast<Reply*>(context)->append(line); },
        &reply);
}

}  // namespace

void FrameLoop::registerCommands()
{
    shell_.add("status", "status", "uptime, frames, fps, per-stage p50/p99 ms, source, display",
               [this](const Args&, Reply& reply) noexcept { formatStatus(reply); });
    shell_.add("snapshot", "snapshot", "write a PNG of the next frame shown",
               [this](const Args&, Reply& reply) noexcept {
                   if (display_->requestSnapshot()) {
                       snapshotReplyPending_ = true;
                       reply.printf("snapshot: requested\n");
                   } else {
                       reply.printf("error: this display cannot take snapshots\n");
                   }
               });
    shell_.add("config", "config", "print the effective configuration (TOML)",
               [this](const Args&, Reply& reply) noexcept {
                   reply.printf("# from %s\n%s", config_.origin.c_str(), configToml_.c_str());
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
                   [this](const Args&, Reply& reply) noexcept { faces_->format(reply); });
        shell_.add("debug", "debug [on|off]",
                   "show or hide the face debug HUD (boxes, corners, roll)",
                   [this](const Args& args, Reply& reply) noexcept {
                       if (args.size() == 2 && (args[1] == "on" || args[1] == "off")) {
                           setDebugHud(args[1] == "on");
                       } else if (args.size() != 1) {
                           reply.printf("error: usage: debug [on|off]\n");
                           return;
                       }
                       reply.printf("debug: %s\n", debugHud() ? "on" : "off");
                   });
    }
    shell_.add("overlay", "overlay [next|prev|off|list|NAME|mode global|per_face]",
               "what the faces wear: show, change, list the catalogue, global or per-face choice",
               [this](const Args& args, Reply& reply) noexcept {
                   overlays_->command(args, state_.faces, reply);
               });
    shell_.add("buttons", "buttons", "the GPIO buttons: device and which are pressed now",
               [this](const Args&, Reply& reply) noexcept { buttonsCommand(reply); });
    shell_.add("selftest", "selftest",
               "check camera, display, inputs, state folder and vision assets: PASS/FAIL each",
               [this](const Args&, Reply& reply) noexcept {
                   const int failed = selfTest(reply);
                   reply.printf("selftest: %s\n", failed == 0 ? "all PASS" : "FAILED");
               });
    shell_.add("log", "log [N]", "the last N log lines (default 20) from memory", logCommand);
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
    reply.printf("%-14s %8s %8s %8s\n", "stage", "p50 ms", "p99 ms", "mean ms");
    for (std::size_t i = 0; i < stepCount_; ++i) {
        const LatencyHistogram& h = timings_[i].total;
        reply.printf("%-14s %8.2f %8.2f %8.2f\n", timings_[i].name, h.percentileMs(0.5),
                     h.percentileMs(0.99), h.meanMs());
    }
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
