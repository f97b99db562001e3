#pragma once
// The appliance configuration: one TOML file, validated strictly against the schema in
// config_schema.cpp (every key, its type, range and meaning in one place). Defaults come from the
// embedded config/mirror.toml; a file and then --set overrides are layered on top.

#include <stdexcept>
#include <string>
#include <vector>

namespace firmware {

/// The embedded default configuration (config/mirror.toml), generated at build time.
extern const char* const kDefaultConfigToml;
/// Where the appliance looks for its config when --config is not given.
inline constexpr const char* kDefaultConfigPath = "/etc/mirror/mirror.toml";

enum class LogLevel { Error, Warn, Info, Debug };

/// Frame pacing of replayed and synthetic sources.
struct Rate {
    enum class Kind { Native, Max, Fixed } kind = Kind::Native;
    double fps = 0.0;  ///< for Fixed
};

struct SourceConfig {
    std::string spec = "auto";  ///< auto | demo | synthetic | file:PATH (later libcamera, v4l2:DEV)
    int width = 640;            ///< capture size for cameras and the synthetic scene
    int height = 480;
    double fps = 30.0;  ///< synthetic scene rate; camera frame rate request
    bool loop = true;   ///< replay files from the start when they end
    Rate rate;          ///< pacing of file replay: native, max or a fixed fps
    enum class Card { Auto, On, Off } card = Card::Auto;  ///< composite the synthetic card
    int rotation = 0;    ///< 0 or 180 (rpicam-apps' --rotation), before the flips
    bool hflip = false;  ///< left-right, before vision (rpicam-apps' --hflip)
    bool vflip = false;  ///< upside down, before vision (rpicam-apps' --vflip)
};

struct DisplayConfig {
    std::string spec = "auto";  ///< auto | headless:DIR (later drm[:CARD], window)
    int width = 1280;
    int height = 720;
    enum class Fit { Cover, Contain } fit = Fit::Cover;
    bool mirror = true;
    bool hud = false;
    bool debug = false;      ///< draw face boxes, corners and roll axes (the debug HUD)
    int rotation = 0;        ///< the picture turned clockwise on the panel: 0, 90, 180, 270
    int snapshotEvery = 30;  ///< frames between automatic snapshots (headless); 0 = on command only
    std::string mode;        ///< drm: "" or "preferred", "WxH" or "WxH@Hz"
    std::string snapshotDir;  ///< drm: where `snapshot` writes PNGs; "" = the state folder
};

struct LogConfig {
    LogLevel level = LogLevel::Info;
    double summaryIntervalS = 1.0;  ///< seconds between one-line summaries; 0 = off
};

struct ConsoleConfig {
    bool stdinEnabled = true;  ///< the shell on stdin/stdout
    int maxLineLength = 256;   ///< longer lines are rejected with one error line
    std::string serial;        ///< serial port of the diagnostics console; "" = none
    int baud = 115200;
};

struct ButtonsConfig {
    bool enabled = true;
    std::string chip = "gpiochip0";           ///< name, number, label or /dev path
    std::vector<std::int64_t> lines{17, 27, 22};  ///< line offsets; button n is the n-th
    bool activeLow = true;
    enum class Bias { AsIs, Disable, PullUp, PullDown } bias = Bias::PullUp;
    int debounceMs = 30;
    int longPressMs = 800;
    std::vector<std::string> shortPress{"next", "prev"};
    std::vector<std::string> longPress{"train-card", "toggle-debug", "enrol-guest"};
};

struct OverlayConfig {
    bool enabled = true;
    std::string catalogue;  ///< catalogue TOML; "" = the installed one (or the source tree's)
    enum class Mode { Global, PerFace } mode = Mode::Global;
    int fadeMs = 250;
    std::string initial = "top_hat";  ///< the `default` key: worn at the very first start
    double verticalFovDeg = 50.0;     ///< the camera's, for the overlays' perspective
    /// Which rule chooses a face's overlay first (firmware/overlay_rules.hpp).
    std::vector<std::string> precedence{"person", "birthday", "day", "weather", "global"};
};

struct DaysConfig {
    /// Special days and their overlays (firmware/day_calendar.hpp), first match wins.
    std::vector<std::string> dates{"12-24..12-26 santa_hat", "12-31..01-01 party_hat"};
    std::string birthday = "birthday_hat";  ///< on a known person's birthday
};

struct PeopleConfig {
    bool enabled = true;      ///< recognise enrolled people (needs `[faces] model`)
    int enrolFits = 24;       ///< fits `person add` averages into a person's signature
    int enrolTimeoutS = 15;   ///< `person add` gives up when they are not collected by then
};

struct WeatherConfig {
    std::string source;  ///< "" (none), an http(s):// URL or file:PATH (Open-Meteo's JSON)
    int intervalMinutes = 30;
    int timeoutSeconds = 10;
    std::string sun = "sun_hat", rain = "rain_hat", snow = "winter_hat";
    std::vector<std::int64_t> sunCodes{0, 1};
    std::vector<std::int64_t> rainCodes{51, 53, 55, 56, 57, 61, 63, 65,
                                        66, 67, 80, 81, 82, 95, 96, 99};
    std::vector<std::int64_t> snowCodes{71, 73, 75, 77, 85, 86};
};

struct VisionConfig {
    bool chromaticity = true;  ///< §1: normalised-RGB planes (forced on when a colour tracker runs)
    bool deinterlace = false;  ///< §2 (dissertation 4.2.4): remove interlace tearing first
};

struct FacesConfig {
    bool enabled = true;
    std::string cascade = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";
    std::string model;  ///< the AAM model file (5.3); "" = no 3D head, the 2D pose only
    int downscale = 2;  ///< motion and detection run at the frame size / downscale
    enum class Tracking { None, Translation, Similarity, Affine } tracking = Tracking::Similarity;
    bool motionMask = true;
    double scaleFactor = 1.1;
    int minNeighbors = 3;
    int minSize = 24;  ///< smallest face box at the working resolution
    int confirmFrames = 2;
    int graceFrames = 5;
    int occludedGraceFrames = 30;
    int maxFaces = 8;
    int detectionBudget = 5000;   ///< detector windows per frame; 0 = whole scan every frame
    double tiltScanDeg = 25.0;    ///< moving areas also scanned turned by +-this; 0 = off
    int tiltWindowBudget = 4000;  ///< tilted-scan windows per frame; 0 = no limit of its own
    double staticDropS = 300.0;   ///< a face that has not moved this long is background
    int motionComponents = 3;
    double motionLearningRate = 0.005;
};

struct CardConfig {
    bool enabled = true;
    std::string picture;  ///< PNG/JPEG shown on the card; "" = the built-in picture
    double trainFraction =
        0.5;                 ///< central share of width and height that `card train` learns from
    double threshold = 3.0;  ///< colour test in standard deviations
    double alpha = 0.25;     ///< model update: weight of the trained colour
    double beta = 0.75;      ///< model update: weight of the previous colour
};

struct StateConfig {
    std::string dir = "/var/lib/mirror";  ///< what the mirror learns, kept across restarts
};

struct Config {
    SourceConfig source;
    DisplayConfig display;
    LogConfig log;
    ConsoleConfig console;
    VisionConfig vision;
    FacesConfig faces;
    OverlayConfig overlay;
    DaysConfig days;
    PeopleConfig people;
    WeatherConfig weather;
    ButtonsConfig buttons;
    CardConfig card;
    StateConfig state;
    /// Where it came from, e.g. "/etc/mirror/mirror.toml" or "built-in defaults".
    std::string origin;
};

/// One problem found in a config file, printed as `FILE:LINE:COL: key: what is wrong (allowed:
/// ...)`.
struct ConfigProblem {
    std::string file;
    int line = 0;
    int column = 0;
    std::string key;      ///< dotted key, or "config" for file-level problems
    std::string message;  ///< what is wrong, with "(allowed: ...)" where it helps
    std::string format() const;
};

/// Thrown by loadConfig with every problem found (not just the first).
class ConfigError : public std::runtime_error {
public:
    explicit ConfigError(std::vector<ConfigProblem> problems);
    const std::vector<ConfigProblem>& problems() const noexcept { return problems_; }

private:
    std::vector<ConfigProblem> problems_;
};

struct ConfigRequest {
    std::string path;               ///< config file; empty = kDefaultConfigPath if it exists
    bool pathExplicit = false;      ///< given with --config: a missing file is then an error
    std::vector<std::string> sets;  ///< --set KEY=VALUE overrides, VALUE in TOML syntax
};

/// Defaults, then the file, then the overrides; validates everything. Throws ConfigError.
Config loadConfig(const ConfigRequest& request);
/// Parses and validates one TOML text over the defaults (used by loadConfig and tests).
Config parseConfig(const std::string& tomlText, const std::string& fileName);
/// The effective configuration as TOML, every key present, loadable again by loadConfig.
std::string toToml(const Config& config);

}  // namespace firmware
