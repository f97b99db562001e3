#include "firmware/frame_loop.hpp"

#include "firmware/exit_codes.hpp"
#include "firmware/log.hpp"
#include "platform/image_file.hpp"
#include "render/default_card_picture.hpp"
#include "vision/chromaticity_stage.hpp"
#include "vision/deinterlace_stage.hpp"
#include "vision/frame_check_stage.hpp"
#include "vision/haar_cascade.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
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

constexpr const char* kTrackingNames[] = {"none", "translation", "similarity", "affine"};
constexpr const char* kFaceStateNames[] = {"tentative", "shown", "missing"};

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
    if (faceStage_ && config.overlay.enabled)
        setUpOverlays(size);
    if (faceStage_) {
        faceDebug_ = std::make_unique<render::FaceDebugLayer>();
        faceDebug_->setVisible(config.display.debug);
        renderer_->addLayer(faceDebug_.get());
    }

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
    if (config_.faces.enabled)
        addFaceStages(size);
}

void FrameLoop::addFaceStages(vision::Size size)
{
    const FacesConfig& c = config_.faces;
    // 5.1: motion at reduced resolution, then detection and tracking on the same grey image.
    vision::MotionStageOptions motion;
    motion.downscale = c.downscale;
    motion.detector.components = c.motionComponents;
    motion.detector.learningRate = static_cast<float>(c.motionLearningRate);
    auto motionStage = std::make_unique<vision::MotionStage>(size, motion);

    vision::FaceTrackerOptions o;
    o.detector.scaleFactor = c.scaleFactor;
    o.detector.minNeighbors = c.minNeighbors;
    o.detector.minSize = {c.minSize, c.minSize};
    switch (c.tracking) {
        case FacesConfig::Tracking::None:
            o.mode = vision::FaceTrackingMode::None;
            break;
        case FacesConfig::Tracking::Translation:
            o.mode = vision::FaceTrackingMode::Translation;
            break;
        case FacesConfig::Tracking::Similarity:
            o.mode = vision::FaceTrackingMode::Similarity;
            break;
        case FacesConfig::Tracking::Affine:
            o.mode = vision::FaceTrackingMode::Affine;
            break;
    }
    o.useMotionMask = c.motionMask;
    o.confirmFrames = c.confirmFrames;
    o.graceFrames = c.graceFrames;
    o.occludedGraceFrames = c.occludedGraceFrames;
    o.maxFaces = c.maxFaces;
    o.detectionWindowBudget = c.detectionBudget;
    o.tiltScanDegrees = static_cast<float>(c.tiltScanDeg);
    o.tiltWindowBudget = c.tiltWindowBudget;
    const double fps = config_.source.fps > 0 ? config_.source.fps : 30.0;
    o.staticDropFrames = static_cast<int>(c.staticDropS * fps + 0.5);
    // The cascade is read once here; a missing or broken file stops start-up with one line.
    const vision::HaarCascade cascade = vision::loadHaarCascade(c.cascade);
    auto faceStage = std::make_unique<vision::FaceStage>(*motionStage, cascade, o);
    motionStage_ = motionStage.get();
    faceStage_ = faceStage.get();
    pipeline_.add(std::move(motionStage));
    pipeline_.add(std::move(faceStage));
    const vision::ConstImageView gray = motionStage_->gray();
    MIRROR_LOG_INFO("faces: %s at %dx%d, tracking %s", c.cascade.c_str(), gray.width, gray.height,
                    kTrackingNames[static_cast<int>(c.tracking)]);
}

static std::string findCatalogue(const std::string& configured)
{
    if (!configured.empty())
        return configured;
    // Installed by the package; else the source tree's (a developer's build).
    for (const char* candidate : {"/usr/share/mirror/overlays/catalogue.toml",
                                  MIRROR_SOURCE_ASSETS "/overlays/catalogue.toml"})
        if (::access(candidate, R_OK) == 0)
            return candidate;
    return "/usr/share/mirror/overlays/catalogue.toml";
}

void FrameLoop::setUpOverlays(vision::Size size)
{
    // A broken catalogue is one error line and a mirror without hats, not a mirror that does not
    // start: the video, the card and the console still work, and `selftest` reports it.
    const std::string path = findCatalogue(config_.overlay.catalogue);
    render::OverlayCatalogue catalogue;
    try {
        catalogue = render::OverlayCatalogue::load(path);
    } catch (const std::exception& e) {
        overlaysProblem_ = e.what();
        MIRROR_LOG_ERROR("%s; running without overlays", e.what());
        return;
    }
    if (catalogue.size() == 0) {
        overlaysProblem_ = "overlay catalogue " + path + " lists no overlays";
        MIRROR_LOG_ERROR("%s; running without overlays", overlaysProblem_.c_str());
        return;
    }
    render::FaceOverlayOptions options;
    options.verticalFovDegrees = static_cast<float>(config_.overlay.verticalFovDeg);
    overlayLayer_ = std::make_unique<render::FaceOverlayLayer>(catalogue, options);
    renderer_->addLayer(overlayLayer_.get());

    std::vector<std::string> names;
    for (const render::Overlay& o : catalogue.overlays())
        names.push_back(o.name);
    OverlaySelectionOptions selectionOptions;
    selectionOptions.mode = config_.overlay.mode == OverlayConfig::Mode::PerFace
                                ? OverlayMode::PerFace
                                : OverlayMode::Global;
    selectionOptions.fadeNs = static_cast<std::int64_t>(config_.overlay.fadeMs) * 1'000'000;
    selectionOptions.maxFaces = config_.faces.maxFaces;
    int initial = -1;
    if (config_.overlay.initial != "none" &&
        (initial = catalogue.find(config_.overlay.initial)) < 0)
        MIRROR_LOG_WARN("overlay.default: no overlay '%s' in %s; starting with none",
                        config_.overlay.initial.c_str(), path.c_str());
    selection_ = std::make_unique<OverlaySelection>(std::move(names), selectionOptions, initial);

    // The last choice survives restarts (state folder); a corrupt file is ignored with a warning.
    overlayStore_ = std::make_unique<OverlayStateStore>(config_.state.dir);
    std::string warning;
    if (const auto saved = overlayStore_->load(warning)) {
        selection_->setMode(saved->mode);
        if (!selection_->select(saved->overlay))
            MIRROR_LOG_WARN("overlay: kept choice '%s' is not in the catalogue; ignored",
                            saved->overlay.c_str());
    } else if (!warning.empty()) {
        MIRROR_LOG_WARN("overlay: %s", warning.c_str());
    }
    savedGeneration_ = selection_->generation();
    warmUpOverlays(size);
    MIRROR_LOG_INFO("overlays: %d from %s, wearing %s (%s)", selection_->size(), path.c_str(),
                    selection_->name(selection_->selected()), toString(selection_->mode()));
}

void FrameLoop::warmUpOverlays(vision::Size size)
{
    // A software GL driver compiles each pipeline variant (an overlay opaque, blended, fading)
    // the first time it is drawn: tens of milliseconds, and allocations, in the middle of the
    // mirror. Draw every overlay once now, opaque and half faded, into the display's framebuffer
    // (not presented), so the first person to try a hat sees no hitch.
    const int n = selection_->size();
    std::vector<vision::TrackedFace> faces;
    for (int pass = 0; pass < 2; ++pass) {
        faces.clear();
        for (int i = 0; i < n && i < render::FaceOverlayLayer::kMaxFaces; ++i) {
            vision::TrackedFace f;
            f.id = 1 + pass * 100 + i;
            f.centre = {static_cast<float>(size.width) * static_cast<float>(i + 1) /
                            static_cast<float>(n + 1),
                        static_cast<float>(size.height) * 0.5f};
            f.size = static_cast<float>(size.height) * 0.25f;
            f.state = vision::FaceState::Confirmed;
            faces.push_back(f);
            overlayLayer_->setOverlay(f.id, i, pass == 0 ? 1.f : 0.5f);
        }
        overlayLayer_->setFaces(faces);
        renderer_->draw(vision::ConstImageView{}, display_->width(), display_->height(), "");
    }
    overlayLayer_->setFaces({});
    overlayLayer_->clearSelection();
}

void FrameLoop::pollButtons() noexcept
{
    if (!buttons_ || buttonsFailed_)
        return;
    platform::ButtonEvent events[8];
    const int n = buttons_->poll(events, 8);
    if (n < 0) {
        MIRROR_LOG_WARN("buttons: %s; ignoring them from now on", buttons_->lastError());
        buttonsFailed_ = true;
        return;
    }
    for (int i = 0; i < n; ++i) {
        const ButtonAction action = buttonActions_.actionFor(events[i]);
        MIRROR_LOG_INFO("button %d %s press: %s", events[i].button,
                        events[i].kind == platform::ButtonEvent::Long ? "long" : "short",
                        toString(action));
        runButtonAction(action);
    }
}

void FrameLoop::pollKeys() noexcept
{
    // A display with a keyboard (the desktop window, for development): the keys do what the
    // buttons and the console do.
    if (display_->closeRequested()) {
        MIRROR_LOG_INFO("window closed: stopping");
        requestStop();
        return;
    }
    platform::KeyEvent key;
    while (display_->nextKey(key)) {
        const std::string_view k = key.name;
        if (k == "n" || k == "Right")
            runButtonAction(ButtonAction::NextOverlay);
        else if (k == "p" || k == "Left")
            runButtonAction(ButtonAction::PrevOverlay);
        else if (k == "o")
            runButtonAction(ButtonAction::OverlayOff);
        else if (k == "t")
            runButtonAction(ButtonAction::TrainCard);
        else if (k == "d")
            runButtonAction(ButtonAction::ToggleDebugHud);
        else if (k == "s")
            runButtonAction(ButtonAction::Snapshot);
        else if (k == "h")
            renderer_->setHudVisible(!renderer_->hudVisible());
        else if (k == "q" || k == "Escape")
            requestStop();
    }
}

void FrameLoop::runButtonAction(ButtonAction action) noexcept
{
    // The same paths as the console commands.
    switch (action) {
        case ButtonAction::None:
            break;
        case ButtonAction::NextOverlay:
            if (selection_)
                selection_->next();
            break;
        case ButtonAction::PrevOverlay:
            if (selection_)
                selection_->prev();
            break;
        case ButtonAction::OverlayOff:
            if (selection_)
                selection_->off();
            break;
        case ButtonAction::TrainCard:
            requestCardTraining();
            break;
        case ButtonAction::ToggleDebugHud:
            setDebugHud(!debugHud());
            break;
        case ButtonAction::Snapshot:
            display_->requestSnapshot();
            break;
    }
}

void FrameLoop::updateOverlays() noexcept
{
    // Fades and smoothing run on the loop's clock: what the viewer sees is wall time.
    const std::int64_t now = nowNs();
    selection_->update(state_.faces, now);
    // 5.4: overlays ride on smoothed poses (no jitter, no visible lag), lit like the face.
    const std::span<const vision::TrackedFace> smooth = smoother_.apply(state_.faces, now);
    overlayLayer_->setFaces(smooth);
    for (const vision::TrackedFace& f : smooth) {
        if (!f.shown())
            continue;
        const OverlayChoice choice = selection_->choiceFor(f.id);
        overlayLayer_->setOverlay(f.id, choice.overlay, choice.alpha);
        overlayLayer_->setBrightness(
            f.id, std::clamp(faceStage_->brightnessAround(f.centre, f.size), 0.4f, 1.6f));
    }
    if (selection_->generation() != savedGeneration_) {
        savedGeneration_ = selection_->generation();
        if (!overlayStore_->save(*selection_))
            MIRROR_LOG_WARN("overlay: choice not kept: %s", overlayStore_->lastError());
    }
}

void FrameLoop::formatOverlays(Reply& reply) const noexcept
{
    reply.printf("overlay: %s (%s)\n", selection_->name(selection_->selected()),
                 toString(selection_->mode()));
    for (const vision::TrackedFace& f : state_.faces) {
        if (!f.shown())
            continue;
        const OverlayChoice c = selection_->choiceFor(f.id);
        reply.printf("face %d: %s alpha %.2f%s\n", f.id, selection_->name(c.overlay),
                     static_cast<double>(c.alpha),
                     f.id == selection_->targetFace() ? " (buttons act on this face)" : "");
    }
}

void FrameLoop::overlayCommand(const Args& args, Reply& reply) noexcept
{
    if (!selection_) {
        reply.printf("overlay: none loaded%s%.200s\n", overlaysProblem_.empty() ? "" : ": ",
                     overlaysProblem_.c_str());
        return;
    }
    OverlayChange change;
    const std::string_view what = args[1];
    if (args.size() == 1) {
        formatOverlays(reply);
        return;
    }
    if (args.size() == 2 && what == "list") {
        for (int i = 0; i < selection_->size(); ++i)
            reply.printf("%d %s%s\n", i + 1, selection_->name(i),
                         i == selection_->selected() ? " *" : "");
        return;
    }
    if (args.size() == 3 && what == "mode") {
        OverlayMode mode{};
        if (!parseOverlayMode(args[2], mode)) {
            reply.printf("error: usage: overlay mode global|per_face\n");
            return;
        }
        selection_->setMode(mode);
        reply.printf("overlay: mode %s\n", toString(mode));
        return;
    }
    if (args.size() != 2) {
        reply.printf("error: usage: overlay [next|prev|off|list|NAME|mode global|per_face]\n");
        return;
    }
    if (what == "next")
        change = selection_->next();
    else if (what == "prev")
        change = selection_->prev();
    else if (what == "off")
        change = selection_->off();
    else if (!selection_->select(what, &change)) {
        reply.printf("error: no overlay '%.*s' (overlay list)\n", static_cast<int>(what.size()),
                     what.data());
        return;
    }
    if (change.faceId != 0)
        reply.printf("overlay: face %d wears %s\n", change.faceId,
                     selection_->name(change.overlay));
    else
        reply.printf("overlay: %s\n", selection_->name(change.overlay));
}

void FrameLoop::setDebugHud(bool on) noexcept
{
    if (faceDebug_)
        faceDebug_->setVisible(on);
}

void FrameLoop::noteFaces() noexcept
{
    int shown = 0;
    for (const vision::TrackedFace& f : state_.faces)
        shown += f.shown();
    if (shown != facesShown_)
        MIRROR_LOG_INFO("faces: %d shown (was %d)", shown, facesShown_);
    facesShown_ = shown;
    if (faceDebug_)
        faceDebug_->update(state_.faces);
}

void FrameLoop::formatFaces(Reply& reply) const noexcept
{
    const std::span<const vision::TrackedFace> faces = faceStage_->faces();
    int shown = 0;
    for (const vision::TrackedFace& f : faces)
        shown += f.shown();
    reply.printf("faces: %d shown, %d tracked, motion %d px\n", shown,
                 static_cast<int>(faces.size()), motionStage_->foregroundPixels());
    for (const vision::TrackedFace& f : faces)
        reply.printf(
            "face %d: %s centre (%.1f, %.1f) size %.1f roll %.1f deg confidence %.2f "
            "age %d points %d\n",
            f.id, kFaceStateNames[static_cast<int>(f.state)], static_cast<double>(f.centre.x),
            static_cast<double>(f.centre.y), static_cast<double>(f.size),
            static_cast<double>(f.rollDegrees), static_cast<double>(f.confidence), f.age,
            f.pointCount);
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
        overlayLayer_.reset();
        faceDebug_.reset();
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
    const std::int64_t t0 = nowNs();
    if (startNs_ == 0)
        startNs_ = intervalStartNs_ = t0;
    notifier_.pingWatchdog(t0);
    // A console whose input closed (stdin at EOF) is let go, so it costs nothing per frame.
    for (std::size_t c = 0; c < consoles_.size(); ++c)
        if (consoles_[c] && shell_.poll(*consoles_[c], c).closed)
            consoles_[c] = nullptr;
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
        if (source_->needsProcessRestart()) {
            // libcamera 0.0.3 cannot let go of a camera that vanished without killing the
            // process: stop now, and let main leave at once for the service manager to start a
            // fresh one.
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
        showSourceLost(t1);
        std::this_thread::sleep_for(kLostRetry);
        updateRate(nowNs());
        return true;
    }
    if (lastFrameNs_ != 0)  // slow average of the time between frames, for `selftest`
        frameIntervalNs_ += (t1 - lastFrameNs_ - frameIntervalNs_) / 8;
    lastFrameNs_ = t1;
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
    if (faceStage_)
        noteFaces();
    pollButtons();
    pollKeys();
    if (overlayLayer_)
        updateOverlays();

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
    if (snapshotReplyPending_) {
        char line[512];
        std::snprintf(line, sizeof line, "snapshot: %s\n",
                      *display_->lastSnapshot() ? display_->lastSnapshot() : display_->lastError());
        tellConsoles(line);
        snapshotReplyPending_ = false;
    }
    updateRate(t3);
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
    if (renderer_->drawMessage("camera unavailable\nreconnecting ...", display_->width(),
                               display_->height()))
        display_->present();
}

void FrameLoop::tellConsoles(const char* text) noexcept
{
    for (std::size_t c = 0; c < consoles_.size(); ++c)
        if (consoles_[c])
            shell_.notify(*consoles_[c], c, text);
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
    tellConsoles(line);
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
    if (lost && !sourceLost_) {
        MIRROR_LOG_WARN("source lost: %s (retrying)", source_->lastError());
        notifier_.status("camera unavailable, retrying");
    } else if (!lost && sourceLost_) {
        MIRROR_LOG_INFO("source is back: %s", source_->description());
        notifier_.status("showing the mirror");
        // The faces tracked before the loss are stale (people left, the camera may have moved):
        // start afresh, with a whole-image scan of the first frame back.
        if (faceStage_)
            faceStage_->tracker().reset();
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
    int m = n;
    if (cardStage_ && m > 0 && m < static_cast<int>(sizeof hud_))
        m += std::snprintf(hud_ + m, sizeof hud_ - static_cast<std::size_t>(m), "\ncard %s %.2f",
                           vision::cardStateName(cardState_),
                           static_cast<double>(cardStage_->tracker().observation().confidence));
    if (faceStage_ && m > 0 && m < static_cast<int>(sizeof hud_))
        std::snprintf(hud_ + m, sizeof hud_ - static_cast<std::size_t>(m), "\nfaces %d",
                      facesShown_);
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
    if (faceStage_)
        reply.printf("faces: %d shown\n", facesShown_);
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
    if (faceStage_)
        shell_.add("faces", "faces",
                   "tracked faces: id, state, centre, size, roll, confidence, age",
                   [this](const Args&, Reply& reply) noexcept { formatFaces(reply); });
    if (faceDebug_)
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
    shell_.add("overlay", "overlay [next|prev|off|list|NAME|mode global|per_face]",
               "what the faces wear: show, change, list the catalogue, global or per-face choice",
               [this](const Args& args, Reply& reply) noexcept { overlayCommand(args, reply); });
    shell_.add("buttons", "buttons", "the GPIO buttons: device and which are pressed now",
               [this](const Args&, Reply& reply) noexcept {
                   if (!buttons_) {
                       reply.printf(
                           "buttons: none (disabled, or the GPIO chip was unavailable "
                           "at start: see `log`)\n");
                       return;
                   }
                   bool pressed[16] = {};
                   const int n = buttons_->readPressed(pressed, 16);
                   reply.printf("buttons: %s%s\n", buttons_->description(),
                                buttonsFailed_ ? " [FAILED]" : "");
                   for (int i = 0; i < n; ++i)
                       reply.printf("button %d: %s\n", i + 1, pressed[i] ? "pressed" : "up");
                   if (n < 0)
                       reply.printf("error: %s\n", buttons_->lastError());
               });
    shell_.add("selftest", "selftest",
               "check camera, display, inputs, state folder and vision assets: PASS/FAIL each",
               [this](const Args&, Reply& reply) noexcept {
                   const int failed = selfTest(reply);
                   reply.printf("selftest: %s\n", failed == 0 ? "all PASS" : "FAILED");
               });
    shell_.add(
        "log", "log [N]", "the last N log lines (default 20) from memory",
        [](const Args& args, Reply& reply) noexcept {
            int n = 20;
            if (args.size() == 2) {
                int v = 0;
                const auto [end, ec] =
                    std::from_chars(args[1].data(), args[1].data() + args[1].size(), v);
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
                n,
                [](const char* line, void* context) { static_cast<Reply*>(context)->append(line); },
                &reply);
        });
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

int FrameLoop::selfTest(Reply& reply) const noexcept
{
    int failed = 0;
    auto check = [&](bool ok, const char* name, const char* format, auto... args) {
        char detail[256];
        std::snprintf(detail, sizeof detail, format, args...);
        reply.printf("%s %s: %s\n", ok ? "PASS" : "FAIL", name, detail);
        failed += !ok;
    };
    const std::int64_t now = nowNs();
    // A live camera delivers within 2 s, or within a few of its own frame intervals when the
    // whole loop is slower than that (an emulated machine, a first frame's shader compiles).
    const std::int64_t kRecent = std::max<std::int64_t>(2'000'000'000, 4 * frameIntervalNs_);
    const bool frames = lastFrameNs_ != 0 && now - lastFrameNs_ < kRecent && !sourceLost_;
    check(frames, "camera", "%s, %s", source_->description(),
          frames ? "delivering frames" : (sourceLost_ ? source_->lastError() : "no recent frame"));
    const bool shown = lastPresentNs_ != 0 && now - lastPresentNs_ < kRecent && !displayDown_;
    check(shown, "display", "%s, %dx%d, %s", display_->description(), display_->width(),
          display_->height(), shown ? "showing frames" : display_->lastError());

    // The state folder: create, write, sync and remove a probe file (what the stores do).
    char path[1024];
    std::snprintf(path, sizeof path, "%s/.selftest-%d", config_.state.dir.c_str(),
                  static_cast<int>(::getpid()));
    const int fd = ::open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    bool writable = fd >= 0;
    const int error = errno;
    if (fd >= 0) {
        writable = ::write(fd, "ok\n", 3) == 3 && ::fsync(fd) == 0;
        ::close(fd);
        ::unlink(path);
    }
    check(writable, "state", "%s %s", config_.state.dir.c_str(),
          writable ? "writable" : std::strerror(error));
    if (config_.faces.enabled)
        check(faceStage_ != nullptr, "faces", "cascade %s loaded", config_.faces.cascade.c_str());
    else
        reply.printf("SKIP faces: disabled in the config\n");
    if (config_.faces.enabled && config_.overlay.enabled)
        check(selection_ != nullptr, "overlays", "%d loaded%s%.200s",
              selection_ ? selection_->size() : 0, overlaysProblem_.empty() ? "" : ": ",
              overlaysProblem_.c_str());
    else
        reply.printf("SKIP overlays: disabled in the config\n");
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
