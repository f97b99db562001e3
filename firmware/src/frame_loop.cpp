#include "firmware/frame_loop.hpp"

#include "bug_report.hpp"
#include "card_control.hpp"
#include "face_control.hpp"
#include "firmware/exit_codes.hpp"
#include "firmware/log.hpp"
#include "monotonic_clock.hpp"
#include "overlay_control.hpp"
#include "people_control.hpp"
#include "pipeline_builder.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace firmware {

namespace {

render::RendererOptions rendererOptions(const DisplayConfig& d)
{
    render::RendererOptions o;
    o.mirror = d.mirror;
    o.fit = d.fit == DisplayConfig::Fit::Cover ? render::Fit::Cover : render::Fit::Contain;
    o.hud = d.hud;
    o.rotation = d.rotation;
    return o;
}

// While the source is lost, poll it at this pace so the console stays responsive and the CPU idle.
constexpr auto kLostRetry = std::chrono::milliseconds(50);
constexpr const char* kCalmScreen = "camera unavailable\nreconnecting ...";

}  // namespace

FrameLoop::FrameLoop(const Config& config, std::unique_ptr<platform::FrameSource> source,
                     std::unique_ptr<platform::Display> display)
    : config_(config),
      configToml_(toToml(config)),
      source_(std::move(source)),
      display_(std::move(display)),
      shell_(ShellOptions{
          .maxLineLength = static_cast<std::size_t>(config.console.maxLineLength),
          // The longest reply: the whole config, or the whole log ring.
          .replyCapacity = std::max(Reply::kDefaultCapacity, configToml_.size() + 4096)})
{
    const vision::Size size = source_->size();
    const vision::PixelFormat format = source_->format();
    const VisionStages stages = buildPipeline(config_, size, format, pipeline_);

    // The renderer's GL objects belong to the display's context: make it current first. The
    // layers are drawn in the order they are made: the card's picture, overlays, the debug HUD.
    if (!display_->beginFrame())
        throw std::runtime_error(std::string("display: ") + display_->lastError());
    renderer_ = std::make_unique<render::Renderer>(size, format, rendererOptions(config.display));
    if (stages.card)
        card_ = std::make_unique<CardControl>(config_, *stages.card, *renderer_, size);
    overlays_ =
        std::make_unique<OverlayControl>(config_, stages.faces, *renderer_, *display_, size);
    if (stages.faces)
        faces_ = std::make_unique<FaceControl>(*stages.motion, *stages.faces, stages.aam,
                                               *renderer_, config.display.debug);
    if (stages.faces && config.people.enabled)
        people_ = std::make_unique<PeopleControl>(config_, stages.aam, stages.modelId,
                                                  overlays_->selection());

    timings_[stepCount_++].name = "wait";
    timings_[stepCount_++].name = "capture";
    for (std::size_t i = 0; i < pipeline_.size(); ++i)
        timings_[stepCount_++].name = pipeline_.stage(i).name();
    renderStep_ = stepCount_;
    timings_[stepCount_++].name = "render";
    presentStep_ = stepCount_;
    timings_[stepCount_++].name = "present";

    // Displays with an output folder (headless) also keep the one-line summaries there.
    if (*display_->outputDir()) {
        const std::string path = std::string(display_->outputDir()) + "/summary.log";
        summaryFd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (summaryFd_ < 0)
            throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    }
    for (const std::size_t capacity :
         {std::size_t{16384}, std::size_t{16384}, std::size_t{16384}, configToml_.size() + 4096,
          std::size_t{kLogRingLines} * 512 + 1024})
        bugTexts_.emplace_back(capacity);
    bugReports_ = std::make_unique<BugReportWorker>();
    registerCommands();
}

FrameLoop::~FrameLoop()
{
    if (summaryFd_ >= 0)
        ::close(summaryFd_);
    // GL objects must go while the display's context still exists.
    people_.reset();  // it points at the overlays' selection
    if (renderer_ && display_->beginFrame()) {
        card_.reset();
        overlays_.reset();
        faces_.reset();
        renderer_.reset();
    }
}

const OverlaySelection* FrameLoop::overlaySelection() const noexcept
{
    return overlays_->selection();
}

bool FrameLoop::debugHud() const noexcept
{
    return faces_ && faces_->debugHud();
}

int FrameLoop::run(std::uint64_t maxFrames) noexcept
{
    MIRROR_LOG_INFO("running: source %s, display %s", source_->description(),
                    display_->description());
    while (!stop_.load() && (maxFrames == 0 || framesShown_ < maxFrames)) {
        if (!step())
            break;
    }
    writeSummary();
    if (!restart_ && !processRestart_)
        notifier_.stopping();
    const char* why = processRestart_ ? "the source needs a new process"
                      : stop_.load()  ? "stop requested"
                      : sourceEnded_  ? "end of source"
                                      : "frame limit reached";
    MIRROR_LOG_INFO("stopped (%s) after %llu frames, %.1f s", why,
                    static_cast<unsigned long long>(framesShown_), uptimeSeconds());
    return processRestart_ ? kExitSource : kExitOk;
}

bool FrameLoop::step() noexcept
{
    const std::int64_t start = startIteration();
    if (!serveConsoles())  // 1. console
        return false;
    const platform::SourceStatus status = capture(start);  // 2. wait, capture
    if (status == platform::SourceStatus::EndOfStream)
        return false;
    if (status == platform::SourceStatus::Lost)
        return waitForSource();
    if (!runVision())  // 3. vision
        return finishIteration(monotonicNs());
    handleInputsAndOverlays();  // 4. inputs and overlays
    if (!render())              // 5. render
        return finishIteration(monotonicNs());
    const std::int64_t presentedNs = present();  // 6. present
    return finishIteration(presentedNs);         // 7. stats
}

std::int64_t FrameLoop::startIteration() noexcept
{
    const std::int64_t now = monotonicNs();
    if (intervalStartNs_ == 0)
        intervalStartNs_ = now;
    notifier_.pingWatchdog(now);
    return now;
}

bool FrameLoop::serveConsoles() noexcept
{
    // A console whose input closed (stdin at EOF) is let go, so it costs nothing per frame.
    for (std::size_t c = 0; c < consoles_.size(); ++c)
        if (consoles_[c] && shell_.poll(*consoles_[c], c).closed)
            consoles_[c] = nullptr;
    return !stop_.load();
}

platform::SourceStatus FrameLoop::capture(std::int64_t start) noexcept
{
    const platform::SourceStatus status = source_->next(frame_);
    capturedNs_ = monotonicNs();
    noteSourceStatus(status);
    if (status == platform::SourceStatus::EndOfStream)
        sourceEnded_ = true;
    if (status != platform::SourceStatus::Ok)
        return status;
    if (lastFrameNs_ != 0)  // slow average of the time between frames, for `selftest`
        frameIntervalNs_ += (capturedNs_ - lastFrameNs_ - frameIntervalNs_) / 8;
    lastFrameNs_ = capturedNs_;
    const std::int64_t waited =
        std::clamp<std::int64_t>(source_->lastWaitNs(), 0, capturedNs_ - start);
    record(kWaitStep, waited);
    record(kCaptureStep, capturedNs_ - start - waited);
    return status;
}

/// The source is lost: the calm screen, a short sleep, and the questions only the source can
/// answer (a new process, or a new pipeline for the size it came back with).
bool FrameLoop::waitForSource() noexcept
{
    if (source_->needsProcessRestart()) {
        // libcamera 0.0.3 cannot let go of a camera that vanished without killing the process:
        // stop now, and let main leave at once for the service manager to start a fresh one.
        MIRROR_LOG_ERROR("camera vanished; libcamera needs a new process: exiting for restart");
        processRestart_ = true;
        requestStop();
        return false;
    }
    if (source_->needsPipelineRebuild() && !restart_) {
        MIRROR_LOG_WARN("camera is back with another size or format: rebuilding the pipeline");
        restart_ = true;
        requestStop();
    }
    showSourceLost(capturedNs_);
    std::this_thread::sleep_for(kLostRetry);
    return finishIteration(monotonicNs());
}

/// The vision stages, timed one by one; false for a frame they rejected (skipped).
bool FrameLoop::runVision() noexcept
{
    vision::Pipeline::begin(state_, frame_);
    std::int64_t t = capturedNs_;
    for (std::size_t i = 0; i < pipeline_.size() && state_.valid; ++i) {
        pipeline_.stage(i).process(state_);
        const std::int64_t after = monotonicNs();
        record(kFirstVisionStep + i, after - t);
        t = after;
    }
    visionEndNs_ = t;
    if (!state_.valid) {
        ++badFrames_;
        if (!frameBad_)
            MIRROR_LOG_WARN("frame %llu skipped: %s",
                            static_cast<unsigned long long>(frame_.sequence), state_.problem);
        frameBad_ = true;
        return false;
    }
    if (frameBad_)
        MIRROR_LOG_INFO("frames are good again");
    frameBad_ = false;
    noteVisionResults();
    return true;
}

/// A finished card training reported, card and face changes logged once, the debug HUD fed.
void FrameLoop::noteVisionResults() noexcept
{
    if (card_)
        if (const char* report = card_->update(state_))
            tellConsoles(report);
    if (faces_)
        faces_->update(state_.faces, state_.fits);
}

void FrameLoop::handleInputsAndOverlays() noexcept
{
    pollButtons();
    pollKeys();
    // Who the faces are, before the overlays decide what they wear.
    if (people_)
        if (const char* report = people_->update(state_.faces, state_.fits, monotonicNs()))
            tellConsoles(report);
    // Fades and smoothing run on the loop's clock: what the viewer sees is wall time.
    overlays_->update(state_.faces, state_.fits, monotonicNs());
}

bool FrameLoop::render() noexcept
{
    if (!display_->beginFrame()) {
        if (!displayDown_)
            MIRROR_LOG_WARN("display unavailable: %s", display_->lastError());
        displayDown_ = true;
        return false;
    }
    formatHud();
    // A GL error usually repeats every frame: one line when it starts, one when it ends.
    if (!renderer_->draw(frame_.image, display_->width(), display_->height(), hud_)) {
        if (renderErrorFrames_++ == 0)
            MIRROR_LOG_WARN("render: %s (not repeated while it lasts)", renderer_->lastError());
    } else if (renderErrorFrames_ > 0) {
        MIRROR_LOG_INFO("render: drawing without GL errors again after %llu frames",
                        static_cast<unsigned long long>(renderErrorFrames_));
        renderErrorFrames_ = 0;
    }
    return true;
}

/// Shows the rendered frame; returns when it was done. Tells systemd READY after the first
/// frame shown, and the consoles where an asked-for snapshot went.
std::int64_t FrameLoop::present() noexcept
{
    const std::int64_t t2 = monotonicNs();
    record(renderStep_, t2 - visionEndNs_);
    const bool presented = display_->present();
    const std::int64_t t3 = monotonicNs();
    record(presentStep_, t3 - t2);
    if (!presented) {
        if (!displayDown_)
            MIRROR_LOG_WARN("display: %s", display_->lastError());
        displayDown_ = true;
    } else {
        if (displayDown_)
            MIRROR_LOG_INFO("display is back");
        displayDown_ = false;
        lastPresentNs_ = t3;
        ++framesShown_;
        if (framesShown_ == 1) {
            char ready[160];
            std::snprintf(ready, sizeof ready, "showing the mirror: %.60s on %.60s",
                          source_->description(), display_->description());
            notifier_.ready(ready);
        }
        ++intervalFrames_;
    }
    afterPresent();
    return t3;
}

void FrameLoop::afterPresent() noexcept
{
    if (bugSnapshotWanted_)
        startBugReport(display_->lastSnapshot());
    if (!snapshotReplyPending_)
        return;
    char line[512];
    if (*display_->lastSnapshot())
        std::snprintf(line, sizeof line, "snapshot: wrote %s\n", display_->lastSnapshot());
    else
        std::snprintf(line, sizeof line, "snapshot: failed: %s\n", display_->lastError());
    tellConsoles(line);
    snapshotReplyPending_ = false;
}

bool FrameLoop::finishIteration(std::int64_t now) noexcept
{
    updateRate(now);
    serviceBugReport(now);
    if (deviceWait_ && !restart_ && deviceWait_->poll(now)) {
        MIRROR_LOG_INFO("%s connected: rebuilding the pipeline on it", deviceWait_->found());
        restart_ = true;
        requestStop();
    }
    return true;
}

void FrameLoop::showSourceLost(std::int64_t now) noexcept
{
    // A calm screen instead of a frozen frame, redrawn once a second (a display may lose what it
    // shows, and the headless one keeps snapshots of it).
    if (lostScreenNs_ != 0 && now - lostScreenNs_ < 1'000'000'000)
        return;
    lostScreenNs_ = now;
    if (!display_->beginFrame())
        return;
    // The calm screen is a frame shown: `selftest` must not blame the display for the camera,
    // and a snapshot asked for meanwhile is of this screen.
    if (renderer_->drawMessage(kCalmScreen, display_->width(), display_->height()) &&
        display_->present()) {
        lastPresentNs_ = monotonicNs();
        afterPresent();
        notifier_.ready("camera unavailable, retrying");  // the mirror runs and says so: ready
    }
}

void FrameLoop::tellConsoles(const char* text) noexcept
{
    for (std::size_t c = 0; c < consoles_.size(); ++c)
        if (consoles_[c])
            shell_.notify(*consoles_[c], c, text);
}

void FrameLoop::noteSourceStatus(platform::SourceStatus status) noexcept
{
    const bool lost = status == platform::SourceStatus::Lost;
    if (lost && !sourceLost_) {
        MIRROR_LOG_WARN("source lost: %s (retrying)", source_->lastError());
        notifier_.status("camera unavailable, retrying");
    } else if (!lost && sourceLost_) {
        MIRROR_LOG_INFO("source is back: %s", source_->description());
        notifier_.status("showing the mirror");
        // The faces tracked before the loss are stale (people left, the camera may have moved):
        // start afresh, with a whole-image scan of the first frame back.
        if (faces_)
            faces_->forgetTracks();
    }
    if (!lost)
        lostScreenNs_ = 0;
    sourceLost_ = lost;
}

void FrameLoop::updateRate(std::int64_t now) noexcept
{
    const double interval = config_.log.summaryIntervalS > 0 ? config_.log.summaryIntervalS : 1.0;
    const double elapsed = static_cast<double>(now - intervalStartNs_) * 1e-9;
    if (elapsed < interval)
        return;
    fps_ = static_cast<double>(intervalFrames_) / elapsed;
    if (config_.log.summaryIntervalS > 0)
        writeSummary();
    for (std::size_t i = 0; i < stepCount_; ++i)
        timings_[i].interval.reset();
    intervalFrames_ = 0;
    intervalStartNs_ = now;
}

/// Whether this summary goes to the log: the first, one whose frame rate moved by a quarter or
/// more since the last logged (a camera lost or back, a stall), else one a minute. The log ring
/// then keeps the causes, not sixty identical lines; summary.log keeps every one.
bool FrameLoop::summaryWorthLogging(std::int64_t nowNs) noexcept
{
    constexpr std::int64_t kQuietNs = 60'000'000'000;
    const bool changed = std::abs(fps_ - loggedFps_) > 0.25 * std::max(loggedFps_, 1.0);
    if (loggedSummaryNs_ != 0 && !changed && nowNs - loggedSummaryNs_ < kQuietNs)
        return false;
    loggedSummaryNs_ = nowNs;
    loggedFps_ = fps_;
    return true;
}

void FrameLoop::writeSummary() noexcept
{
    char line[768];
    int n = std::snprintf(line, sizeof line, "frames=%llu fps=%.1f",
                          static_cast<unsigned long long>(framesShown_), fps_);
    for (std::size_t i = 0; i < stepCount_ && n < static_cast<int>(sizeof line); ++i) {
        const LatencyHistogram& h =
            timings_[i].interval.count() ? timings_[i].interval : timings_[i].total;
        n += std::snprintf(line + n, sizeof line - static_cast<std::size_t>(n), " %s=%.2f/%.2f",
                           timings_[i].name, h.percentileMs(0.5), h.percentileMs(0.99));
    }
    if (n < static_cast<int>(sizeof line))
        std::snprintf(line + n, sizeof line - static_cast<std::size_t>(n), " (p50/p99 ms)");
    logf(summaryWorthLogging(monotonicNs()) ? LogLevel::Info : LogLevel::Debug, "%s", line);
    if (summaryFd_ >= 0) {
        // Bounded: a mirror left running headless must not fill its storage with summaries.
        constexpr std::int64_t kMaxSummaryBytes = 1 << 20;
        if (summaryBytes_ > kMaxSummaryBytes && ::ftruncate(summaryFd_, 0) == 0 &&
            ::lseek(summaryFd_, 0, SEEK_SET) == 0)
            summaryBytes_ = 0;
        const std::size_t len = std::strlen(line);
        line[len] = '\n';
        const ssize_t w = ::write(summaryFd_, line, len + 1);
        summaryBytes_ += w > 0 ? w : 0;
    }
}

void FrameLoop::formatHud() noexcept
{
    if (!renderer_->hudVisible()) {
        hud_[0] = '\0';
        return;
    }
    // Means over the current summary interval: what the frames on screen now cost.
    double visionMs = 0.0;
    for (std::size_t i = kFirstVisionStep; i < renderStep_; ++i)
        visionMs += timings_[i].interval.meanMs();
    const int n =
        std::snprintf(hud_, sizeof hud_, "%.1f fps  frame %llu\nvision %.2f ms  render %.2f ms",
                      fps_, static_cast<unsigned long long>(framesShown_), visionMs,
                      timings_[renderStep_].interval.meanMs());
    int m = n;
    if (card_ && m > 0 && m < static_cast<int>(sizeof hud_))
        m += std::snprintf(hud_ + m, sizeof hud_ - static_cast<std::size_t>(m), "\ncard %s %.2f",
                           vision::cardStateName(card_->state()),
                           static_cast<double>(card_->confidence()));
    if (faces_ && m > 0 && m < static_cast<int>(sizeof hud_))
        std::snprintf(hud_ + m, sizeof hud_ - static_cast<std::size_t>(m), "\nfaces %d",
                      faces_->shown());
}

}  // namespace firmware
