#pragma once
// The schema's keys and values as text: a key's type and allowed values as the messages and
// config/SCHEMA.md name them, and values as TOML literals that parse back to the same value.
// Private to the config module and its tests.

#include "config_schema.hpp"

#include <string>
#include <string_view>

namespace firmware::config_schema {

/// The type as the docs and messages name it: "boolean", "integer", "float", "string", ...
std::string_view typeName(const KeySpec& spec);
/// The allowed values, e.g. `16..7680`, `"cover", "contain"`.
std::string allowed(const KeySpec& spec);
/// The value as a TOML literal that parses back to the same value.
std::string formatValue(const KeySpec& spec, const Value& value);

/// A TOML basic string literal with everything escaped that must be ("a\"b").
std::string quoted(std::string_view text);
/// A value quoted for a message: `quoted` of its first 64 bytes, and when it is longer, "..." and
/// its length, so one problem stays one short line whatever was typed.
std::string excerpt(std::string_view text);
/// The shortest text that reads back as the same double ("30", "0.1", "1e+20").
std::string formatNumber(double value);

}  // namespace firmware::config_schema
