#pragma once
// The configuration schema, private to the config module and its tests: every key of the config
// file with its type, allowed values, one-line meaning and where it is stored in Config. Adding a
// key means adding one entry to the table in config_schema.cpp (and the key to config/mirror.toml
// and config/SCHEMA.md; config_test fails until all three agree).

#include "firmware/config.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace firmware::config_schema {

/// How a key's value is written in TOML and checked.
enum class Kind {
    Bool,
    Int,     ///< TOML integer in [min, max] (a float is the wrong type)
    Float,   ///< TOML float or integer in [min, max]
    String,  ///< TOML string whose form `check` accepts
    Enum,    ///< one of `choices`
    Rate,    ///< "native", "max" or a number in [min, max]
    IntList,   ///< TOML array of 1..maxItems distinct integers, each in [min, max]
    WordList,  ///< TOML array of 0..maxItems strings, each accepted by `check`
};

/// A checked value on its way into or out of Config. Enum values travel as the index into
/// KeySpec::choices (the choices are listed in the order of the C++ enum); a Rate travels as the
/// string "native"/"max" or as the fps (double).
using Value = std::variant<bool, std::int64_t, double, std::string, std::vector<std::int64_t>,
                           std::vector<std::string>>;

/// Checks the form of a String value: empty if it is fine, else what is wrong (one line).
using StringCheck = std::string (*)(std::string_view value);

/// One key of the config file.
struct KeySpec {
    std::string_view name{};  ///< dotted, "section.key"
    Kind kind = Kind::Bool;
    double min = 0.0;  ///< Int, Float, Rate: inclusive range
    double max = 0.0;
    bool even = false;                            ///< Int: odd values are rejected
    std::span<const int> oneOf{};                 ///< Int: when not empty, the only values allowed
    int maxItems = 0;                             ///< IntList, WordList: most entries
    std::span<const std::string_view> choices{};  ///< Enum
    StringCheck check = nullptr;                  ///< String, WordList (each word)
    std::string_view stringForms{};               ///< String: the accepted forms, for messages/docs
    std::string_view doc{};                       ///< one line, what the key means
    void (*set)(Config& config, const Value& value) = nullptr;
    Value (*get)(const Config& config) = nullptr;

    std::string_view section() const { return name.substr(0, name.find('.')); }
    std::string_view key() const { return name.substr(name.find('.') + 1); }
};

/// Every key, grouped by section, in the order they are printed and documented.
std::span<const KeySpec> schema();
/// The key with that dotted name, or nullptr.
const KeySpec* findKey(std::string_view dottedName);
/// The section names in schema order.
std::vector<std::string_view> sections();
/// The keys of one section in schema order, e.g. "spec, width, height".
std::string keysOf(std::string_view section);

}  // namespace firmware::config_schema
