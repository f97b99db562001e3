// The configuration: defaults, layering, round trip, every kind of problem with its exact message
// and position, and that config/mirror.toml, config/SCHEMA.md and the schema table agree.

#include "firmware/config.hpp"

#include "../../firmware/src/config_schema.hpp"  // white-box: the schema table itself
#include "../../firmware/src/config_value_text.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <sstream>

namespace {

using firmware::Config;
using firmware::ConfigError;
using firmware::ConfigProblem;
using firmware::ConfigRequest;
using firmware::DisplayConfig;
using firmware::LogLevel;
using firmware::Rate;
using firmware::SourceConfig;
namespace schema = firmware::config_schema;

std::string configData(const std::string& name)
{
    return testing_support::sourceDir() + "/tests/data/config/" + name;
}

std::string readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void writeFile(const std::string& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

Config loadFile(const std::string& path, std::vector<std::string> sets = {})
{
    return firmware::loadConfig({path, true, std::move(sets)});
}

/// The ConfigError's what() of `action`, or a failure if it does not throw one.
std::string errorOf(const std::function<void()>& action)
{
    try {
        action();
    } catch (const ConfigError& error) {
        return error.what();
    }
    ADD_FAILURE() << "no ConfigError thrown";
    return {};
}

std::vector<std::string> lines(const std::string& text)
{
    std::vector<std::string> result;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        result.push_back(line);
    }
    return result;
}

void expectSameConfig(const Config& a, const Config& b)
{
    EXPECT_EQ(a.source.spec, b.source.spec);
    EXPECT_EQ(a.source.width, b.source.width);
    EXPECT_EQ(a.source.height, b.source.height);
    EXPECT_EQ(a.source.fps, b.source.fps);
    EXPECT_EQ(a.source.loop, b.source.loop);
    EXPECT_EQ(a.source.rate.kind, b.source.rate.kind);
    EXPECT_EQ(a.source.rate.fps, b.source.rate.fps);
    EXPECT_EQ(a.source.card, b.source.card);
    EXPECT_EQ(a.display.spec, b.display.spec);
    EXPECT_EQ(a.display.width, b.display.width);
    EXPECT_EQ(a.display.height, b.display.height);
    EXPECT_EQ(a.display.fit, b.display.fit);
    EXPECT_EQ(a.display.mirror, b.display.mirror);
    EXPECT_EQ(a.display.hud, b.display.hud);
    EXPECT_EQ(a.display.snapshotEvery, b.display.snapshotEvery);
    EXPECT_EQ(a.log.level, b.log.level);
    EXPECT_EQ(a.log.summaryIntervalS, b.log.summaryIntervalS);
    EXPECT_EQ(a.console.stdinEnabled, b.console.stdinEnabled);
    EXPECT_EQ(a.console.maxLineLength, b.console.maxLineLength);
    EXPECT_EQ(a.vision.chromaticity, b.vision.chromaticity);
}

Config parseDefaults()
{
    return firmware::parseConfig(firmware::kDefaultConfigToml, "mirror.toml");
}

/// The one problem line of parsing `text` as file "t.toml" over the defaults.
std::string problemOf(const std::string& text)
{
    return errorOf([&] { firmware::parseConfig(text, "t.toml"); });
}

// ---- defaults -------------------------------------------------------------------------------

TEST(ConfigDefaults, EmbeddedCopyIsConfigMirrorToml)
{
    EXPECT_EQ(firmware::kDefaultConfigToml,
              readFile(testing_support::sourceDir() + "/config/mirror.toml"));
}

TEST(ConfigDefaults, ParseAndAgreeWithTheHeaderInitialisers)
{
    // mirror.toml is the source of defaults; the struct initialisers must not tell another story.
    expectSameConfig(parseDefaults(), Config{});
}

TEST(ConfigDefaults, TheShippedConfigHidesTheDeveloperHud)
{
    // The packaged /etc/mirror/mirror.toml is what the people in front of the mirror see: no fps
    // and stage times over their face (the demo and developers turn it on with display.hud=true).
    EXPECT_FALSE(parseDefaults().display.hud);
    EXPECT_FALSE(Config{}.display.hud);
}

TEST(ConfigDefaults, NoFileMeansBuiltInDefaults)
{
    ConfigRequest request;
    request.path = testing_support::freshOutputDir("config_no_file") + "/missing.toml";
    request.pathExplicit = false;
    const Config config = firmware::loadConfig(request);
    expectSameConfig(config, Config{});
    EXPECT_EQ(config.origin, "built-in defaults");
}

TEST(ConfigDefaults, AFileOverlaysOnlyTheKeysItSets)
{
    const Config config = firmware::parseConfig("[display]\nwidth = 800\n", "x.toml");
    Config expected;
    expected.display.width = 800;
    expectSameConfig(config, expected);
    EXPECT_EQ(config.origin, "x.toml");
}

TEST(ConfigDefaults, GoodExampleLoads)
{
    const std::string path = configData("good_example.toml");
    const Config config = loadFile(path);
    EXPECT_EQ(config.origin, path);
    EXPECT_EQ(config.source.spec, "file:/usr/share/doc/opencv-doc/examples/data/Megamind.avi");
    EXPECT_EQ(config.source.rate.kind, Rate::Kind::Fixed);
    EXPECT_EQ(config.source.rate.fps, 60.0);
    EXPECT_EQ(config.source.card, SourceConfig::Card::On);
    EXPECT_EQ(config.source.fps, 25.0);   // an integer where a float is expected
    EXPECT_EQ(config.source.width, 640);  // not in the file: default
    EXPECT_EQ(config.display.spec, "headless:/tmp/mirror-snapshots");
    EXPECT_EQ(config.display.width, 640);
    EXPECT_EQ(config.display.height, 360);
    EXPECT_EQ(config.display.fit, DisplayConfig::Fit::Contain);
    EXPECT_FALSE(config.display.hud);
    EXPECT_TRUE(config.display.mirror);
    EXPECT_EQ(config.display.snapshotEvery, 0);
    EXPECT_EQ(config.log.level, LogLevel::Warn);
    EXPECT_EQ(config.log.summaryIntervalS, 0.5);
    EXPECT_FALSE(config.console.stdinEnabled);
    EXPECT_TRUE(config.vision.chromaticity);
}

// ---- toToml ---------------------------------------------------------------------------------

Config everythingChanged()
{
    Config c;
    // Quotes, a backslash and UTF-8 survive; control characters are refused (ConfigInputBounds).
    c.source.spec = "file:/data/a \"quoted\" \\ path, é.avi";
    c.source.width = 1920;
    c.source.height = 1080;
    c.source.fps = 59.94;
    c.source.loop = false;
    c.source.rate = {Rate::Kind::Fixed, 0.1 + 12.2};  // not exactly representable: all digits
    c.source.card = SourceConfig::Card::Off;
    c.display.spec = "headless:/tmp/out";
    c.display.width = 16;
    c.display.height = 4320;
    c.display.fit = DisplayConfig::Fit::Contain;
    c.display.mirror = false;
    c.display.hud = false;
    c.display.snapshotEvery = 100000;
    c.log.level = LogLevel::Debug;
    c.log.summaryIntervalS = 1.0 / 3.0;
    c.console.stdinEnabled = false;
    c.console.maxLineLength = 4096;
    c.vision.chromaticity = false;
    return c;
}

TEST(ConfigToToml, DefaultsRoundTrip)
{
    const Config defaults = parseDefaults();
    expectSameConfig(firmware::parseConfig(firmware::toToml(defaults), "printed"), defaults);
}

TEST(ConfigToToml, EveryFieldRoundTrips)
{
    const Config changed = everythingChanged();
    expectSameConfig(firmware::parseConfig(firmware::toToml(changed), "printed"), changed);
}

TEST(ConfigToToml, RateFormsRoundTrip)
{
    for (const Rate rate :
         {Rate{Rate::Kind::Native, 0.0}, Rate{Rate::Kind::Max, 0.0}, Rate{Rate::Kind::Fixed, 60.0},
          Rate{Rate::Kind::Fixed, 1.0}, Rate{Rate::Kind::Fixed, 240.0}}) {
        Config config;
        config.source.rate = rate;
        expectSameConfig(firmware::parseConfig(firmware::toToml(config), "printed"), config);
    }
}

TEST(ConfigToToml, EnumValuesRoundTrip)
{
    for (const LogLevel level :
         {LogLevel::Error, LogLevel::Warn, LogLevel::Info, LogLevel::Debug}) {
        Config config;
        config.log.level = level;
        EXPECT_EQ(firmware::parseConfig(firmware::toToml(config), "p").log.level, level);
    }
    for (const auto card :
         {SourceConfig::Card::Auto, SourceConfig::Card::On, SourceConfig::Card::Off}) {
        Config config;
        config.source.card = card;
        EXPECT_EQ(firmware::parseConfig(firmware::toToml(config), "p").source.card, card);
    }
}

TEST(ConfigToToml, LoadsAgainFromAFile)
{
    const std::string path = testing_support::freshOutputDir("config_to_toml") + "/printed.toml";
    writeFile(path, firmware::toToml(everythingChanged()));
    const Config loaded = loadFile(path);
    expectSameConfig(loaded, everythingChanged());
    EXPECT_EQ(loaded.origin, path);
}

TEST(ConfigToToml, EveryKeyInSchemaOrderFloatsAsFloats)
{
    const std::string text = firmware::toToml(parseDefaults());
    const toml::table table = toml::parse(text);
    std::size_t lastLine = 0;
    for (const auto& spec : schema::schema()) {
        const toml::node* node = table.at_path(spec.name).node();
        ASSERT_NE(node, nullptr) << spec.name;
        EXPECT_GT(node->source().begin.line, lastLine) << spec.name << " out of schema order";
        lastLine = node->source().begin.line;
        if (spec.kind == schema::Kind::Float) {
            EXPECT_TRUE(node->is_floating_point()) << spec.name;
        }
    }
    EXPECT_NE(text.find("\nfps = 30.0\n"), std::string::npos);
    EXPECT_NE(text.find("\nsummary_interval_s = 1.0\n"), std::string::npos);
    EXPECT_NE(text.find("\nrate = \"native\"\n"), std::string::npos);
}

// ---- the schema, mirror.toml and SCHEMA.md agree ------------------------------------------------

TEST(ConfigSchema, MirrorTomlHasEveryKeyInSchemaOrderAndNoOther)
{
    const toml::table table =
        toml::parse_file(testing_support::sourceDir() + "/config/mirror.toml");
    std::vector<std::pair<std::size_t, std::string>> fileKeys;  // (line, dotted key)
    for (const auto& [section, node] : table) {
        ASSERT_TRUE(node.is_table()) << section;
        for (const auto& [key, value] : *node.as_table()) {
            fileKeys.emplace_back(value.source().begin.line,
                                  std::string(section.str()) + "." + std::string(key.str()));
        }
    }
    std::sort(fileKeys.begin(), fileKeys.end());
    std::vector<std::string> inFile;
    for (const auto& [line, key] : fileKeys) {
        inFile.push_back(key);
    }
    std::vector<std::string> inSchema;
    for (const auto& spec : schema::schema()) {
        inSchema.emplace_back(spec.name);
    }
    EXPECT_EQ(inFile, inSchema);
}

TEST(ConfigSchema, SchemaMdDocumentsEveryKeyAsTheSchemaSaysAndNoOther)
{
    // Each key is a row `| `key` | type | `default` | allowed | meaning |` under `## [section]`.
    std::map<std::string, std::string> rows;  // dotted key -> row text
    std::string section;
    for (const std::string& line :
         lines(readFile(testing_support::sourceDir() + "/config/SCHEMA.md"))) {
        if (line.starts_with("## [") && line.ends_with("]")) {
            section = line.substr(4, line.size() - 5);
        } else if (line.starts_with("| `")) {
            const auto end = line.find('`', 3);
            ASSERT_NE(end, std::string::npos) << line;
            const std::string key = section + "." + line.substr(3, end - 3);
            EXPECT_TRUE(rows.emplace(key, line).second) << "twice: " << key;
        }
    }
    const Config defaults = parseDefaults();
    for (const auto& spec : schema::schema()) {
        const std::string expected = "| `" + std::string(spec.key()) + "` | " +
                                     std::string(schema::typeName(spec)) + " | `" +
                                     schema::formatValue(spec, spec.get(defaults)) + "` | " +
                                     schema::allowed(spec) + " | " + std::string(spec.doc) + " |";
        const auto row = rows.find(std::string(spec.name));
        if (row == rows.end()) {
            ADD_FAILURE() << "config/SCHEMA.md lacks " << spec.name << "; under ## ["
                          << spec.section() << "] add:\n"
                          << expected;
            continue;
        }
        EXPECT_EQ(row->second, expected) << "config/SCHEMA.md row of " << spec.name;
        rows.erase(row);
    }
    for (const auto& [key, row] : rows) {
        ADD_FAILURE() << "config/SCHEMA.md documents " << key << ", which is not in the schema";
    }
}

TEST(ConfigSchema, EntriesAreComplete)
{
    for (const auto& spec : schema::schema()) {
        EXPECT_NE(spec.set, nullptr) << spec.name;
        EXPECT_NE(spec.get, nullptr) << spec.name;
        EXPECT_FALSE(spec.doc.empty()) << spec.name;
        EXPECT_EQ(spec.doc.find_first_of("|\n"), std::string_view::npos) << spec.name;
        EXPECT_TRUE(std::regex_match(std::string(spec.name), std::regex("[a-z]+\\.[a-z_]+")))
            << spec.name;
        EXPECT_EQ(schema::findKey(spec.name), &spec);
    }
    EXPECT_EQ(schema::findKey("display.nothing"), nullptr);
}

// ---- malformed files ------------------------------------------------------------------------

/// Every problem line of each bad_*.toml after "FILE:". The toml++ texts (syntax errors) are
/// those of toml++ 3.3; a newer toml++ may word them differently.
const std::map<std::string, std::vector<std::string>> kBadFiles = {
    {"bad_syntax.toml",
     {R"(4:8: config: Error while parsing key-value pair: expected value, saw '\n')"}},
    {"bad_unknown_key.toml",
     {"3:1: display.widht: unknown key (allowed: spec, width, height, fit, mirror, hud, debug, "
      "rotation, mode, snapshot_dir, snapshot_every)"}},
    {"bad_unknown_section.toml",
     {"4:2: camera: unknown section (allowed: source, display, log, console, vision, faces, "
      "overlay, days, people, weather, "
      "buttons, card, state)"}},
    {"bad_wrong_type.toml", {"2:9: source.width: expected integer, got string"}},
    {"bad_float_for_int.toml", {"2:9: source.width: expected integer, got float"}},
    {"bad_out_of_range.toml", {"2:9: display.width: 4000000 is out of range (allowed: 16..7680)"}},
    {"bad_odd_width.toml", {"2:9: source.width: 641 is odd (allowed: even numbers 16..7680)"}},
    {"bad_enum.toml",
     {R"(2:9: log.level: unknown value "loud" (allowed: "error", "warn", "info", "debug"))"}},
    {"bad_rate.toml",
     {R"(2:8: source.rate: 0 is out of range (allowed: "native", "max" or a number 1..240))"}},
    {"bad_spec.toml",
     {R"(2:8: source.spec: unknown source "camera" (allowed: "auto", "demo", "synthetic", )"
      R"("file:PATH", "libcamera[:ID]", "v4l2:DEVICE"))"}},
    {"bad_display_spec.toml",
     {R"(2:8: display.spec: "headless:" needs a directory after "headless:" (allowed: "auto", )"
      R"("headless:DIR", "drm[:CARD]", "window"))"}},
    {"bad_section_not_table.toml", {"1:10: source: expected table, got string"}},
    {"bad_empty.toml", {"1:1: config: file is empty (expected at least one [section])"}},
    {"bad_whitespace_only.toml", {"1:1: config: file is empty (expected at least one [section])"}},
    {"bad_comments_only.toml", {"1:1: config: file is empty (expected at least one [section])"}},
    {"bad_binary.toml", {"1:1: config: Encountered invalid utf-8 sequence"}},
    {"bad_invalid_utf8.toml", {"3:5: config: Encountered invalid utf-8 sequence"}},
    {"bad_duplicate_key.toml",
     {"4:9: config: Error while parsing key-value pair: cannot redefine existing integer "
      "'width'"}},
    {"bad_many_problems.toml",
     {R"(3:8: source.spec: "file:" needs a path after "file:" (allowed: "auto", "demo", )"
      R"("synthetic", "file:PATH", "libcamera[:ID]", "v4l2:DEVICE"))",
      "4:9: source.width: 8000 is out of range (allowed: even numbers 16..7680)",
      "5:7: source.fps: expected float, got string",
      R"(8:7: display.fit: unknown value "stretch" (allowed: "cover", "contain"))",
      "9:10: display.mirror: expected boolean, got integer",
      "10:1: display.colour: unknown key (allowed: spec, width, height, fit, mirror, hud, debug, "
      "rotation, mode, snapshot_dir, snapshot_every)",
      "13:22: log.summary_interval_s: -1 is out of range (allowed: 0..3600)",
      "15:2: extras: unknown section (allowed: source, display, log, console, vision, faces, "
      "overlay, days, people, weather, "
      "buttons, card, state)"}},
};

TEST(ConfigBadFiles, EachReportsExactlyItsProblems)
{
    for (const auto& [name, expectedLines] : kBadFiles) {
        SCOPED_TRACE(name);
        const std::string path = configData(name);
        const std::string what = errorOf([&] { loadFile(path); });
        std::vector<std::string> expected;
        for (const std::string& line : expectedLines) {
            expected.push_back(path + ":" + line);
        }
        EXPECT_EQ(lines(what), expected);
    }
}

TEST(ConfigBadFiles, EveryFixtureFailsWithWellFormedLines)
{
    const std::regex form("^[^:]+:[0-9]+:[0-9]+: [a-z_.]+: .+");
    int count = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(testing_support::sourceDir() + "/tests/data/config")) {
        const std::string name = entry.path().filename().string();
        if (!name.starts_with("bad_")) {
            continue;
        }
        SCOPED_TRACE(name);
        ++count;
        EXPECT_TRUE(kBadFiles.contains(name)) << "add the expected problems to kBadFiles";
        try {
            loadFile(entry.path().string());
            ADD_FAILURE() << "loaded without error";
        } catch (const ConfigError& error) {
            ASSERT_FALSE(error.problems().empty());
            EXPECT_EQ(lines(error.what()).size(), error.problems().size());
            for (const std::string& line : lines(error.what())) {
                EXPECT_TRUE(std::regex_match(line, form)) << line;
            }
            for (const ConfigProblem& problem : error.problems()) {
                EXPECT_EQ(problem.file, entry.path().string());
            }
        }
    }
    EXPECT_GE(count, 12);
}

TEST(ConfigBadFiles, ProblemsAreSortedByLine)
{
    try {
        loadFile(configData("bad_many_problems.toml"));
        FAIL() << "no error";
    } catch (const ConfigError& error) {
        const auto& problems = error.problems();
        EXPECT_TRUE(std::is_sorted(problems.begin(), problems.end(),
                                   [](auto& a, auto& b) { return a.line < b.line; }));
    }
}

// ---- other problems, one kind each ------------------------------------------------------------

TEST(ConfigProblems, MissingExplicitFile)
{
    const std::string path = testing_support::freshOutputDir("config_missing") + "/nope.toml";
    EXPECT_EQ(errorOf([&] { loadFile(path); }),
              path + ":1:1: config: cannot read file: No such file or directory");
}

TEST(ConfigProblems, DirectoryInsteadOfFile)
{
    const std::string dir = testing_support::freshOutputDir("config_directory");
    EXPECT_EQ(errorOf([&] { loadFile(dir); }),
              dir + ":1:1: config: cannot read file: Is a directory");
}

TEST(ConfigProblems, FileOverOneMebibyteIsRejectedBeforeParsing)
{
    const std::string dir = testing_support::freshOutputDir("config_large");
    // Exactly 1 MiB is fine (a section, then a long comment)...
    std::string text = "[log]\n#";
    text.resize(1024 * 1024 - 1, 'x');
    text += '\n';
    writeFile(dir + "/limit.toml", text);
    EXPECT_NO_THROW(loadFile(dir + "/limit.toml"));
    // ...one byte more is not, even though it is syntax errors all the way down.
    writeFile(dir + "/large.toml", text + "=");
    EXPECT_EQ(errorOf([&] { loadFile(dir + "/large.toml"); }),
              dir +
                  "/large.toml:1:1: config: file is too large: 1048577 bytes (allowed: up to "
                  "1048576 bytes)");
    EXPECT_EQ(problemOf(text + "="),
              "t.toml:1:1: config: file is too large: 1048577 bytes (allowed: up to 1048576 "
              "bytes)");
}

TEST(ConfigProblems, WrongTypes)
{
    EXPECT_EQ(problemOf("[display]\nhud = \"no\"\n"),
              "t.toml:2:7: display.hud: expected boolean, got string");
    EXPECT_EQ(problemOf("[source]\nspec = 3\n"),
              "t.toml:2:8: source.spec: expected string, got integer");
    EXPECT_EQ(problemOf("[source]\nrate = true\n"),
              "t.toml:2:8: source.rate: expected string or number, got boolean");
    EXPECT_EQ(problemOf("[log]\nlevel = [\"info\"]\n"),
              "t.toml:2:9: log.level: expected string, got array");
    EXPECT_EQ(problemOf("[[log]]\nlevel = \"info\"\n"),
              "t.toml:1:1: log: expected table, got array");
    EXPECT_EQ(problemOf("[source]\nwidth = 1979-05-27\n"),
              "t.toml:2:9: source.width: expected integer, got date");
}

TEST(ConfigProblems, NumbersAndRanges)
{
    EXPECT_NO_THROW(firmware::parseConfig("[source]\nwidth = 16\nheight = 4320\n", "t"));
    EXPECT_NO_THROW(firmware::parseConfig("[source]\nwidth = 7680\n", "t"));
    EXPECT_EQ(problemOf("[source]\nwidth = 7682\n"),
              "t.toml:2:9: source.width: 7682 is out of range (allowed: even numbers 16..7680)");
    EXPECT_EQ(problemOf("[display]\nheight = -9223372036854775808\n"),
              "t.toml:2:10: display.height: -9223372036854775808 is out of range (allowed: "
              "16..4320)");
    EXPECT_EQ(problemOf("[display]\nsnapshot_every = 100001\n"),
              "t.toml:2:18: display.snapshot_every: 100001 is out of range (allowed: 0..100000)");
    EXPECT_EQ(problemOf("[console]\nmax_line_length = 15\n"),
              "t.toml:2:19: console.max_line_length: 15 is out of range (allowed: 16..4096)");
    EXPECT_EQ(problemOf("[source]\nfps = 240.5\n"),
              "t.toml:2:7: source.fps: 240.5 is out of range (allowed: 1..240)");
    EXPECT_EQ(problemOf("[source]\nfps = nan\n"),
              "t.toml:2:7: source.fps: nan is out of range (allowed: 1..240)");
    EXPECT_EQ(problemOf("[log]\nsummary_interval_s = inf\n"),
              "t.toml:2:22: log.summary_interval_s: inf is out of range (allowed: 0..3600)");
    EXPECT_EQ(firmware::parseConfig("[log]\nsummary_interval_s = 0\n", "t").log.summaryIntervalS,
              0.0);
}

TEST(ConfigProblems, Rates)
{
    EXPECT_EQ(firmware::parseConfig("[source]\nrate = \"max\"\n", "t").source.rate.kind,
              Rate::Kind::Max);
    const Rate fixed = firmware::parseConfig("[source]\nrate = 29.97\n", "t").source.rate;
    EXPECT_EQ(fixed.kind, Rate::Kind::Fixed);
    EXPECT_EQ(fixed.fps, 29.97);
    EXPECT_EQ(problemOf("[source]\nrate = \"fast\"\n"),
              R"(t.toml:2:8: source.rate: unknown value "fast" (allowed: "native", "max" or a )"
              R"(number 1..240))");
    EXPECT_EQ(problemOf("[source]\nrate = 241\n"),
              R"(t.toml:2:8: source.rate: 241 is out of range (allowed: "native", "max" or a )"
              R"(number 1..240))");
}

TEST(ConfigProblems, SpecForms)
{
    for (const char* good : {"auto", "demo", "synthetic", "file:x.avi", "file:/d/*.png",
                             "libcamera", "libcamera:0", "v4l2:/dev/video0"}) {
        EXPECT_EQ(firmware::parseConfig(std::string("[source]\nspec = \"") + good + "\"\n", "t")
                      .source.spec,
                  good);
    }
    for (const char* good : {"auto", "headless:out", "drm", "drm:card1", "window"}) {
        EXPECT_EQ(firmware::parseConfig(std::string("[display]\nspec = \"") + good + "\"\n", "t")
                      .display.spec,
                  good);
    }
    const std::string sources =
        R"((allowed: "auto", "demo", "synthetic", "file:PATH", "libcamera[:ID]", "v4l2:DEVICE"))";
    EXPECT_EQ(problemOf("[source]\nspec = \"\"\n"),
              "t.toml:2:8: source.spec: unknown source \"\" " + sources);
    EXPECT_EQ(problemOf("[source]\nspec = \"Demo\"\n"),
              "t.toml:2:8: source.spec: unknown source \"Demo\" " + sources);
    EXPECT_EQ(problemOf("[source]\nspec = \"v4l2:\"\n"),
              "t.toml:2:8: source.spec: \"v4l2:\" needs a device path after \"v4l2:\" " + sources);
    EXPECT_EQ(problemOf("[source]\nspec = \"libcamera:\"\n"),
              "t.toml:2:8: source.spec: \"libcamera:\" needs a camera id after \"libcamera:\" " +
                  sources);
    const std::string displays = R"((allowed: "auto", "headless:DIR", "drm[:CARD]", "window"))";
    EXPECT_EQ(problemOf("[display]\nspec = \"drm:\"\n"),
              "t.toml:2:8: display.spec: \"drm:\" needs a card after \"drm:\" " + displays);
    EXPECT_EQ(problemOf("[display]\nspec = \"x11\"\n"),
              "t.toml:2:8: display.spec: unknown display \"x11\" " + displays);
    // Control characters in a value are refused, escaped: one problem, one line.
    EXPECT_EQ(
        problemOf("[display]\nspec = \"a\\nb\"\n"),
        "t.toml:2:8: display.spec: control character 0x0A at byte 2 of \"a\\nb\" " + displays);
}

TEST(ConfigProblems, NestedUnknownKeys)
{
    EXPECT_EQ(problemOf("[source.extra]\nx = 1\n"),
              "t.toml:1:9: source.extra: unknown key (allowed: spec, width, height, fps, loop, "
              "rate, card, rotation, hflip, vflip)");
    EXPECT_EQ(problemOf("[vision]\n\"odd key\" = 1\n"),
              "t.toml:2:1: vision.\"odd key\": unknown key (allowed: chromaticity, deinterlace)");
}

TEST(ConfigProblems, ErrorCarriesEveryProblemAndJoinsThemByLine)
{
    const std::vector<ConfigProblem> problems = {
        {"a.toml", 3, 7, "display.width", "2 is out of range (allowed: 16..7680)"},
        {"a.toml", 9, 1, "config", "something"},
    };
    const ConfigError error(problems);
    EXPECT_EQ(error.problems().size(), 2u);
    EXPECT_STREQ(error.what(),
                 "a.toml:3:7: display.width: 2 is out of range (allowed: 16..7680)\n"
                 "a.toml:9:1: config: something");
}

// ---- --set ----------------------------------------------------------------------------------

TEST(ConfigSet, OverridesTheFile)
{
    const Config config =
        loadFile(configData("good_example.toml"),
                 {"display.hud=true", R"(source.spec="file:x.avi")", "source.rate=\"max\"",
                  "display.width = 800", "display.width=1024", "log.summary_interval_s=2"});
    EXPECT_TRUE(config.display.hud);
    EXPECT_EQ(config.source.spec, "file:x.avi");
    EXPECT_EQ(config.source.rate.kind, Rate::Kind::Max);
    EXPECT_EQ(config.display.width, 1024);  // the later --set wins
    EXPECT_EQ(config.log.summaryIntervalS, 2.0);
    EXPECT_EQ(config.display.fit, DisplayConfig::Fit::Contain);  // from the file
}

TEST(ConfigSet, WithoutAFile)
{
    ConfigRequest request;
    request.path = testing_support::freshOutputDir("config_set_only") + "/missing.toml";
    request.sets = {"source.rate=60", "display.hud=false"};
    const Config config = firmware::loadConfig(request);
    EXPECT_EQ(config.source.rate.kind, Rate::Kind::Fixed);
    EXPECT_EQ(config.source.rate.fps, 60.0);
    EXPECT_FALSE(config.display.hud);
    EXPECT_EQ(config.origin, "built-in defaults");
}

TEST(ConfigSet, UnquotedStringsAreTakenLiterallyForStringKeys)
{
    const Config config =
        loadFile(configData("good_example.toml"),
                 {"source.spec=file:clip 1.avi", "source.rate=native", "log.level=debug"});
    EXPECT_EQ(config.source.spec, "file:clip 1.avi");
    EXPECT_EQ(config.source.rate.kind, Rate::Kind::Native);
    EXPECT_EQ(config.log.level, LogLevel::Debug);
    // The problem then points at the value as typed.
    EXPECT_EQ(errorOf([] { loadFile(configData("good_example.toml"), {"log.level= loud"}); }),
              R"(--set:1:12: log.level: unknown value "loud" (allowed: "error", "warn", "info", )"
              R"("debug"))");
}

TEST(ConfigSet, ProblemsNameTheSetByIndexAfterTheFileProblems)
{
    const std::string path = configData("bad_enum.toml");
    const std::string what = errorOf([&] {
        loadFile(path, {"display.hud=false", "display.width=1", "nonsense", "display.widht=3",
                        "display.hud=yes", "display=3", "x=", "# a=1", "display.width=640.0"});
    });
    EXPECT_EQ(
        lines(what),
        (std::vector<std::string>{
            path + R"(:2:9: log.level: unknown value "loud" (allowed: "error", "warn", "info", )"
                   R"("debug"))",
            "--set:2:15: display.width: 1 is out of range (allowed: 16..7680)",
            R"(--set:3:1: config: expected KEY=VALUE, got "nonsense" (allowed: KEY is )"
            R"(section.key, VALUE is TOML))",
            "--set:4:9: display.widht: unknown key (allowed: spec, width, height, fit, mirror, "
            "hud, debug, rotation, mode, snapshot_dir, snapshot_every)",
            "--set:5:13: display.hud: Error while parsing value: could not determine value type "
            "(allowed: true, false)",
            "--set:6:9: display: expected table, got integer",
            "--set:7:3: config: Error while parsing key-value pair: encountered end-of-file",
            "--set:8:1: config: nothing to set (expected KEY=VALUE)",
            "--set:9:15: display.width: expected integer, got float",
        }));
}

}  // namespace
