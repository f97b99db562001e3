#include "firmware/device_factory.hpp"

#include "firmware/exit_codes.hpp"
#include "firmware/log.hpp"
#include "firmware/startup_error.hpp"
#include "platform/card_scene_source.hpp"
#include "platform/file_source.hpp"
#include "platform/headless_display.hpp"
#include "platform/synthetic_source.hpp"

#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace firmware {

namespace {

bool startsWith(std::string_view s, std::string_view prefix)
{
    return s.substr(0, prefix.size()) == prefix;
}

platform::ReplayRate replayRate(const Rate& rate)
{
    switch (rate.kind) {
        case Rate::Kind::Native:
            return platform::ReplayRate::native();
        case Rate::Kind::Max:
            return platform::ReplayRate::max();
        case Rate::Kind::Fixed:
            return platform::ReplayRate::fixed(rate.fps);
    }
    return platform::ReplayRate::native();
}

/// The synthetic scene's pace: its own fps, unless replay is asked to run flat out.
double syntheticFps(const SourceConfig& c)
{
    switch (c.rate.kind) {
        case Rate::Kind::Max:
            return 0.0;
        case Rate::Kind::Fixed:
            return c.rate.fps;
        case Rate::Kind::Native:
            return c.fps;
    }
    return c.fps;
}

std::unique_ptr<platform::FrameSource> withCard(std::unique_ptr<platform::FrameSource> scene,
                                                const SourceConfig& c, bool cardByDefault)
{
    const bool card =
        c.card == SourceConfig::Card::On || (c.card == SourceConfig::Card::Auto && cardByDefault);
    if (!card)
        return scene;
    // The scene opens with the card held up over the centre, as a person does before `card
    // train`, so a demo can train and then track it.
    platform::CardSceneOptions options;
    options.introFrames = 45;
    return std::make_unique<platform::CardSceneSource>(std::move(scene), options);
}

std::unique_ptr<platform::FrameSource> openSource(const SourceConfig& c)
{
    const std::string& spec = c.spec;
    if (spec == "synthetic")
        return withCard(
            std::make_unique<platform::SyntheticSource>(c.width, c.height, syntheticFps(c)), c,
            true);
    if (startsWith(spec, "file:"))
        return withCard(std::make_unique<platform::FileSource>(spec.substr(5), c.loop,
                                                               replayRate(c.rate), c.fps),
                        c, false);
    if (spec == "demo" || spec == "auto") {
        if (spec == "auto")
            MIRROR_LOG_INFO("source auto: no camera support in this build, playing the demo scene");
        std::error_code ec;
        if (std::filesystem::exists(kDemoVideoPath, ec))
            return withCard(std::make_unique<platform::FileSource>(kDemoVideoPath, true,
                                                                   replayRate(c.rate), c.fps),
                            c, true);
        MIRROR_LOG_INFO("demo video %s not installed (package opencv-doc): synthetic scene",
                        kDemoVideoPath);
        return withCard(
            std::make_unique<platform::SyntheticSource>(c.width, c.height, syntheticFps(c)), c,
            true);
    }
    throw StartupError(kExitSource, "source " + spec +
                                        ": not supported by this build (allowed: auto, demo, "
                                        "synthetic, file:PATH)");
}

/// Where `auto` keeps headless output: systemd's StateDirectory when run as the service.
std::string defaultHeadlessDir()
{
    const char* state = std::getenv("STATE_DIRECTORY");
    return std::string(state && *state ? state : "/var/lib/mirror") + "/display";
}

}  // namespace

std::unique_ptr<platform::FrameSource> makeSource(const SourceConfig& config)
{
    try {
        return openSource(config);
    } catch (const StartupError&) {
        throw;
    } catch (const std::exception& e) {
        throw StartupError(kExitSource, e.what());
    }
}

std::unique_ptr<platform::Display> makeDisplay(const DisplayConfig& config)
{
    std::string spec = config.spec;
    if (spec == "auto") {
        spec = "headless:" + defaultHeadlessDir();
        MIRROR_LOG_INFO("display auto: no screen support in this build, rendering %s",
                        spec.c_str());
    }
    try {
        if (startsWith(spec, "headless:"))
            return std::make_unique<platform::HeadlessDisplay>(spec.substr(9), config.width,
                                                               config.height, config.snapshotEvery);
    } catch (const std::exception& e) {
        throw StartupError(kExitDisplay, e.what());
    }
    throw StartupError(kExitDisplay, "display " + spec +
                                         ": not supported by this build (allowed: auto, "
                                         "headless:DIR)");
}

}  // namespace firmware
