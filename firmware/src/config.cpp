// Loading, validating and printing the configuration. The keys themselves live in
// config_schema.cpp; this file layers TOML documents onto a Config and reports every problem with
// its position.

#include "firmware/config.hpp"

#include "config_schema.hpp"
#include "config_string_checks.hpp"
#include "config_value_text.hpp"
#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace firmware {

namespace {

using config_schema::KeySpec;
using config_schema::Kind;
using config_schema::checkText;
using config_schema::excerpt;
using config_schema::quoted;
using config_schema::Value;

constexpr std::size_t kMaxFileBytes = vision::limits::kConfigBytes;
constexpr const char* kBuiltInOrigin = "built-in defaults";

/// Where the TOML text being applied came from, for problem positions.
struct Layer {
    std::string file;
    /// --set texts are one pseudo-file each; their problems report the --set's index as the line.
    std::optional<int> line;
    /// Set when the text parsed is not the user's text (an unquoted --set string was quoted for
    /// them): every problem then points at the value the user typed.
    std::optional<int> column;
};

/// Collects the problems of one layer; positions come from toml++ nodes.
class Problems {
public:
    explicit Problems(const Layer& layer) : layer_(layer) {}

    void add(const toml::source_region& where, std::string key, std::string message)
    {
        // Nodes made by toml++ itself (implicit tables) have no position: point at the start.
        const int line = where.begin.line > 0 ? static_cast<int>(where.begin.line) : 1;
        const int column = where.begin.column > 0 ? static_cast<int>(where.begin.column) : 1;
        list_.push_back({layer_.file, layer_.line.value_or(line), layer_.column.value_or(column),
                         std::move(key), std::move(message)});
    }
    void addAtStart(std::string key, std::string message)
    {
        add(toml::source_region{}, std::move(key), std::move(message));
    }

    /// Sorted by position, appended to `all` (layers stay in the order they were applied).
    void moveInto(std::vector<ConfigProblem>& all)
    {
        std::stable_sort(list_.begin(), list_.end(), [](const auto& a, const auto& b) {
            return std::pair(a.line, a.column) < std::pair(b.line, b.column);
        });
        std::move(list_.begin(), list_.end(), std::back_inserter(all));
        list_.clear();
    }

private:
    const Layer& layer_;
    std::vector<ConfigProblem> list_;
};

std::string_view nodeTypeName(const toml::node& node)
{
    switch (node.type()) {
        case toml::node_type::table:
            return "table";
        case toml::node_type::array:
            return "array";
        case toml::node_type::string:
            return "string";
        case toml::node_type::integer:
            return "integer";
        case toml::node_type::floating_point:
            return "float";
        case toml::node_type::boolean:
            return "boolean";
        case toml::node_type::date:
            return "date";
        case toml::node_type::time:
            return "time";
        case toml::node_type::date_time:
            return "date-time";
        case toml::node_type::none:
            break;
    }
    return "nothing";
}

/// A key as it can be typed back into TOML: bare if it can be, else quoted.
std::string keyText(std::string_view key)
{
    const bool bare = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '-';
    });
    return bare && key.size() <= 64 ? std::string(key) : excerpt(key);
}

/// toml++ descriptions are one line today; keep it so if that changes (one problem, one line).
std::string oneLine(std::string_view text)
{
    std::string line(text);
    std::replace_if(
        line.begin(), line.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    return line;
}

std::string withAllowed(std::string what, const KeySpec& spec)
{
    return what + " (allowed: " + config_schema::allowed(spec) + ")";
}

/// The number of a Float or Rate node (an integer is fine where a number is expected).
std::optional<double> numberOf(const toml::node& node)
{
    if (const auto* f = node.as_floating_point()) {
        return f->get();
    }
    if (const auto* i = node.as_integer()) {
        return static_cast<double>(i->get());
    }
    return std::nullopt;
}

/// Checks one value against its key; the value to store, or nullopt with `what` set.
std::optional<Value> checkValue(const KeySpec& spec, const toml::node& node, std::string& what)
{
    const auto wrongType = [&](std::string_view expected) {
        what = "expected " + std::string(expected) + ", got " + std::string(nodeTypeName(node));
        return std::nullopt;
    };
    const auto outOfRange = [&](std::string valueText) {
        what = withAllowed(std::move(valueText) + " is out of range", spec);
        return std::nullopt;
    };

    switch (spec.kind) {
        case Kind::Bool:
            if (const auto* b = node.as_boolean()) {
                return Value(b->get());
            }
            return wrongType("boolean");
        case Kind::Int: {
            const auto* i = node.as_integer();
            if (i == nullptr) {
                return wrongType("integer");
            }
            const std::int64_t v = i->get();
            if (static_cast<double>(v) < spec.min || static_cast<double>(v) > spec.max) {
                return outOfRange(std::to_string(v));
            }
            if (!spec.oneOf.empty() &&
                std::find(spec.oneOf.begin(), spec.oneOf.end(), v) == spec.oneOf.end()) {
                what = withAllowed(std::to_string(v) + " is not in the list", spec);
                return std::nullopt;
            }
            if (spec.even && v % 2 != 0) {
                what = withAllowed(std::to_string(v) + " is odd", spec);
                return std::nullopt;
            }
            return Value(v);
        }
        case Kind::Float: {
            const auto v = numberOf(node);
            if (!v) {
                return wrongType("float");
            }
            if (!(*v >= spec.min && *v <= spec.max)) {  // written so NaN is out of range too
                return outOfRange(config_schema::formatNumber(*v));
            }
            return Value(*v);
        }
        case Kind::String: {
            const auto* s = node.as_string();
            if (s == nullptr) {
                return wrongType("string");
            }
            std::string wrong = checkText(s->get());
            if (wrong.empty() && spec.check != nullptr)
                wrong = spec.check(s->get());
            if (!wrong.empty()) {
                what = withAllowed(std::move(wrong), spec);
                return std::nullopt;
            }
            return Value(s->get());
        }
        case Kind::Enum: {
            const auto* s = node.as_string();
            if (s == nullptr) {
                return wrongType("string");
            }
            const auto found = std::find(spec.choices.begin(), spec.choices.end(), s->get());
            if (found == spec.choices.end()) {
                what = withAllowed("unknown value " + excerpt(s->get()), spec);
                return std::nullopt;
            }
            return Value(static_cast<std::int64_t>(found - spec.choices.begin()));
        }
        case Kind::IntList: {
            const auto* array = node.as_array();
            if (array == nullptr)
                return wrongType("array of integers");
            if (array->empty() || static_cast<int>(array->size()) > spec.maxItems) {
                what = withAllowed(std::to_string(array->size()) + " entries", spec);
                return std::nullopt;
            }
            std::vector<std::int64_t> values;
            for (const toml::node& item : *array) {
                const auto* i = item.as_integer();
                if (i == nullptr) {
                    what = "expected integers, got " + std::string(nodeTypeName(item));
                    return std::nullopt;
                }
                const std::int64_t v = i->get();
                if (static_cast<double>(v) < spec.min || static_cast<double>(v) > spec.max)
                    return outOfRange(std::to_string(v));
                if (std::find(values.begin(), values.end(), v) != values.end()) {
                    what = withAllowed(std::to_string(v) + " is listed twice", spec);
                    return std::nullopt;
                }
                values.push_back(v);
            }
            return Value(std::move(values));
        }
        case Kind::WordList: {
            const auto* array = node.as_array();
            if (array == nullptr)
                return wrongType("array of strings");
            if (static_cast<int>(array->size()) > spec.maxItems) {
                what = withAllowed(std::to_string(array->size()) + " entries", spec);
                return std::nullopt;
            }
            std::vector<std::string> words;
            for (const toml::node& item : *array) {
                const auto* w = item.as_string();
                if (w == nullptr) {
                    what = "expected strings, got " + std::string(nodeTypeName(item));
                    return std::nullopt;
                }
                std::string wrong = checkText(w->get());
                if (wrong.empty() && spec.check != nullptr)
                    wrong = spec.check(w->get());
                if (!wrong.empty()) {
                    what = withAllowed(std::move(wrong), spec);
                    return std::nullopt;
                }
                words.push_back(w->get());
            }
            return Value(std::move(words));
        }
        case Kind::Rate: {
            if (const auto* s = node.as_string()) {
                if (s->get() == "native" || s->get() == "max") {
                    return Value(s->get());
                }
                what = withAllowed("unknown value " + excerpt(s->get()), spec);
                return std::nullopt;
            }
            const auto v = numberOf(node);
            if (!v) {
                return wrongType("string or number");
            }
            if (!(*v >= spec.min && *v <= spec.max)) {
                return outOfRange(config_schema::formatNumber(*v));
            }
            return Value(*v);
        }
    }
    return std::nullopt;
}

std::string sectionList()
{
    std::string list;
    for (std::string_view section : config_schema::sections()) {
        list += (list.empty() ? "" : ", ") + std::string(section);
    }
    return list;
}

/// Checks every key of one parsed document and stores the good ones into `config`.
void applyTable(const toml::table& root, Config& config, Problems& problems)
{
    const auto known = config_schema::sections();
    for (const auto& [sectionKey, sectionNode] : root) {
        const std::string section = keyText(sectionKey.str());
        if (std::find(known.begin(), known.end(), sectionKey.str()) == known.end()) {
            problems.add(sectionKey.source(), section,
                         "unknown section (allowed: " + sectionList() + ")");
            continue;
        }
        const auto* table = sectionNode.as_table();
        if (table == nullptr) {
            problems.add(sectionNode.source(), section,
                         "expected table, got " + std::string(nodeTypeName(sectionNode)));
            continue;
        }
        for (const auto& [key, node] : *table) {
            const std::string name = section + "." + keyText(key.str());
            const KeySpec* spec = config_schema::findKey(name);
            if (spec == nullptr) {
                problems.add(key.source(), name,
                             "unknown key (allowed: " + config_schema::keysOf(section) + ")");
                continue;
            }
            std::string what;
            if (const auto value = checkValue(*spec, node, what)) {
                spec->set(config, *value);
            } else {
                problems.add(node.source(), name, std::move(what));
            }
        }
    }
}

/// What an empty document is told. An empty or comment-only file is far more likely a mistake
/// (wrong file, truncated copy) than a wish for all defaults.
constexpr const char* kEmptyFile = "file is empty (expected at least one [section])";
constexpr const char* kNothingToSet = "nothing to set (expected KEY=VALUE)";

/// Parses one TOML text and applies it. A syntax error is the file's ("config") unless the text
/// is a --set of one known key, whose allowed values then help.
void applyText(std::string_view text, Config& config, Problems& problems, const char* ifEmpty,
               const KeySpec* setKey = nullptr)
{
    if (text.size() > kMaxFileBytes) {
        problems.addAtStart("config", "file is too large: " + std::to_string(text.size()) +
                                          " bytes (allowed: up to " +
                                          std::to_string(kMaxFileBytes) + " bytes)");
        return;
    }
    try {
        const toml::table root = toml::parse(text);
        if (root.empty()) {
            problems.addAtStart("config", ifEmpty);
            return;
        }
        applyTable(root, config, problems);
    } catch (const toml::parse_error& error) {
        if (setKey != nullptr) {
            problems.add(error.source(), std::string(setKey->name),
                         withAllowed(oneLine(error.description()), *setKey));
        } else {
            problems.add(error.source(), "config", oneLine(error.description()));
        }
    }
}

Config builtInDefaults()
{
    Config config;
    const Layer layer{kBuiltInOrigin, {}, {}};
    Problems problems(layer);
    applyText(kDefaultConfigToml, config, problems, kEmptyFile);
    std::vector<ConfigProblem> all;
    problems.moveInto(all);
    if (!all.empty()) {
        throw ConfigError(std::move(all));  // a build with a broken config/mirror.toml
    }
    config.origin = kBuiltInOrigin;
    return config;
}

std::string_view trim(std::string_view text)
{
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string_view::npos) {
        return {};
    }
    const auto last = text.find_last_not_of(" \t");
    return text.substr(first, last - first + 1);
}

/// Applies one --set KEY=VALUE. VALUE is TOML; as a convenience for shells (which eat the quotes
/// of source.spec="file:x.avi"), a value of a string key that is not valid TOML is taken as the
/// literal string.
void applySet(const std::string& set, int index, Config& config, std::vector<ConfigProblem>& all)
{
    Layer layer{"--set", index, {}};
    Problems problems(layer);
    // One --set is one key: a line break would let its text set a second one.
    if (set.find_first_of("\n\r") != std::string::npos) {
        problems.addAtStart("config", "one key per --set, got a line break in " + excerpt(set) +
                                          " (allowed: KEY=VALUE on one line)");
        problems.moveInto(all);
        return;
    }
    const auto equals = set.find('=');
    if (equals == std::string::npos || trim(std::string_view(set).substr(0, equals)).empty()) {
        problems.addAtStart("config", "expected KEY=VALUE, got " + excerpt(set) +
                                          " (allowed: KEY is section.key, VALUE is TOML)");
        problems.moveInto(all);
        return;
    }
    const std::string key(trim(std::string_view(set).substr(0, equals)));
    const std::string_view value = trim(std::string_view(set).substr(equals + 1));
    const KeySpec* spec = config_schema::findKey(key);
    const bool stringKey = spec != nullptr && spec->kind != Kind::Bool && spec->kind != Kind::Int &&
                           spec->kind != Kind::Float && spec->kind != Kind::IntList &&
                           spec->kind != Kind::WordList;
    if (stringKey && !value.empty() && value.front() != '"' && value.front() != '\'') {
        bool validToml = true;
        try {
            (void)toml::parse(set);
        } catch (const toml::parse_error&) {
            validToml = false;
        }
        if (!validToml) {
            layer.column = static_cast<int>(set.find_first_not_of(" \t", equals + 1)) + 1;
            applyText(key + " = " + quoted(value), config, problems, kNothingToSet);
            problems.moveInto(all);
            return;
        }
    }
    applyText(set, config, problems, kNothingToSet, spec);
    problems.moveInto(all);
}

std::string joinLines(const std::vector<ConfigProblem>& problems)
{
    std::string text;
    for (const ConfigProblem& problem : problems) {
        if (!text.empty())
            text += '\n';
        text += problem.format();
    }
    return text;
}

}  // namespace

std::string ConfigProblem::format() const
{
    return file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + key + ": " +
           message;
}

ConfigError::ConfigError(std::vector<ConfigProblem> problems)
    : std::runtime_error(joinLines(problems)), problems_(std::move(problems))
{
}

Config parseConfig(const std::string& tomlText, const std::string& fileName)
{
    Config config = builtInDefaults();
    const Layer layer{fileName, {}, {}};
    Problems problems(layer);
    applyText(tomlText, config, problems, kEmptyFile);
    std::vector<ConfigProblem> all;
    problems.moveInto(all);
    if (!all.empty()) {
        throw ConfigError(std::move(all));
    }
    config.origin = fileName;
    return config;
}

Config loadConfig(const ConfigRequest& request)
{
    Config config = builtInDefaults();
    std::vector<ConfigProblem> all;

    const std::string path = request.path.empty() ? kDefaultConfigPath : request.path;
    vision::BoundedFile file = vision::readBoundedFile(path, kMaxFileBytes);
    // Without --config a missing file just means "use the defaults"; one that exists but cannot be
    // read is still an error, so a broken installation does not silently run on defaults.
    if (file.status != vision::BoundedFile::Status::Missing || request.pathExplicit) {
        const Layer layer{path, {}, {}};
        Problems problems(layer);
        if (file.status == vision::BoundedFile::Status::Ok) {
            applyText(file.text, config, problems, kEmptyFile);
            config.origin = path;
        } else {
            problems.addAtStart("config", file.problem);
        }
        problems.moveInto(all);
    }

    for (std::size_t i = 0; i < request.sets.size(); ++i) {
        applySet(request.sets[i], static_cast<int>(i) + 1, config, all);
    }
    if (!all.empty()) {
        throw ConfigError(std::move(all));
    }
    return config;
}

std::string toToml(const Config& config)
{
    // Where it came from (config.origin) is the caller's to print: it is not part of the config.
    std::string text = "# Every key with its type, range and meaning: config/SCHEMA.md.\n";
    std::string_view section;
    for (const KeySpec& spec : config_schema::schema()) {
        if (spec.section() != section) {
            section = spec.section();
            text += "\n[" + std::string(section) + "]\n";
        }
        text += "# " + std::string(spec.doc) + "\n";
        text += std::string(spec.key()) + " = " +
                config_schema::formatValue(spec, spec.get(config)) + "\n";
    }
    return text;
}

}  // namespace firmware
