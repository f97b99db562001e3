#include "overlay_control.hpp"

#include "firmware/log.hpp"

#include <unistd.h>

#include <algorithm>
#include <exception>
#include <string_view>
#include <vector>

namespace firmware {

namespace {

std::string findCatalogue(const std::string& configured)
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

}  // namespace

OverlayControl::OverlayControl(const Config& config, const vision::FaceStage* faces,
                               render::Renderer& renderer, const platform::Display& display,
                               vision::Size frameSize)
    : faces_(faces), renderer_(renderer), display_(display)
{
    frameSize_ = frameSize;
    if (faces_ && config.overlay.enabled)
        load(config, frameSize);
}

void OverlayControl::load(const Config& config, vision::Size frameSize)
{
    // A broken catalogue is one error line and a mirror without hats, not a mirror that does not
    // start: the video, the card and the console still work, and `selftest` reports it.
    const std::string path = findCatalogue(config.overlay.catalogue);
    render::OverlayCatalogue catalogue;
    try {
        catalogue = render::OverlayCatalogue::load(path);
    } catch (const std::exception& e) {
        problem_ = e.what();
        MIRROR_LOG_ERROR("%s; running without overlays", e.what());
        return;
    }
    if (catalogue.size() == 0) {
        problem_ = "overlay catalogue " + path + " lists no overlays";
        MIRROR_LOG_ERROR("%s; running without overlays", problem_.c_str());
        return;
    }
    render::FaceOverlayOptions options;
    options.verticalFovDegrees = static_cast<float>(config.overlay.verticalFovDeg);
    layer_ = std::make_unique<render::FaceOverlayLayer>(catalogue, options);
    renderer_.addLayer(layer_.get());

    std::vector<std::string> names;
    for (const render::Overlay& o : catalogue.overlays())
        names.push_back(o.name);
    OverlaySelectionOptions selectionOptions;
    selectionOptions.mode = config.overlay.mode == OverlayConfig::Mode::PerFace
                                ? OverlayMode::PerFace
                                : OverlayMode::Global;
    selectionOptions.fadeNs = static_cast<std::int64_t>(config.overlay.fadeMs) * 1'000'000;
    selectionOptions.maxFaces = config.faces.maxFaces;
    std::string problem;
    if (!parseOverlayPrecedence(config.overlay.precedence, selectionOptions.precedence, problem))
        MIRROR_LOG_ERROR("overlay.%s; using person, birthday, day, weather, global",
                         problem.c_str());
    int initial = -1;
    if (config.overlay.initial != "none" && (initial = catalogue.find(config.overlay.initial)) < 0)
        MIRROR_LOG_WARN("overlay.default: no overlay '%s' in %s; starting with none",
                        config.overlay.initial.c_str(), path.c_str());
    selection_ = std::make_unique<OverlaySelection>(std::move(names), selectionOptions, initial);

    // The last choice survives restarts (state folder); a corrupt file is ignored with a warning.
    store_ = std::make_unique<OverlayStateStore>(config.state.dir);
    std::string warning;
    if (const auto saved = store_->load(warning)) {
        selection_->setMode(saved->mode);
        if (!selection_->select(saved->overlay))
            MIRROR_LOG_WARN("overlay: kept choice '%s' is not in the catalogue; ignored",
                            saved->overlay.c_str());
    } else if (!warning.empty()) {
        MIRROR_LOG_WARN("overlay: %s", warning.c_str());
    }
    savedGeneration_ = selection_->generation();
    automatic_ = std::make_unique<AutomaticOverlays>(config, *selection_);
    warmUp(frameSize);
    MIRROR_LOG_INFO("overlays: %d from %s, wearing %s (%s)", selection_->size(), path.c_str(),
                    selection_->name(selection_->selected()), toString(selection_->mode()));
}

void OverlayControl::warmUp(vision::Size size)
{
    // A software GL driver compiles each pipeline variant (an overlay opaque, blended, fading)
    // the first time it is drawn: tens of milliseconds, and allocations, in the middle of the
    // mirror. Draw every overlay once now, opaque and half faded, into the display's framebuffer
    // (not presented), so the first person to try a hat sees no hitch.
    const int n = selection_->size();
    for (int pass = 0; pass < 2; ++pass) {
        std::size_t count = 0;
        for (int i = 0; i < n && i < render::FaceOverlayLayer::kMaxFaces; ++i) {
            render::FaceDrawing& d = drawings_[count++];
            d = render::FaceDrawing{};
            d.face.id = 1 + pass * 100 + i;
            d.face.centre = {static_cast<float>(size.width) * static_cast<float>(i + 1) /
                                 static_cast<float>(n + 1),
                             static_cast<float>(size.height) * 0.5f};
            d.face.size = static_cast<float>(size.height) * 0.25f;
            d.face.state = vision::FaceState::Confirmed;
            d.overlay = i;
            d.alpha = pass == 0 ? 1.f : 0.5f;
        }
        layer_->setFaces({drawings_.data(), count});
        renderer_.draw(vision::ConstImageView{}, display_.width(), display_.height(), "");
    }
    layer_->setFaces({});
}

void OverlayControl::update(std::span<const vision::TrackedFace> faces,
                            std::span<const vision::FaceFit> fits, std::int64_t now) noexcept
{
    if (!selection_)
        return;
    automatic_->apply(*selection_);
    selection_->update(faces, now);
    // §6: overlays ride on smoothed poses (no jitter, no visible lag), lit like the face; by the
    // fitted head's full pose where the AAM's fit holds (§5.3), else by the box.
    const std::span<const vision::TrackedFace> smoothed = smoother_.apply(faces, now, fits);
    const std::span<const vision::FaceFit> smoothedFits = smoother_.fits();
    const vision::CameraModel camera{frameSize_, layer_->options().verticalFovDegrees};
    std::size_t count = 0;
    for (std::size_t i = 0; i < smoothed.size(); ++i) {
        const vision::TrackedFace& f = smoothed[i];
        if (count == drawings_.size())
            break;
        render::FaceDrawing& d = drawings_[count++];
        d = render::FaceDrawing{};
        d.face = f;
        if (i < smoothedFits.size() && smoothedFits[i].ok()) {
            d.hasPose = true;
            d.pose = vision::headPoseFromFit(smoothedFits[i], camera,
                                             layer_->options().head.faceWidthMetres);
            d.animation = smoothedFits[i].animation;
        }
        if (!f.shown())
            continue;  // not drawn: wears nothing
        const OverlayChoice choice = selection_->choiceFor(f.id);
        d.overlay = choice.overlay;
        d.alpha = choice.alpha;
        d.brightness = std::clamp(faces_->brightnessAround(f.centre, f.size), 0.4f, 1.6f);
    }
    layer_->setFaces({drawings_.data(), count});
    if (selection_->generation() != savedGeneration_) {
        savedGeneration_ = selection_->generation();
        if (!store_->save(*selection_))
            MIRROR_LOG_WARN("overlay: choice not kept: %s", store_->lastError());
    }
}

void OverlayControl::format(std::span<const vision::TrackedFace> faces, Reply& reply) const noexcept
{
    reply.printf("overlay: %s (%s)\n", selection_->name(selection_->selected()),
                 toString(selection_->mode()));
    for (const vision::TrackedFace& f : faces) {
        if (!f.shown())
            continue;
        const OverlayChoice c = selection_->choiceFor(f.id);
        reply.printf("face %d: %s alpha %.2f by %s%s\n", f.id, selection_->name(c.overlay),
                     static_cast<double>(c.alpha), toString(selection_->ruleFor(f.id)),
                     f.id == selection_->targetFace() ? " (buttons act on this face)" : "");
    }
}

void OverlayControl::formatStatus(std::span<const vision::TrackedFace> faces,
                                  Reply& reply) const noexcept
{
    if (!selection_) {
        reply.printf("overlay: none loaded\n");
        return;
    }
    format(faces, reply);
    automatic_->format(*selection_, reply);
}

void OverlayControl::command(const Args& args, std::span<const vision::TrackedFace> faces,
                             Reply& reply) noexcept
{
    if (!selection_) {
        reply.printf("overlay: none loaded%s%.200s\n", problem_.empty() ? "" : ": ",
                     problem_.c_str());
        return;
    }
    OverlayChange change;
    const std::string_view what = args[1];
    if (args.size() == 1) {
        format(faces, reply);
        automatic_->format(*selection_, reply);
        return;
    }
    if (what == "mode") {
        OverlayMode mode{};
        if (!parseOverlayMode(args[2], mode)) {
            reply.usageError("mode needs global or per_face");
            return;
        }
        selection_->setMode(mode);
        reply.printf("overlay: mode %s\n", toString(mode));
        return;
    }
    if (args.size() != 2) {
        reply.usageError("unexpected '%.*s'", Args::shown(args[2]), args[2].data());
        return;
    }
    if (what == "list") {
        for (int i = 0; i < selection_->size(); ++i)
            reply.printf("%d %s%s\n", i + 1, selection_->name(i),
                         i == selection_->selected() ? " *" : "");
        return;
    }
    long number = 0;
    if (what == "next")
        change = selection_->next();
    else if (what == "prev")
        change = selection_->prev();
    else if (what == "off")
        change = selection_->off();
    else if (!selection_->select(what, &change)) {
        // Not a name: the number `overlay list` prints before it.
        if (!args.number(1, 1, selection_->size(), number)) {
            reply.usageError("no overlay '%.*s' (overlay list: names and numbers 1..%d)",
                             Args::shown(what), what.data(), selection_->size());
            return;
        }
        selection_->select(static_cast<int>(number) - 1, &change);
    }
    if (change.faceId != 0)
        reply.printf("overlay: face %d wears %s\n", change.faceId,
                     selection_->name(change.overlay));
    else
        reply.printf("overlay: %s\n", selection_->name(change.overlay));
}

}  // namespace firmware
