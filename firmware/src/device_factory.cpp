#include "firmware/device_factory.hpp"

#include "firmware/device_wait.hpp"
#include "firmware/exit_codes.hpp"
#include "firmware/log.hpp"
#include "firmware/startup_error.hpp"
#include "platform/card_scene_source.hpp"
#include "platform/drm_display.hpp"
#include "platform/file_source.hpp"
#include "platform/gpiod_button_input.hpp"
#include "platform/headless_display.hpp"
#include "platform/hotplug_watch.hpp"
#include "platform/libcamera_source.hpp"
#include "platform/oriented_source.hpp"
#include "platform/reconnecting_source.hpp"
#include "platform/synthetic_source.hpp"
#include "platform/v4l2_source.hpp"
#include "platform/window_display.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace firmware {

namespace {

bool startsWith(std::string_view s, std::string_view prefix)
{
    return s.substr(0, prefix.size()) == prefix;
}

/// Started by systemd as the appliance's service (Type=notify gives it a notification socket),
/// as opposed to a developer's run in a terminal or a script.
bool applianceRun()
{
    const char* socket = std::getenv("NOTIFY_SOCKET");
    return socket && *socket;
}

/// `auto` on the appliance with no camera yet: Lost until the pipeline is rebuilt on a camera
/// (DeviceWait says when one came), so the loop shows the calm "camera unavailable" screen.
class NoCameraYet final : public platform::FrameSource {
public:
    NoCameraYet(int width, int height) : size_{width, height}
    {
        std::snprintf(description_, sizeof description_, "auto (no camera yet, %dx%d)", width,
                      height);
    }
    const char* description() const noexcept override { return description_; }
    vision::Size size() const noexcept override { return size_; }
    vision::PixelFormat format() const noexcept override { return vision::PixelFormat::RGB24; }
    platform::SourceStatus next(vision::Frame&) noexcept override
    {
        return platform::SourceStatus::Lost;
    }
    const char* lastError() const noexcept override
    {
        return "no camera found; waiting for one to be plugged in";
    }

private:
    vision::Size size_;
    char description_[64] = "";
};

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

/// The scene opens with the card held up over the centre, as a person does before `card train`,
/// so a demo can train and then track it.
platform::CardSceneOptions sceneCard() noexcept
{
    platform::CardSceneOptions options;
    options.introFrames = 45;
    return options;
}

/// The demo video's card: held up only briefly (scripts/dev demo trains at once), then smaller and
/// kept to the lower corner that shows on the mirrored screen's lower left, where the video has
/// table and clothes, never a face: the hats are on from the first seconds.
platform::CardSceneOptions demoVideoCard() noexcept
{
    platform::CardSceneOptions options;
    options.introFrames = 12;
    options.heightFraction = 0.24;
    options.pathCentreX = 0.8;
    options.pathCentreY = 0.72;
    return options;
}

std::unique_ptr<platform::FrameSource> withCard(std::unique_ptr<platform::FrameSource> scene,
                                                const SourceConfig& c, bool cardByDefault,
                                                const platform::CardSceneOptions& options)
{
    const bool card =
        c.card == SourceConfig::Card::On || (c.card == SourceConfig::Card::Auto && cardByDefault);
    if (!card)
        return scene;
    return std::make_unique<platform::CardSceneSource>(std::move(scene), options);
}

/// A camera behind the reconnecting wrapper: missing at boot, unplugged or stalled cameras become
/// the "camera unavailable" state and are reopened with back-off (issue: real devices).
std::unique_ptr<platform::FrameSource> openCamera(const SourceConfig& c, const std::string& spec)
{
    platform::SourceOpener open;
    platform::ReconnectOptions reconnect;
    if (startsWith(spec, "libcamera")) {
        // A camera that vanished leaves libcamera unable to open any camera in this process.
        reconnect.processRestartRequired = platform::libcameraRestartRequired;
        platform::LibcameraOptions o;
        o.camera = spec.size() > 10 ? spec.substr(10) : std::string("0");
        o.width = c.width;
        o.height = c.height;
        o.fps = c.fps;
        open = [o] { return std::make_unique<platform::LibcameraSource>(o); };
    } else {
        platform::V4l2Options o;
        o.device = spec.substr(5);
        o.width = c.width;
        o.height = c.height;
        o.fps = c.fps;
        open = [o] { return std::make_unique<platform::V4l2Source>(o); };
    }
    auto camera = std::make_unique<platform::ReconnectingSource>(
        spec, std::move(open), vision::Size{c.width, c.height}, vision::PixelFormat::RGB24,
        reconnect);
    if (camera->state() != platform::CameraState::Running)
        MIRROR_LOG_WARN("camera %s unavailable at start: %s (retrying)", spec.c_str(),
                        camera->lastError());
    return camera;
}

std::unique_ptr<platform::FrameSource> openSource(const SourceConfig& c)
{
    const std::string& spec = c.spec;
    if (spec == "libcamera" || startsWith(spec, "libcamera:") || startsWith(spec, "v4l2:"))
        return openCamera(c, spec);
    if (spec == "auto") {
        // The camera the board has: libcamera first (CSI and USB cameras), then plain V4L2.
        if (platform::libcameraCameraAvailable()) {
            MIRROR_LOG_INFO("source auto: libcamera camera found");
            return openCamera(c, "libcamera:0");
        }
        const std::string device = platform::findV4l2CaptureDevice();
        if (!device.empty()) {
            MIRROR_LOG_INFO("source auto: V4L2 capture device %s", device.c_str());
            return openCamera(c, "v4l2:" + device);
        }
    }
    if (spec == "auto" && applianceRun()) {
        // The appliance shows the calm screen and keeps looking (DeviceWait), never a cartoon.
        MIRROR_LOG_WARN("source auto: no camera found; waiting for one (hot-plug)");
        return std::make_unique<NoCameraYet>(c.width, c.height);
    }
    if (spec == "synthetic")
        return withCard(
            std::make_unique<platform::SyntheticSource>(c.width, c.height, syntheticFps(c)), c,
            true, sceneCard());
    if (startsWith(spec, "file:"))
        return withCard(std::make_unique<platform::FileSource>(spec.substr(5), c.loop,
                                                               replayRate(c.rate), c.fps),
                        c, false, sceneCard());
    if (spec == "demo" || spec == "auto") {
        if (spec == "auto")
            MIRROR_LOG_INFO("source auto: no camera found, playing the demo scene");
        std::error_code ec;
        if (std::filesystem::exists(kDemoVideoPath, ec))
            return withCard(std::make_unique<platform::FileSource>(kDemoVideoPath, true,
                                                                   replayRate(c.rate), c.fps),
                            c, true, demoVideoCard());
        MIRROR_LOG_INFO("demo video %s not installed (package opencv-doc): synthetic scene",
                        kDemoVideoPath);
        return withCard(
            std::make_unique<platform::SyntheticSource>(c.width, c.height, syntheticFps(c)), c,
            true, sceneCard());
    }
    throw StartupError(kExitSource, "source " + spec +
                                        ": unknown (allowed: auto, demo, synthetic, file:PATH, "
                                        "libcamera[:ID], v4l2:DEVICE)");
}

/// Where `auto` keeps headless output: systemd's StateDirectory when run as the service.
std::string defaultHeadlessDir()
{
    const char* state = std::getenv("STATE_DIRECTORY");
    return std::string(state && *state ? state : "/var/lib/mirror") + "/display";
}

std::unique_ptr<platform::Display> makeHeadless(const std::string& dir, const DisplayConfig& c,
                                                int snapshotEvery)
{
    try {
        return std::make_unique<platform::HeadlessDisplay>(dir, c.width, c.height, snapshotEvery);
    } catch (const std::exception& e) {
        throw StartupError(kExitDisplay, e.what());
    }
}

/// Whether some /dev/mediaN exists (a media controller: where libcamera finds its cameras).
bool mediaDevicePresent()
{
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator("/dev", ec))
        if (entry.path().filename().string().starts_with("media"))
            return true;
    return false;
}

}  // namespace

std::unique_ptr<platform::FrameSource> makeSource(const SourceConfig& config)
{
    try {
        auto source = openSource(config);
        const platform::Orientation orientation{config.rotation, config.hflip, config.vflip};
        if (orientation.identity() || dynamic_cast<const NoCameraYet*>(source.get()))
            return source;
        return std::make_unique<platform::OrientedSource>(std::move(source), orientation);
    } catch (const StartupError&) {
        throw;
    } catch (const std::exception& e) {
        throw StartupError(kExitSource, e.what());
    }
}

std::unique_ptr<platform::Display> makeDisplay(const DisplayConfig& config,
                                               const std::string& stateDir)
{
    std::string spec = config.spec;
    if (spec == "auto") {
        // The panel when a DRM card has a connected connector, else headless output.
        if (platform::drmDisplayAvailable()) {
            spec = "drm";
            MIRROR_LOG_INFO("display auto: DRM/KMS panel found");
        } else if (platform::windowDisplayAvailable()) {
            spec = "window";
            MIRROR_LOG_INFO("display auto: a window on the desktop");
        } else {
            // Off screen until a panel comes (DeviceWait), and bounded: snapshots only when asked
            // for, never a picture every few frames into the state folder.
            const std::string dir = defaultHeadlessDir();
            MIRROR_LOG_WARN(
                "display auto: no connected screen; rendering off screen (snapshots "
                "on request in %s) until a panel is connected",
                dir.c_str());
            return makeHeadless(dir, config, 0);
        }
    }
    try {
        if (startsWith(spec, "headless:"))
            return makeHeadless(spec.substr(9), config, config.snapshotEvery);
        if (spec == "window")
            return std::make_unique<platform::WindowDisplay>(config.width, config.height);
        if (spec == "drm" || startsWith(spec, "drm:")) {
            platform::DrmOptions o;
            o.card = spec.size() > 4 ? spec.substr(4) : std::string();
            o.mode = config.mode;
            o.snapshotDir = config.snapshotDir;
            if (o.snapshotDir.empty() && !stateDir.empty()) {
                o.snapshotDir = stateDir + "/snapshots";
                std::error_code ec;
                std::filesystem::create_directories(o.snapshotDir, ec);
                if (ec) {
                    MIRROR_LOG_WARN("display: cannot make %s: %s; no snapshots",
                                    o.snapshotDir.c_str(), ec.message().c_str());
                    o.snapshotDir.clear();
                }
            }
            return std::make_unique<platform::DrmDisplay>(o);
        }
    } catch (const std::exception& e) {
        throw StartupError(kExitDisplay, e.what());
    }
    throw StartupError(
        kExitDisplay,
        "display " + spec + ": unknown (allowed: auto, headless:DIR, drm[:CARD], window)");
}

std::unique_ptr<DeviceWait> makeDeviceWait(const Config& config,
                                           const platform::FrameSource& source,
                                           const platform::Display& display)
{
    const bool camera =
        config.source.spec == "auto" && dynamic_cast<const NoCameraYet*>(&source) != nullptr;
    const bool panel = config.display.spec == "auto" &&
                       dynamic_cast<const platform::HeadlessDisplay*>(&display) != nullptr;
    if (!camera && !panel)
        return nullptr;
    static constexpr const char* kSubsystems[] = {"video4linux", "drm", nullptr};
    auto watch = std::make_unique<platform::HotplugWatch>(kSubsystems);
    if (!watch->listening())
        MIRROR_LOG_WARN("%s; looking for devices every 10 s instead", watch->lastError());
    DeviceProbes probes;
    // libcamera's check starts a CameraManager: only when a media controller is there at all
    // (every libcamera camera has one), not every 10 s of a machine without any.
    probes.camera = [] {
        return platform::v4l2CaptureDeviceAvailable() ||
               (mediaDevicePresent() && platform::libcameraCameraAvailable());
    };
    probes.panel = [] { return platform::drmDisplayAvailable(); };
    return std::make_unique<DeviceWait>(camera, panel, std::move(probes), std::move(watch));
}

std::unique_ptr<platform::ButtonInput> makeButtons(const ButtonsConfig& config)
{
    if (!config.enabled)
        return nullptr;
    platform::GpiodButtonOptions o;
    o.chip = config.chip;
    for (const std::int64_t line : config.lines)
        o.lines.push_back(static_cast<unsigned>(line));
    static_assert(static_cast<int>(ButtonsConfig::Bias::PullDown) ==
                  static_cast<int>(platform::GpioBias::PullDown));
    o.bias = static_cast<platform::GpioBias>(config.bias);
    o.press.debounceNs = static_cast<std::int64_t>(config.debounceMs) * 1'000'000;
    o.press.longPressNs = static_cast<std::int64_t>(config.longPressMs) * 1'000'000;
    o.press.activeLow = config.activeLow;
    try {
        auto buttons = std::make_unique<platform::GpiodButtonInput>(o);
        MIRROR_LOG_INFO("buttons: %s", buttons->description());
        return buttons;
    } catch (const std::exception& e) {
        MIRROR_LOG_WARN("buttons: %s; running without buttons", e.what());
        return nullptr;
    }
}

}  // namespace firmware
