#include "firmware/frame_loop.hpp"

#include "firmware/exit_codes.hpp"
#include "firmware/log.hpp"
#include "vision/chromaticity_stage.hpp"
#include "vision/frame_check_stage.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <thread>

namespace firmware {

namespace {

std::int64_t nowNs() noexcept
{
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

render::RendererOptions rendererOptions(const DisplayConfig& d)
{
    render::RendererOptions o;
    o.mirror = d.mirror;
    o.fit = d.fit == DisplayConfig::Fit::Cover ? render::Fit::Cover : render::Fit::Contain;
    o.hud = d.hud;
    return o;
}

// While the source is lost, poll it at this pace so the console stays responsive and the CPU idle.
constexpr auto kLostRetry = std::chrono::milliseconds(50);

}  // namespace

FrameLoop::FrameLoop(const Config& config, std::unique_ptr<platform::FrameSource> source,
                     std::unique_ptr<platform::Display> display)
    : config_(config),
      configToml_(toToml(config)),
      source_(std::move(source)),
      display_(std::move(display)),
      shell_(config.console.maxLineLength)
{
    const vision::Size size = source_->size();
    const vision::PixelFormat format = source_->format();

    pipeline_.add(std::make_unique<vision::FrameCheckStage>(size, format));
    if (config.vision.chromaticity)
        pipeline_.add(std::make_unique<vision::ChromaticityStage>(size));

    // The renderer's GL objects belong to the display's context: make it current first.
    if (!display_->beginFrame())
        throw std::runtime_error(std::string("display: ") + display_->lastError());
    renderer_ = std::make_unique<render::Renderer>(size, format, rendererOptions(config.display));

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
    registerCommands();
}

FrameLoop::~FrameLoop()
{
    if (summaryFd_ >= 0)
        ::close(summaryFd_);
    // The renderer's GL objects must go while the display's context still exists.
    if (renderer_ && display_->beginFrame())
        renderer_.reset();
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
    const char* why = stop_.load()   ? "stop requested"
                      : sourceEnded_ ? "end of source"
                                     : "frame limit reached";
    MIRROR_LOG_INFO("stopped (%s) after %llu frames, %.1f s", why,
                    static_cast<unsigned long long>(framesShown_), uptimeSeconds());
    return kExitOk;
}

bool FrameLoop::step() noexcept
{
    const std::int64_t t0 = nowNs();
    if (startNs_ == 0)
        startNs_ = intervalStartNs_ = t0;
    // A console whose input closed (stdin at EOF) is let go, so it costs nothing per frame.
    if (console_ && shell_.poll(*console_).closed)
        console_ = nullptr;
    if (stop_.load())
        return false;

    const platform::SourceStatus status = source_->next(frame_);
    const std::int64_t t1 = nowNs();
    noteSourceStatus(status);
    if (status == platform::SourceStatus::EndOfStream) {
        sourceEnded_ = true;
        return false;
    }
    if (status == platform::SourceStatus::Lost) {
        ++lostPolls_;
        std::this_thread::sleep_for(kLostRetry);
        updateRate(nowNs());
        return true;
    }
    const std::int64_t waited = std::clamp<std::int64_t>(source_->lastWaitNs(), 0, t1 - t0);
    record(kWaitStep, waited);
    record(kCaptureStep, t1 - t0 - waited);

    // Vision stages, timed one by one.
    vision::Pipeline::begin(state_, frame_);
    std::int64_t t = t1;
    for (std::size_t i = 0; i < pipeline_.size() && state_.valid; ++i) {
        pipeline_.stage(i).process(state_);
        const std::int64_t after = nowNs();
        record(kFirstVisionStep + i, after - t);
        t = after;
    }
    if (!state_.valid) {
        ++badFrames_;
        if (!frameBad_)
            MIRROR_LOG_WARN("frame %llu skipped: %s",
                            static_cast<unsigned long long>(frame_.sequence), state_.problem);
        frameBad_ = true;
        updateRate(nowNs());
        return true;
    }
    if (frameBad_)
        MIRROR_LOG_INFO("frames are good again");
    frameBad_ = false;

    // Render and present.
    if (!display_->beginFrame()) {
        if (!displayDown_)
            MIRROR_LOG_WARN("display unavailable: %s", display_->lastError());
        displayDown_ = true;
        updateRate(nowNs());
        return true;
    }
    formatHud();
    if (!renderer_->draw(frame_.image, display_->width(), display_->height(), hud_))
        MIRROR_LOG_WARN("render: %s", renderer_->lastError());
    const std::int64_t t2 = nowNs();
    record(renderStep_, t2 - t);
    const bool presented = display_->present();
    const std::int64_t t3 = nowNs();
    record(presentStep_, t3 - t2);
    if (!presented) {
        if (!displayDown_)
            MIRROR_LOG_WARN("display: %s", display_->lastError());
        displayDown_ = true;
    } else {
        if (displayDown_)
            MIRROR_LOG_INFO("display is back");
        displayDown_ = false;
        ++framesShown_;
        ++intervalFrames_;
    }
    if (snapshotReplyPending_ && console_) {
        char line[512];
        std::snprintf(line, sizeof line, "snapshot: %s\n",
                      *display_->lastSnapshot() ? display_->lastSnapshot() : display_->lastError());
        console_->write(line);
        snapshotReplyPending_ = false;
    }
    updateRate(t3);
    return true;
}

void FrameLoop::noteSourceStatus(platform::SourceStatus status) noexcept
{
    const bool lost = status == platform::SourceStatus::Lost;
    if (lost && !sourceLost_)
        MIRROR_LOG_WARN("source lost: %s (retrying)", source_->lastError());
    else if (!lost && sourceLost_)
        MIRROR_LOG_INFO("source is back: %s", source_->description());
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
    MIRROR_LOG_INFO("%s", line);
    if (summaryFd_ >= 0) {
        const std::size_t len = std::strlen(line);
        line[len] = '\n';
        [[maybe_unused]] const ssize_t w = ::write(summaryFd_, line, len + 1);
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
    std::snprintf(hud_, sizeof hud_, "%.1f fps  frame %llu\nvision %.2f ms  render %.2f ms", fps_,
                  static_cast<unsigned long long>(framesShown_), visionMs,
                  timings_[renderStep_].interval.meanMs());
}

void FrameLoop::formatStatus(Reply& reply) const noexcept
{
    reply.printf("uptime %.1f s, frames %llu, fps %.1f, bad frames %llu\n", uptimeSeconds(),
                 static_cast<unsigned long long>(framesShown_), fps_,
                 static_cast<unsigned long long>(badFrames_));
    reply.printf("source: %s%s\n", source_->description(), sourceLost_ ? " [LOST]" : "");
    reply.printf("display: %s%s\n", display_->description(), displayDown_ ? " [UNAVAILABLE]" : "");
    reply.printf("%-14s %8s %8s %8s\n", "stage", "p50 ms", "p99 ms", "mean ms");
    for (std::size_t i = 0; i < stepCount_; ++i) {
        const LatencyHistogram& h = timings_[i].total;
        reply.printf("%-14s %8.2f %8.2f %8.2f\n", timings_[i].name, h.percentileMs(0.5),
                     h.percentileMs(0.99), h.meanMs());
    }
}

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
    shell_.add("quit", "quit", "stop the mirror (the service manager may restart it)",
               [this](const Args&, Reply& reply) noexcept {
                   reply.printf("bye\n");
                   requestStop();
               });
}

}  // namespace firmware
