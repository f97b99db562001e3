#include "firmware/frame_loop.hpp"

#include "firmware/exit_codes.hpp"
#include "firmware/log.hpp"
#include "platform/image_file.hpp"
#include "render/default_card_picture.hpp"
#include "vision/chromaticity_stage.hpp"
#include "vision/deinterlace_stage.hpp"
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
    buildPipeline(size, format);

    // The renderer's GL objects belong to the display's context: make it current first.
    if (!display_->beginFrame())
        throw std::runtime_error(std::string("display: ") + display_->lastError());
    renderer_ = std::make_unique<render::Renderer>(size, format, rendererOptions(config.display));
    if (cardStage_)
        setUpCard(size);

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

void FrameLoop::buildPipeline(vision::Size size, vision::PixelFormat format)
{
    pipeline_.add(std::make_unique<vision::FrameCheckStage>(size, format));
    if (config_.vision.deinterlace)
        pipeline_.add(std::make_unique<vision::DeinterlaceStage>(size, format));
    // The card's colour test works on chromaticity (ch. 3): the tracker needs the planes.
    if (config_.vision.chromaticity || config_.card.enabled)
        pipeline_.add(std::make_unique<vision::ChromaticityStage>(size));
    if (config_.card.enabled) {
        vision::CardTrackerOptions options;
        options.threshold = static_cast<float>(config_.card.threshold);
        options.alpha = static_cast<float>(config_.card.alpha);
        options.beta = static_cast<float>(config_.card.beta);
        auto stage = std::make_unique<vision::CardStage>(size, options);
        cardStage_ = stage.get();
        pipeline_.add(std::move(stage));
    }
}

void FrameLoop::setUpCard(vision::Size size)
{
    // The trained colour survives restarts; a corrupt file is reported and ignored.
    cardStore_ = std::make_unique<CardModelStore>(config_.state.dir);
    if (!cardStore_->usable())
        MIRROR_LOG_WARN("card: %s; a trained colour will not be kept across restarts",
                        cardStore_->lastError());
    std::string warning;
    if (const auto model = cardStore_->load(warning)) {
        cardStage_->tracker().setModel(*model);
        MIRROR_LOG_INFO("card: colour loaded from %s", cardStore_->path().c_str());
    } else if (!warning.empty()) {
        MIRROR_LOG_WARN("card: %s", warning.c_str());
    } else {
        MIRROR_LOG_INFO(
            "card: not trained yet (console: card train, with the card filling the "
            "middle of the view)");
    }

    // The picture: the configured file, else the built-in one; a file that cannot be read is
    // reported and the card's outline is drawn instead, so tracking still shows.
    vision::ImageBuffer picture;
    if (config_.card.picture.empty()) {
        picture = render::defaultCardPicture({640, 452});
    } else {
        try {
            picture = platform::loadImageFile(config_.card.picture, "card picture");
        } catch (const std::exception& e) {
            MIRROR_LOG_ERROR("%s; drawing the card's outline instead", e.what());
        }
    }
    const vision::ConstImageView view =
        picture.empty() ? vision::ConstImageView{} : vision::ConstImageView(picture.view());
    cardLayer_ = std::make_unique<render::CardPictureLayer>(view, size);
    renderer_->addLayer(cardLayer_.get());
}

FrameLoop::~FrameLoop()
{
    if (summaryFd_ >= 0)
        ::close(summaryFd_);
    // GL objects must go while the display's context still exists.
    if (renderer_ && display_->beginFrame()) {
        cardLayer_.reset();
        renderer_.reset();
    }
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
    if (cardStage_) {
        if (cardTrainPending_ && !cardStage_->trainingPending())
            reportCardTraining();
        noteCardState();
        cardLayer_->update(state_.card);
    }

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

void FrameLoop::requestCardTraining() noexcept
{
    // Step 1 of 4.2: the card stage learns the colour from the centre of the next good frame
    // (the card held there), the same way mirror-eval trains it.
    if (!cardStage_)
        return;
    cardStage_->requestTraining(static_cast<float>(config_.card.trainFraction));
    cardTrainPending_ = true;
}

void FrameLoop::reportCardTraining() noexcept
{
    cardTrainPending_ = false;
    const double f = config_.card.trainFraction;
    char line[640];
    const vision::CardTracker& tracker = cardStage_->tracker();
    if (!cardStage_->lastTrainingSucceeded()) {
        std::snprintf(line, sizeof line,
                      "card: training failed (no usable pixels in the centre)\n");
    } else {
        const vision::CardColorModel& m = tracker.trainedModel();
        const bool saved = cardStore_ && cardStore_->save(m);
        std::snprintf(line, sizeof line,
                      "card: trained on the central %.0f%% (r %.1f g %.1f b %.1f, sigma %.1f %.1f "
                      "%.1f), %s %.400s\n",
                      f * 100, static_cast<double>(m.mean[0]), static_cast<double>(m.mean[1]),
                      static_cast<double>(m.mean[2]), static_cast<double>(m.sigma[0]),
                      static_cast<double>(m.sigma[1]), static_cast<double>(m.sigma[2]),
                      saved ? "saved to" : "NOT saved:",
                      saved ? cardStore_->path().c_str()
                            : (cardStore_ ? cardStore_->lastError() : "no state folder"));
    }
    MIRROR_LOG_INFO("%.*s", static_cast<int>(std::strlen(line)) - 1, line);
    if (console_)
        console_->write(line);
}

void FrameLoop::noteCardState() noexcept
{
    const vision::CardState now =
        state_.card ? state_.card->state : cardStage_->tracker().observation().state;
    if (now != cardState_)
        MIRROR_LOG_INFO("card: %s -> %s", vision::cardStateName(cardState_),
                        vision::cardStateName(now));
    cardState_ = now;
}

void FrameLoop::formatCard(Reply& reply) const noexcept
{
    const vision::CardTracker& tracker = cardStage_->tracker();
    const vision::CardObservation& o = tracker.observation();
    reply.printf("card: %s, confidence %.2f, area %d px\n", vision::cardStateName(o.state),
                 static_cast<double>(o.confidence), o.area);
    if (o.hasQuad)
        reply.printf("corners: (%.1f, %.1f) (%.1f, %.1f) (%.1f, %.1f) (%.1f, %.1f)\n",
                     static_cast<double>(o.quad[0].x), static_cast<double>(o.quad[0].y),
                     static_cast<double>(o.quad[1].x), static_cast<double>(o.quad[1].y),
                     static_cast<double>(o.quad[2].x), static_cast<double>(o.quad[2].y),
                     static_cast<double>(o.quad[3].x), static_cast<double>(o.quad[3].y));
    const vision::CardColorModel& m = tracker.trainedModel();
    if (m.valid)
        reply.printf("colour: r %.1f g %.1f b %.1f, sigma %.1f %.1f %.1f (%s)\n",
                     static_cast<double>(m.mean[0]), static_cast<double>(m.mean[1]),
                     static_cast<double>(m.mean[2]), static_cast<double>(m.sigma[0]),
                     static_cast<double>(m.sigma[1]), static_cast<double>(m.sigma[2]),
                     cardStore_ ? cardStore_->path().c_str() : "not kept");
    else
        reply.printf("colour: not trained (card train)\n");
    reply.printf("picture: %s\n",
                 cardLayer_->outlineMode() ? "none (drawing the outline)" : "shown on the card");
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
    const int n =
        std::snprintf(hud_, sizeof hud_, "%.1f fps  frame %llu\nvision %.2f ms  render %.2f ms",
                      fps_, static_cast<unsigned long long>(framesShown_), visionMs,
                      timings_[renderStep_].interval.meanMs());
    if (cardStage_ && n > 0 && n < static_cast<int>(sizeof hud_))
        std::snprintf(hud_ + n, sizeof hud_ - static_cast<std::size_t>(n), "\ncard %s %.2f",
                      vision::cardStateName(cardState_),
                      static_cast<double>(cardStage_->tracker().observation().confidence));
}

void FrameLoop::formatStatus(Reply& reply) const noexcept
{
    reply.printf("uptime %.1f s, frames %llu, fps %.1f, bad frames %llu\n", uptimeSeconds(),
                 static_cast<unsigned long long>(framesShown_), fps_,
                 static_cast<unsigned long long>(badFrames_));
    reply.printf("source: %s%s\n", source_->description(), sourceLost_ ? " [LOST]" : "");
    reply.printf("display: %s%s\n", display_->description(), displayDown_ ? " [UNAVAILABLE]" : "");
    if (cardStage_)
        reply.printf("card: %s\n", vision::cardStateName(cardState_));
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
    if (cardStage_)
        shell_.add("card", "card [train|reset]",
                   "the colour card: state and colour; train on the centre of the next frame; "
                   "forget the track",
                   [this](const Args& args, Reply& reply) noexcept {
                       if (args.size() == 1) {
                           formatCard(reply);
                       } else if (args[1] == "train" && args.size() == 2) {
                           requestCardTraining();
                           reply.printf(
                               "card: hold the card in the middle of the view; training "
                               "on the next frame\n");
                       } else if (args[1] == "reset" && args.size() == 2) {
                           cardStage_->tracker().reset();
                           reply.printf("card: track reset, searching\n");
                       } else {
                           reply.printf("error: usage: card [train|reset]\n");
                       }
                   });
    shell_.add("quit", "quit", "stop the mirror (the service manager may restart it)",
               [this](const Args&, Reply& reply) noexcept {
                   reply.printf("bye\n");
                   requestStop();
               });
}

}  // namespace firmware
