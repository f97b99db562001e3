// FrameLoop's `selftest`: one PASS/FAIL/SKIP line per check of camera, display, state folder,
// vision assets, overlays and the GPIO buttons.
#include "firmware/frame_loop.hpp"
#include "face_control.hpp"
#include "monotonic_clock.hpp"
#include "overlay_control.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace firmware {

namespace {

/// The state folder: create, write, sync and remove a probe file (what the stores do). False when
/// that failed; `error` is errno as the open left it.
bool probeWritable(const std::string& dir, int& error) noexcept
{
    char path[1024];
    std::snprintf(path, sizeof path, "%s/.selftest-%d", dir.c_str(), static_cast<int>(::getpid()));
    const int fd = ::open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    bool writable = fd >= 0;
    error = errno;
    if (fd >= 0) {
        writable = ::write(fd, "ok\n", 3) == 3 && ::fsync(fd) == 0;
        ::close(fd);
        ::unlink(path);
    }
    return writable;
}

}  // namespace

int FrameLoop::selfTest(Reply& reply) const noexcept
{
    int failed = 0;
    auto check = [&](bool ok, const char* name, const char* format, auto... args) {
        char detail[256];
        std::snprintf(detail, sizeof detail, format, args...);
        reply.printf("%s %s: %s\n", ok ? "PASS" : "FAIL", name, detail);
        failed += !ok;
    };
    const std::int64_t now = monotonicNs();
    // A live camera delivers within 2 s, or within a few of its own frame intervals when the
    // whole loop is slower than that (an emulated machine, a first frame's shader compiles).
    const std::int64_t kRecent = std::max<std::int64_t>(2'000'000'000, 4 * frameIntervalNs_);
    const bool frames = lastFrameNs_ != 0 && now - lastFrameNs_ < kRecent && !sourceLost_;
    check(frames, "camera", "%s, %s", source_->description(),
          frames        ? "delivering frames"
          : sourceLost_ ? (*source_->lastError() ? source_->lastError() : "lost")
                        : "no recent frame");
    const bool shown = lastPresentNs_ != 0 && now - lastPresentNs_ < kRecent && !displayDown_;
    check(shown, "display", "%s, %dx%d, %s", display_->description(), display_->width(),
          display_->height(),
          shown                    ? "showing frames"
          : *display_->lastError() ? display_->lastError()
                                   : "no frame shown recently");

    int error = 0;
    const bool writable = probeWritable(config_.state.dir, error);
    check(writable, "state", "%s %s", config_.state.dir.c_str(),
          writable ? "writable" : std::strerror(error));
    if (config_.faces.enabled)
        check(faces_ != nullptr, "faces", "cascade %s loaded", config_.faces.cascade.c_str());
    else
        reply.printf("SKIP faces: disabled in the config\n");
    if (config_.faces.enabled && !config_.faces.model.empty()) {
        const bool loaded = faces_ != nullptr && faces_->aamLoaded();
        check(loaded, "aam", "model %s %s", config_.faces.model.c_str(),
              loaded ? "loaded" : "not loaded, faces keep the 2D pose (the log says why)");
    } else {
        reply.printf("SKIP aam: no model in the config (faces.model)\n");
    }
    if (config_.faces.enabled && config_.overlay.enabled) {
        const OverlaySelection* selection = overlays_->selection();
        const std::string& problem = overlays_->problem();
        check(selection != nullptr, "overlays", "%d loaded%s%.200s",
              selection ? selection->size() : 0, problem.empty() ? "" : ": ", problem.c_str());
    } else {
        reply.printf("SKIP overlays: disabled in the config\n");
    }
    if (!config_.buttons.enabled) {
        reply.printf("SKIP gpio: buttons disabled in the config\n");
    } else {
        bool pressed[16] = {};
        const int n = buttons_ ? buttons_->readPressed(pressed, 16) : -1;
        check(n > 0 && !buttonsFailed_, "gpio", "%s%s%s", buttons_ ? buttons_->description() : "",
              n > 0 ? ", lines readable" : (buttons_ ? ": " : "no buttons: chip unavailable"),
              n > 0 ? "" : (buttons_ ? buttons_->lastError() : ""));
    }
    return failed;
}

}  // namespace firmware
