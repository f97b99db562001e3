// The schema's keys and values as text. See config_value_text.hpp.

#include "config_value_text.hpp"

#include <charconv>
#include <cstdio>
#include <system_error>

namespace firmware::config_schema {

namespace {

std::string range(const KeySpec& spec)
{
    return formatNumber(spec.min) + ".." + formatNumber(spec.max);
}

}  // namespace

std::string_view typeName(const KeySpec& spec)
{
    switch (spec.kind) {
        case Kind::Bool:
            return "boolean";
        case Kind::Int:
            return "integer";
        case Kind::Float:
            return "float";
        case Kind::String:
        case Kind::Enum:
            return "string";
        case Kind::Rate:
            return "string or number";
        case Kind::IntList:
            return "array of integers";
        case Kind::WordList:
            return "array of strings";
    }
    return "?";
}

std::string allowed(const KeySpec& spec)
{
    switch (spec.kind) {
        case Kind::Bool:
            return "true, false";
        case Kind::Int: {
            if (spec.oneOf.empty())
                return (spec.even ? "even numbers " : "") + range(spec);
            std::string list;
            for (const int value : spec.oneOf)
                list += (list.empty() ? "" : ", ") + std::to_string(value);
            return list;
        }
        case Kind::Float:
            return range(spec);
        case Kind::String:
            return std::string(spec.stringForms);
        case Kind::Enum: {
            std::string list;
            for (std::string_view choice : spec.choices) {
                list += (list.empty() ? "" : ", ") + quoted(choice);
            }
            return list;
        }
        case Kind::Rate:
            return R"("native", "max" or a number )" + range(spec);
        case Kind::IntList: {
            std::string text = "1..";
            text += std::to_string(spec.maxItems);
            text += " distinct integers, each ";
            text += range(spec);
            return text;
        }
        case Kind::WordList: {
            std::string text = "up to ";
            text += std::to_string(spec.maxItems);
            text += " of ";
            text += spec.stringForms;
            return text;
        }
    }
    return {};
}

std::string formatValue(const KeySpec& spec, const Value& value)
{
    switch (spec.kind) {
        case Kind::Bool:
            return std::get<bool>(value) ? "true" : "false";
        case Kind::Int:
            return std::to_string(std::get<std::int64_t>(value));
        case Kind::Float: {
            // A float key must print as a TOML float (30.0, not 30) so the type survives a reload.
            std::string text = formatNumber(std::get<double>(value));
            if (text.find_first_of(".eEni") == std::string::npos) {
                text += ".0";
            }
            return text;
        }
        case Kind::String:
            return quoted(std::get<std::string>(value));
        case Kind::Enum: {
            const auto index = static_cast<std::size_t>(std::get<std::int64_t>(value));
            return quoted(index < spec.choices.size() ? spec.choices[index] : "?");
        }
        case Kind::Rate:
            if (const auto* text = std::get_if<std::string>(&value)) {
                return quoted(*text);
            }
            // An integral rate prints as an integer: fine.
            return formatNumber(std::get<double>(value));
        case Kind::IntList: {
            std::string text = "[";
            for (const std::int64_t v : std::get<std::vector<std::int64_t>>(value)) {
                if (text.size() > 1)
                    text += ", ";
                text += std::to_string(v);
            }
            return text + "]";
        }
        case Kind::WordList: {
            std::string text = "[";
            for (const std::string& w : std::get<std::vector<std::string>>(value)) {
                if (text.size() > 1)
                    text += ", ";
                text += quoted(w);
            }
            return text + "]";
        }
    }
    return {};
}

std::string quoted(std::string_view text)
{
    std::string out = "\"";
    for (const char ch : text) {
        const auto byte = static_cast<unsigned char>(ch);
        switch (ch) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\b':
                out += "\\b";
                break;
            case '\t':
                out += "\\t";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\f':
                out += "\\f";
                break;
            case '\r':
                out += "\\r";
                break;
            default:
                if (byte < 0x20 || byte == 0x7f) {
                    char escape[8];
                    std::snprintf(escape, sizeof escape, "\\u%04X", static_cast<unsigned>(byte));
                    out += escape;
                } else {
                    out += ch;  // UTF-8 passes through: TOML strings are UTF-8
                }
        }
    }
    return out + "\"";
}

std::string excerpt(std::string_view text)
{
    constexpr std::size_t kShown = 64;
    if (text.size() <= kShown)
        return quoted(text);
    std::size_t cut = kShown;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80)
        --cut;  // not inside a UTF-8 character
    return quoted(text.substr(0, cut)) + "... (" + std::to_string(text.size()) + " bytes)";
}

std::string formatNumber(double value)
{
    // Plain digits read best ("100000", not "1e+05"); exponents only for very large or small
    // values.
    char text[64];
    auto result = std::to_chars(text, text + sizeof text, value, std::chars_format::fixed);
    if (result.ec != std::errc() || result.ptr - text > 20) {
        result = std::to_chars(text, text + sizeof text, value);
    }
    return std::string(text, result.ptr);
}

}  // namespace firmware::config_schema
