// The one table of configuration keys. See config_schema.hpp; the user-facing rendering of this
// table is config/SCHEMA.md (config_test checks that it matches).

#include "config_schema.hpp"

#include "config_string_checks.hpp"
#include "platform/serial_console.hpp"

#include <array>

namespace firmware::config_schema {

namespace {

// rpicam-apps' --rotation takes these for a camera (mounted upside down or not); a display may
// also be on either side (a portrait mirror).
constexpr std::array<int, 2> kCameraRotations = {0, 180};
constexpr std::array<int, 4> kDisplayRotations = {0, 90, 180, 270};

bool asBool(const Value& v)
{
    return std::get<bool>(v);
}
int asInt(const Value& v)
{
    return static_cast<int>(std::get<std::int64_t>(v));
}
double asDouble(const Value& v)
{
    return std::get<double>(v);
}
const std::string& asText(const Value& v)
{
    return std::get<std::string>(v);
}
template <typename E>
E asEnum(const Value& v)
{
    return static_cast<E>(std::get<std::int64_t>(v));
}
template <typename E>
Value enumValue(E e)
{
    return static_cast<std::int64_t>(e);
}
Value intValue(int i)
{
    return static_cast<std::int64_t>(i);
}

// Enum choices, in the order of the C++ enum they map to (values travel as the index).
constexpr std::array<std::string_view, 3> kCardChoices{"auto", "on", "off"};
constexpr std::array<std::string_view, 2> kFitChoices{"cover", "contain"};
constexpr std::array<std::string_view, 4> kLevelChoices{"error", "warn", "info", "debug"};
constexpr std::array<std::string_view, 4> kTrackingChoices{"none", "translation", "similarity",
                                                           "affine"};
constexpr std::array<std::string_view, 4> kBiasChoices{"as-is", "disable", "pull-up", "pull-down"};
constexpr std::array<std::string_view, 2> kOverlayModeChoices{"global", "per_face"};
static_assert(static_cast<int>(ButtonsConfig::Bias::PullDown) == 3);
static_assert(static_cast<int>(OverlayConfig::Mode::PerFace) == 1);
static_assert(static_cast<int>(SourceConfig::Card::Off) == 2);
static_assert(static_cast<int>(FacesConfig::Tracking::Affine) == 3);
static_assert(static_cast<int>(DisplayConfig::Fit::Contain) == 1);
static_assert(static_cast<int>(LogLevel::Debug) == 3);

const KeySpec kSchema[] = {
    // [source]
    {.name = "source.spec",
     .kind = Kind::String,
     .check = checkSourceSpec,
     .stringForms = R"("auto", "demo", "synthetic", "file:PATH", "libcamera[:ID]", "v4l2:DEVICE")",
     .doc = "Where frames come from (file:PATH is a video, a folder of frames or a glob)",
     .set = [](Config& c, const Value& v) { c.source.spec = asText(v); },
     .get = [](const Config& c) -> Value { return c.source.spec; }},
    {.name = "source.width",
     .kind = Kind::Int,
     .min = 16,
     .max = 7680,
     .even = true,
     .doc = "Capture width in pixels for cameras and the synthetic scene",
     .set = [](Config& c, const Value& v) { c.source.width = asInt(v); },
     .get = [](const Config& c) { return intValue(c.source.width); }},
    {.name = "source.height",
     .kind = Kind::Int,
     .min = 16,
     .max = 4320,
     .even = true,
     .doc = "Capture height in pixels for cameras and the synthetic scene",
     .set = [](Config& c, const Value& v) { c.source.height = asInt(v); },
     .get = [](const Config& c) { return intValue(c.source.height); }},
    {.name = "source.fps",
     .kind = Kind::Float,
     .min = 1,
     .max = 240,
     .doc = "Frame rate of the synthetic scene and the rate asked of cameras",
     .set = [](Config& c, const Value& v) { c.source.fps = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.source.fps; }},
    {.name = "source.loop",
     .kind = Kind::Bool,
     .doc = "Replay files from the start when they end",
     .set = [](Config& c, const Value& v) { c.source.loop = asBool(v); },
     .get = [](const Config& c) -> Value { return c.source.loop; }},
    {.name = "source.rate",
     .kind = Kind::Rate,
     .min = 1,
     .max = 240,
     .doc = "Pacing of file replay: the file's own rate, as fast as possible, or a fixed fps",
     .set =
         [](Config& c, const Value& v) {
             if (const auto* text = std::get_if<std::string>(&v)) {
                 c.source.rate = {*text == "max" ? Rate::Kind::Max : Rate::Kind::Native, 0.0};
             } else {
                 c.source.rate = {Rate::Kind::Fixed, asDouble(v)};
             }
         },
     .get = [](const Config& c) -> Value {
         switch (c.source.rate.kind) {
             case Rate::Kind::Native:
                 return std::string("native");
             case Rate::Kind::Max:
                 return std::string("max");
             case Rate::Kind::Fixed:
                 break;
         }
         return c.source.rate.fps;
     }},
    {.name = "source.card",
     .kind = Kind::Enum,
     .choices = kCardChoices,
     .doc = "Composite a synthetic coloured card over the scene (auto: on for demo and synthetic)",
     .set = [](Config& c, const Value& v) { c.source.card = asEnum<SourceConfig::Card>(v); },
     .get = [](const Config& c) { return enumValue(c.source.card); }},
    {.name = "source.rotation",
     .kind = Kind::Int,
     .min = 0,
     .max = 180,
     .oneOf = kCameraRotations,
     .doc = "Camera rotation in degrees, as rpicam-apps' --rotation (180: mounted upside down)",
     .set = [](Config& c, const Value& v) { c.source.rotation = asInt(v); },
     .get = [](const Config& c) { return intValue(c.source.rotation); }},
    {.name = "source.hflip",
     .kind = Kind::Bool,
     .doc = "Flip the camera image left-right before anything sees it, as rpicam-apps' --hflip",
     .set = [](Config& c, const Value& v) { c.source.hflip = asBool(v); },
     .get = [](const Config& c) -> Value { return c.source.hflip; }},
    {.name = "source.vflip",
     .kind = Kind::Bool,
     .doc = "Flip the camera image upside down before anything sees it, as rpicam-apps' --vflip",
     .set = [](Config& c, const Value& v) { c.source.vflip = asBool(v); },
     .get = [](const Config& c) -> Value { return c.source.vflip; }},
    // [display]
    {.name = "display.spec",
     .kind = Kind::String,
     .check = checkDisplaySpec,
     .stringForms = R"("auto", "headless:DIR", "drm[:CARD]", "window")",
     .doc = "Where frames go (headless:DIR renders without a window system, snapshots in DIR)",
     .set = [](Config& c, const Value& v) { c.display.spec = asText(v); },
     .get = [](const Config& c) -> Value { return c.display.spec; }},
    {.name = "display.width",
     .kind = Kind::Int,
     .min = 16,
     .max = 7680,
     .doc = "Output width in pixels",
     .set = [](Config& c, const Value& v) { c.display.width = asInt(v); },
     .get = [](const Config& c) { return intValue(c.display.width); }},
    {.name = "display.height",
     .kind = Kind::Int,
     .min = 16,
     .max = 4320,
     .doc = "Output height in pixels",
     .set = [](Config& c, const Value& v) { c.display.height = asInt(v); },
     .get = [](const Config& c) { return intValue(c.display.height); }},
    {.name = "display.fit",
     .kind = Kind::Enum,
     .choices = kFitChoices,
     .doc = "Fill the screen and crop the overflow (cover) or show the whole image with bars",
     .set = [](Config& c, const Value& v) { c.display.fit = asEnum<DisplayConfig::Fit>(v); },
     .get = [](const Config& c) { return enumValue(c.display.fit); }},
    {.name = "display.mirror",
     .kind = Kind::Bool,
     .doc = "Show the camera image left-right flipped, as a mirror does",
     .set = [](Config& c, const Value& v) { c.display.mirror = asBool(v); },
     .get = [](const Config& c) -> Value { return c.display.mirror; }},
    {.name = "display.hud",
     .kind = Kind::Bool,
     .doc = "Show the diagnostics text (fps, stage times) in the top-left corner",
     .set = [](Config& c, const Value& v) { c.display.hud = asBool(v); },
     .get = [](const Config& c) -> Value { return c.display.hud; }},
    {.name = "display.debug",
     .kind = Kind::Bool,
     .doc = "Debug HUD: draw face boxes, tracked corners and roll axes over the image",
     .set = [](Config& c, const Value& v) { c.display.debug = asBool(v); },
     .get = [](const Config& c) -> Value { return c.display.debug; }},
    {.name = "display.rotation",
     .kind = Kind::Int,
     .min = 0,
     .max = 270,
     .oneOf = kDisplayRotations,
     .doc = "Turn the whole picture clockwise on the panel (90 or 270 for a portrait mirror)",
     .set = [](Config& c, const Value& v) { c.display.rotation = asInt(v); },
     .get = [](const Config& c) { return intValue(c.display.rotation); }},
    {.name = "display.mode",
     .kind = Kind::String,
     .check = checkDisplayMode,
     .stringForms = R"("" or "preferred" (the panel's own), "WxH" or "WxH@Hz", e.g. "1280x720@60")",
     .doc = "Screen mode of a DRM/KMS panel",
     .set = [](Config& c, const Value& v) { c.display.mode = asText(v); },
     .get = [](const Config& c) -> Value { return c.display.mode; }},
    {.name = "display.snapshot_dir",
     .kind = Kind::String,
     .check = checkOptionalPath,
     .stringForms = R"("" (the state folder's snapshots/) or a directory)",
     .doc = "Where a DRM/KMS panel's `snapshot` PNGs go (headless displays use their own folder)",
     .set = [](Config& c, const Value& v) { c.display.snapshotDir = asText(v); },
     .get = [](const Config& c) -> Value { return c.display.snapshotDir; }},
    {.name = "display.snapshot_every",
     .kind = Kind::Int,
     .min = 0,
     .max = 100000,
     .doc = "Frames between automatic snapshots on headless displays; 0 = on command only",
     .set = [](Config& c, const Value& v) { c.display.snapshotEvery = asInt(v); },
     .get = [](const Config& c) { return intValue(c.display.snapshotEvery); }},
    // [log]
    {.name = "log.level",
     .kind = Kind::Enum,
     .choices = kLevelChoices,
     .doc = "Least severe message level that is logged",
     .set = [](Config& c, const Value& v) { c.log.level = asEnum<LogLevel>(v); },
     .get = [](const Config& c) { return enumValue(c.log.level); }},
    {.name = "log.summary_interval_s",
     .kind = Kind::Float,
     .min = 0,
     .max = 3600,
     .doc = "Seconds between one-line summaries (frames, fps, per-stage ms), to the log when "
            "the rate changed by a quarter or once a minute; 0 = off",
     .set = [](Config& c, const Value& v) { c.log.summaryIntervalS = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.log.summaryIntervalS; }},
    // [console]
    {.name = "console.stdin",
     .kind = Kind::Bool,
     .doc = "Run the diagnostics shell on standard input and output",
     .set = [](Config& c, const Value& v) { c.console.stdinEnabled = asBool(v); },
     .get = [](const Config& c) -> Value { return c.console.stdinEnabled; }},
    {.name = "console.max_line_length",
     .kind = Kind::Int,
     .min = 16,
     .max = 4096,
     .doc = "Longest accepted shell line in bytes; longer lines get one error line",
     .set = [](Config& c, const Value& v) { c.console.maxLineLength = asInt(v); },
     .get = [](const Config& c) { return intValue(c.console.maxLineLength); }},
    {.name = "console.serial",
     .kind = Kind::String,
     .check = checkSerial,
     .stringForms = R"("" (no serial console) or a device path, e.g. "/dev/ttyS0", "/dev/ttyAMA0")",
     .doc = "Serial port of the diagnostics console (8N1, raw); a missing port is one warning",
     .set = [](Config& c, const Value& v) { c.console.serial = asText(v); },
     .get = [](const Config& c) -> Value { return c.console.serial; }},
    {.name = "console.baud",
     .kind = Kind::Int,
     .min = platform::kSerialBaudRates.front(),
     .max = platform::kSerialBaudRates.back(),
     .oneOf = platform::kSerialBaudRates,
     .doc = "Serial console speed in bits per second (a standard rate, e.g. 115200)",
     .set = [](Config& c, const Value& v) { c.console.baud = asInt(v); },
     .get = [](const Config& c) { return intValue(c.console.baud); }},
    // [vision]
    {.name = "vision.chromaticity",
     .kind = Kind::Bool,
     .doc = "Compute normalised-RGB (chromaticity) planes for the colour trackers",
     .set = [](Config& c, const Value& v) { c.vision.chromaticity = asBool(v); },
     .get = [](const Config& c) -> Value { return c.vision.chromaticity; }},
    {.name = "vision.deinterlace",
     .kind = Kind::Bool,
     .doc = "4.2.4: remove interlace tearing before tracking (for interlaced cameras)",
     .set = [](Config& c, const Value& v) { c.vision.deinterlace = asBool(v); },
     .get = [](const Config& c) -> Value { return c.vision.deinterlace; }},
    // [faces]
    {.name = "faces.enabled",
     .kind = Kind::Bool,
     .doc = "Find and track faces (5.1): motion, Viola-Jones detection, corner tracking",
     .set = [](Config& c, const Value& v) { c.faces.enabled = asBool(v); },
     .get = [](const Config& c) -> Value { return c.faces.enabled; }},
    {.name = "faces.cascade",
     .kind = Kind::String,
     .check = checkPath,
     .stringForms = R"(an OpenCV Haar cascade XML path)",
     .doc = "Face detector cascade (OpenCV's Haar XML); read at start-up",
     .set = [](Config& c, const Value& v) { c.faces.cascade = asText(v); },
     .get = [](const Config& c) -> Value { return c.faces.cascade; }},
    {.name = "faces.model",
     .kind = Kind::String,
     .check = checkOptionalPath,
     .stringForms = R"("" (no 3D head) or an AAM model file path)",
     .doc = "5.3: the Active Appearance Model fitted to each face for its 3D pose and expression; "
            "a missing or broken file is reported and faces keep the 2D pose",
     .set = [](Config& c, const Value& v) { c.faces.model = asText(v); },
     .get = [](const Config& c) -> Value { return c.faces.model; }},
    {.name = "faces.downscale",
     .kind = Kind::Int,
     .min = 1,
     .max = 4,
     .doc = "Motion and detection run at the camera size divided by this (2: 720x480 -> 360x240)",
     .set = [](Config& c, const Value& v) { c.faces.downscale = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.downscale); }},
    {.name = "faces.tracking",
     .kind = Kind::Enum,
     .choices = kTrackingChoices,
     .doc = "How faces move between detections: none (detector only), translation, similarity "
            "(with roll and roll-warped verification), affine",
     .set = [](Config& c, const Value& v) { c.faces.tracking = asEnum<FacesConfig::Tracking>(v); },
     .get = [](const Config& c) { return enumValue(c.faces.tracking); }},
    {.name = "faces.motion_mask",
     .kind = Kind::Bool,
     .doc = "Scan for new faces only where something moves (static faces are ignored)",
     .set = [](Config& c, const Value& v) { c.faces.motionMask = asBool(v); },
     .get = [](const Config& c) -> Value { return c.faces.motionMask; }},
    {.name = "faces.scale_factor",
     .kind = Kind::Float,
     .min = 1.01,
     .max = 2,
     .doc = "Detector window growth per scale (OpenCV's scaleFactor)",
     .set = [](Config& c, const Value& v) { c.faces.scaleFactor = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.faces.scaleFactor; }},
    {.name = "faces.min_neighbors",
     .kind = Kind::Int,
     .min = 0,
     .max = 20,
     .doc = "Raw detections a face needs beyond this count (OpenCV's minNeighbors)",
     .set = [](Config& c, const Value& v) { c.faces.minNeighbors = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.minNeighbors); }},
    {.name = "faces.min_size",
     .kind = Kind::Int,
     .min = 0,
     .max = 1000,
     .doc = "Smallest face box in pixels at the working (downscaled) resolution",
     .set = [](Config& c, const Value& v) { c.faces.minSize = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.minSize); }},
    {.name = "faces.confirm_frames",
     .kind = Kind::Int,
     .min = 1,
     .max = 30,
     .doc = "n: frames in a row a face must be found before it is shown (fig. 89)",
     .set = [](Config& c, const Value& v) { c.faces.confirmFrames = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.confirmFrames); }},
    {.name = "faces.grace_frames",
     .kind = Kind::Int,
     .min = 0,
     .max = 300,
     .doc = "m: frames in a row a shown face may be missed before it is dropped (fig. 89)",
     .set = [](Config& c, const Value& v) { c.faces.graceFrames = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.graceFrames); }},
    {.name = "faces.occluded_grace_frames",
     .kind = Kind::Int,
     .min = 0,
     .max = 900,
     .doc = "frames in a row a shown face may be missed while its tracked corners still move "
            "together (covered by a hand or another head, or turned away) before it is dropped",
     .set = [](Config& c, const Value& v) { c.faces.occludedGraceFrames = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.occludedGraceFrames); }},
    {.name = "faces.max_faces",
     .kind = Kind::Int,
     .min = 1,
     .max = 16,
     .doc = "Faces tracked at once",
     .set = [](Config& c, const Value& v) { c.faces.maxFaces = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.maxFaces); }},
    {.name = "faces.detection_budget",
     .kind = Kind::Int,
     .min = 0,
     .max = 100000000,
     .doc = "Detector windows per frame; a longer scan continues on the next frames (0 = no limit)",
     .set = [](Config& c, const Value& v) { c.faces.detectionBudget = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.detectionBudget); }},
    {.name = "faces.tilt_scan_deg",
     .kind = Kind::Float,
     .min = 0,
     .max = 60,
     .doc = "Moving areas no face covers are also scanned turned by +- this angle, for faces that "
            "come in tilted (0 = off)",
     .set = [](Config& c, const Value& v) { c.faces.tiltScanDeg = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.faces.tiltScanDeg; }},
    {.name = "faces.tilt_window_budget",
     .kind = Kind::Int,
     .min = 0,
     .max = 100000000,
     .doc = "Tilted-scan windows per frame, within what detection_budget leaves (0 = no limit of "
            "its own)",
     .set = [](Config& c, const Value& v) { c.faces.tiltWindowBudget = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.tiltWindowBudget); }},
    {.name = "faces.static_drop_s",
     .kind = Kind::Float,
     .min = 0.5,
     .max = 3600,
     .doc = "A face that has not moved for this many seconds is a picture, not a person: dropped",
     .set = [](Config& c, const Value& v) { c.faces.staticDropS = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.faces.staticDropS; }},
    {.name = "faces.motion_components",
     .kind = Kind::Int,
     .min = 1,
     .max = 5,
     .doc = "K: Gaussians per pixel of the motion model (Stauffer-Grimson)",
     .set = [](Config& c, const Value& v) { c.faces.motionComponents = asInt(v); },
     .get = [](const Config& c) { return intValue(c.faces.motionComponents); }},
    {.name = "faces.motion_learning_rate",
     .kind = Kind::Float,
     .min = 0.0001,
     .max = 0.5,
     .doc = "How fast the motion model learns the background (per frame)",
     .set = [](Config& c, const Value& v) { c.faces.motionLearningRate = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.faces.motionLearningRate; }},
    // [overlay]
    {.name = "overlay.enabled",
     .kind = Kind::Bool,
     .doc = "Draw hats and glasses (5.4) on the shown faces",
     .set = [](Config& c, const Value& v) { c.overlay.enabled = asBool(v); },
     .get = [](const Config& c) -> Value { return c.overlay.enabled; }},
    {.name = "overlay.catalogue",
     .kind = Kind::String,
     .check = checkOptionalPath,
     .stringForms = R"("" (the installed catalogue) or a catalogue TOML path)",
     .doc = "The overlay catalogue; adding a hat is adding its files and a catalogue entry",
     .set = [](Config& c, const Value& v) { c.overlay.catalogue = asText(v); },
     .get = [](const Config& c) -> Value { return c.overlay.catalogue; }},
    {.name = "overlay.mode",
     .kind = Kind::Enum,
     .choices = kOverlayModeChoices,
     .doc = "One overlay for everyone (global) or one per face, the buttons changing the nearest",
     .set = [](Config& c, const Value& v) { c.overlay.mode = asEnum<OverlayConfig::Mode>(v); },
     .get = [](const Config& c) { return enumValue(c.overlay.mode); }},
    {.name = "overlay.fade_ms",
     .kind = Kind::Int,
     .min = 0,
     .max = 5000,
     .doc = "Overlays fade in and out over this many milliseconds instead of popping",
     .set = [](Config& c, const Value& v) { c.overlay.fadeMs = asInt(v); },
     .get = [](const Config& c) { return intValue(c.overlay.fadeMs); }},
    {.name = "overlay.default",
     .kind = Kind::String,
     .check = checkOverlayName,
     .stringForms = R"("none" or a catalogue name)",
     .doc = "Worn at the very first start; afterwards the last choice is kept in the state folder",
     .set = [](Config& c, const Value& v) { c.overlay.initial = asText(v); },
     .get = [](const Config& c) -> Value { return c.overlay.initial; }},
    {.name = "overlay.fov_deg",
     .kind = Kind::Float,
     .min = 10,
     .max = 150,
     .doc = "The camera's vertical field of view, for the overlays' perspective",
     .set = [](Config& c, const Value& v) { c.overlay.verticalFovDeg = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.overlay.verticalFovDeg; }},
    {.name = "overlay.precedence",
     .kind = Kind::WordList,
     .maxItems = 5,
     .check = checkOverlayRule,
     .stringForms = R"("person", "birthday", "day", "weather", "global", each once)",
     .doc = "Which rule chooses a face's overlay first: its own choice, a birthday, the day, the "
            "weather, the global choice",
     .set = [](Config& c,
               const Value& v) { c.overlay.precedence = std::get<std::vector<std::string>>(v); },
     .get = [](const Config& c) -> Value { return c.overlay.precedence; }},
    // [days]
    {.name = "days.dates",
     .kind = Kind::WordList,
     .maxItems = 64,
     .check = checkDayRule,
     .stringForms =
         R"("MM-DD NAME", "MM-DD..MM-DD NAME", "YYYY-MM-DD NAME", "YYYY-MM-DD..YYYY-MM-DD NAME")",
     .doc = "Special days and the overlay each puts on the faces (yearly or dated; the first that "
            "matches wins)",
     .set = [](Config& c, const Value& v) { c.days.dates = std::get<std::vector<std::string>>(v); },
     .get = [](const Config& c) -> Value { return c.days.dates; }},
    {.name = "days.birthday",
     .kind = Kind::String,
     .check = checkOverlayName,
     .stringForms = R"("none" or a catalogue name)",
     .doc = "Worn by a known person on their birthday",
     .set = [](Config& c, const Value& v) { c.days.birthday = asText(v); },
     .get = [](const Config& c) -> Value { return c.days.birthday; }},
    // [people]
    {.name = "people.enabled",
     .kind = Kind::Bool,
     .doc = "Recognise the people enrolled with `person add` (needs [faces] model)",
     .set = [](Config& c, const Value& v) { c.people.enabled = asBool(v); },
     .get = [](const Config& c) -> Value { return c.people.enabled; }},
    {.name = "people.enrol_fits",
     .kind = Kind::Int,
     .min = 1,
     .max = 600,
     .doc = "Fits of the face that `person add` averages into the person's signature",
     .set = [](Config& c, const Value& v) { c.people.enrolFits = asInt(v); },
     .get = [](const Config& c) { return intValue(c.people.enrolFits); }},
    {.name = "people.enrol_timeout_s",
     .kind = Kind::Int,
     .min = 2,
     .max = 120,
     .doc = "`person add` gives up when the fits are not collected within this many seconds",
     .set = [](Config& c, const Value& v) { c.people.enrolTimeoutS = asInt(v); },
     .get = [](const Config& c) { return intValue(c.people.enrolTimeoutS); }},
    // [weather]
    {.name = "weather.source",
     .kind = Kind::String,
     .check = checkForecastSource,
     .stringForms = R"("" (none), an http(s):// URL or file:PATH answering Open-Meteo's JSON)",
     .doc =
         "Where the forecast comes from, fetched in the background and cached in the state folder",
     .set = [](Config& c, const Value& v) { c.weather.source = asText(v); },
     .get = [](const Config& c) -> Value { return c.weather.source; }},
    {.name = "weather.interval_minutes",
     .kind = Kind::Int,
     .min = 5,
     .max = 1440,
     .doc = "Minutes between forecasts (after a failure: 30 s, doubling up to this)",
     .set = [](Config& c, const Value& v) { c.weather.intervalMinutes = asInt(v); },
     .get = [](const Config& c) { return intValue(c.weather.intervalMinutes); }},
    {.name = "weather.timeout_s",
     .kind = Kind::Int,
     .min = 1,
     .max = 120,
     .doc = "A fetch that takes longer fails (the last forecast stays)",
     .set = [](Config& c, const Value& v) { c.weather.timeoutSeconds = asInt(v); },
     .get = [](const Config& c) { return intValue(c.weather.timeoutSeconds); }},
    {.name = "weather.sun",
     .kind = Kind::String,
     .check = checkOverlayName,
     .stringForms = R"("none" or a catalogue name)",
     .doc = "Worn when the forecast's weather code is one of sun_codes",
     .set = [](Config& c, const Value& v) { c.weather.sun = asText(v); },
     .get = [](const Config& c) -> Value { return c.weather.sun; }},
    {.name = "weather.sun_codes",
     .kind = Kind::IntList,
     .min = 0,
     .max = 99,
     .maxItems = 100,
     .doc = "WMO weather codes of sunny weather",
     .set = [](Config& c,
               const Value& v) { c.weather.sunCodes = std::get<std::vector<std::int64_t>>(v); },
     .get = [](const Config& c) -> Value { return c.weather.sunCodes; }},
    {.name = "weather.rain",
     .kind = Kind::String,
     .check = checkOverlayName,
     .stringForms = R"("none" or a catalogue name)",
     .doc = "Worn when the forecast's weather code is one of rain_codes",
     .set = [](Config& c, const Value& v) { c.weather.rain = asText(v); },
     .get = [](const Config& c) -> Value { return c.weather.rain; }},
    {.name = "weather.rain_codes",
     .kind = Kind::IntList,
     .min = 0,
     .max = 99,
     .maxItems = 100,
     .doc = "WMO weather codes of rain (drizzle, rain, showers, thunderstorms)",
     .set = [](Config& c,
               const Value& v) { c.weather.rainCodes = std::get<std::vector<std::int64_t>>(v); },
     .get = [](const Config& c) -> Value { return c.weather.rainCodes; }},
    {.name = "weather.snow",
     .kind = Kind::String,
     .check = checkOverlayName,
     .stringForms = R"("none" or a catalogue name)",
     .doc = "Worn when the forecast's weather code is one of snow_codes",
     .set = [](Config& c, const Value& v) { c.weather.snow = asText(v); },
     .get = [](const Config& c) -> Value { return c.weather.snow; }},
    {.name = "weather.snow_codes",
     .kind = Kind::IntList,
     .min = 0,
     .max = 99,
     .maxItems = 100,
     .doc = "WMO weather codes of snow",
     .set = [](Config& c,
               const Value& v) { c.weather.snowCodes = std::get<std::vector<std::int64_t>>(v); },
     .get = [](const Config& c) -> Value { return c.weather.snowCodes; }},
    // [buttons]
    {.name = "buttons.enabled",
     .kind = Kind::Bool,
     .doc = "Push buttons on GPIO lines; a missing or busy chip is one warning",
     .set = [](Config& c, const Value& v) { c.buttons.enabled = asBool(v); },
     .get = [](const Config& c) -> Value { return c.buttons.enabled; }},
    {.name = "buttons.chip",
     .kind = Kind::String,
     .check = checkPath,
     .stringForms = R"(a chip name ("gpiochip0"), number, label or path ("/dev/gpiochip0"))",
     .doc = "The GPIO chip of the buttons",
     .set = [](Config& c, const Value& v) { c.buttons.chip = asText(v); },
     .get = [](const Config& c) -> Value { return c.buttons.chip; }},
    {.name = "buttons.lines",
     .kind = Kind::IntList,
     .min = 0,
     .max = 1023,
     .maxItems = 16,
     .doc = "Line offsets on the chip; button 1 is the first (Raspberry Pi: BCM numbers)",
     .set = [](Config& c,
               const Value& v) { c.buttons.lines = std::get<std::vector<std::int64_t>>(v); },
     .get = [](const Config& c) -> Value { return c.buttons.lines; }},
    {.name = "buttons.active_low",
     .kind = Kind::Bool,
     .doc = "A pressed button reads low (a switch to ground with a pull-up)",
     .set = [](Config& c, const Value& v) { c.buttons.activeLow = asBool(v); },
     .get = [](const Config& c) -> Value { return c.buttons.activeLow; }},
    {.name = "buttons.bias",
     .kind = Kind::Enum,
     .choices = kBiasChoices,
     .doc = "The lines' internal resistor (disable when the board has its own)",
     .set = [](Config& c, const Value& v) { c.buttons.bias = asEnum<ButtonsConfig::Bias>(v); },
     .get = [](const Config& c) { return enumValue(c.buttons.bias); }},
    {.name = "buttons.debounce_ms",
     .kind = Kind::Int,
     .min = 0,
     .max = 500,
     .doc = "A level counts once it has lasted this long (contact bounce is ignored)",
     .set = [](Config& c, const Value& v) { c.buttons.debounceMs = asInt(v); },
     .get = [](const Config& c) { return intValue(c.buttons.debounceMs); }},
    {.name = "buttons.long_press_ms",
     .kind = Kind::Int,
     .min = 100,
     .max = 10000,
     .doc = "Held this long is a long press, reported as soon as the time has passed",
     .set = [](Config& c, const Value& v) { c.buttons.longPressMs = asInt(v); },
     .get = [](const Config& c) { return intValue(c.buttons.longPressMs); }},
    {.name = "buttons.short_press",
     .kind = Kind::WordList,
     .maxItems = 16,
     .check = checkButtonAction,
     .stringForms =
         R"("next", "prev", "off", "train-card", "toggle-debug", "snapshot", "enrol-guest", "none")",
     .doc = "What a short press of button 1, 2, ... does",
     .set = [](Config& c,
               const Value& v) { c.buttons.shortPress = std::get<std::vector<std::string>>(v); },
     .get = [](const Config& c) -> Value { return c.buttons.shortPress; }},
    {.name = "buttons.long_press",
     .kind = Kind::WordList,
     .maxItems = 16,
     .check = checkButtonAction,
     .stringForms =
         R"("next", "prev", "off", "train-card", "toggle-debug", "snapshot", "enrol-guest", "none")",
     .doc = "What a long press of button 1, 2, ... does",
     .set = [](Config& c,
               const Value& v) { c.buttons.longPress = std::get<std::vector<std::string>>(v); },
     .get = [](const Config& c) -> Value { return c.buttons.longPress; }},
    // [card]
    {.name = "card.enabled",
     .kind = Kind::Bool,
     .doc = "Track a solid-coloured card (ch. 4) and show the picture on it",
     .set = [](Config& c, const Value& v) { c.card.enabled = asBool(v); },
     .get = [](const Config& c) -> Value { return c.card.enabled; }},
    {.name = "card.picture",
     .kind = Kind::String,
     .check = checkOptionalPath,
     .stringForms = R"("" (the built-in picture) or a PNG/JPEG path)",
     .doc =
         "Picture shown on the card; an unreadable file is reported and the card's outline shown",
     .set = [](Config& c, const Value& v) { c.card.picture = asText(v); },
     .get = [](const Config& c) -> Value { return c.card.picture; }},
    {.name = "card.train_fraction",
     .kind = Kind::Float,
     .min = 0.05,
     .max = 1,
     .doc =
         "Share of the frame's width and height, centred, that `card train` learns the colour from",
     .set = [](Config& c, const Value& v) { c.card.trainFraction = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.card.trainFraction; }},
    {.name = "card.threshold",
     .kind = Kind::Float,
     .min = 0.5,
     .max = 10,
     .doc = "Colour test: a pixel matches when within this many standard deviations (t of 4.2.1)",
     .set = [](Config& c, const Value& v) { c.card.threshold = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.card.threshold; }},
    {.name = "card.alpha",
     .kind = Kind::Float,
     .min = 0,
     .max = 1,
     .doc = "Model update: weight of the trained colour (anchors the model, prevents drift)",
     .set = [](Config& c, const Value& v) { c.card.alpha = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.card.alpha; }},
    {.name = "card.beta",
     .kind = Kind::Float,
     .min = 0,
     .max = 1,
     .doc = "Model update: weight of the previous colour against this frame's (steadiness)",
     .set = [](Config& c, const Value& v) { c.card.beta = asDouble(v); },
     .get = [](const Config& c) -> Value { return c.card.beta; }},
    // [state]
    {.name = "state.dir",
     .kind = Kind::String,
     .check = checkDirectory,
     .stringForms = R"(a directory path)",
     .doc = "Where the mirror keeps what it learns across restarts (the trained card colour, the "
            "overlay choice, the people it knows in people/)",
     .set = [](Config& c, const Value& v) { c.state.dir = asText(v); },
     .get = [](const Config& c) -> Value { return c.state.dir; }},
};

}  // namespace

std::span<const KeySpec> schema()
{
    return kSchema;
}

const KeySpec* findKey(std::string_view dottedName)
{
    for (const KeySpec& spec : kSchema) {
        if (spec.name == dottedName) {
            return &spec;
        }
    }
    return nullptr;
}

std::vector<std::string_view> sections()
{
    std::vector<std::string_view> names;
    for (const KeySpec& spec : kSchema) {
        if (names.empty() || names.back() != spec.section()) {
            names.push_back(spec.section());
        }
    }
    return names;
}

std::string keysOf(std::string_view section)
{
    std::string list;
    for (const KeySpec& spec : kSchema) {
        if (spec.section() == section) {
            list += (list.empty() ? "" : ", ") + std::string(spec.key());
        }
    }
    return list;
}

}  // namespace firmware::config_schema
