// The forms the String keys accept. See config_string_checks.hpp.

#include "config_string_checks.hpp"

#include "config_value_text.hpp"
#include "firmware/button_actions.hpp"
#include "firmware/day_calendar.hpp"
#include "firmware/overlay_rules.hpp"
#include "platform/display_mode.hpp"

#include <cstdio>
#include <initializer_list>
#include <utility>

namespace firmware::config_schema {

namespace {

/// A spec is one of `names`, or PREFIX:ARGUMENT with a non-empty argument for one of `prefixes`
/// (each given with the word for its argument, for the message).
std::string checkSpec(std::string_view value, std::string_view what,
                      std::initializer_list<std::string_view> names,
                      std::initializer_list<std::pair<std::string_view, std::string_view>> prefixes)
{
    for (std::string_view name : names) {
        if (value == name) {
            return {};
        }
    }
    for (const auto& [prefix, argument] : prefixes) {
        if (value.starts_with(prefix)) {
            if (value.size() > prefix.size()) {
                return {};
            }
            return excerpt(value) + " needs a " + std::string(argument) + " after " +
                   quoted(prefix);
        }
    }
    return "unknown " + std::string(what) + " " + excerpt(value);
}

}  // namespace

std::string checkText(std::string_view value)
{
    if (value.size() > kMaxStringBytes)
        return std::to_string(value.size()) + " bytes is too long (at most " +
               std::to_string(kMaxStringBytes) + ")";
    for (std::size_t i = 0; i < value.size(); ++i) {
        const auto byte = static_cast<unsigned char>(value[i]);
        if (byte < 0x20 || byte == 0x7f) {
            char code[8];
            std::snprintf(code, sizeof code, "0x%02X", byte);
            return std::string("control character ") + code + " at byte " + std::to_string(i + 1) +
                   " of " + excerpt(value);
        }
    }
    return {};
}

// libcamera, v4l2, drm and window are accepted here so a config written for a later build still
// validates; the source/display factories say when one is not built into this version.
std::string checkSourceSpec(std::string_view value)
{
    return checkSpec(value, "source", {"auto", "demo", "synthetic", "libcamera"},
                     {{"file:", "path"}, {"libcamera:", "camera id"}, {"v4l2:", "device path"}});
}

std::string checkDisplaySpec(std::string_view value)
{
    return checkSpec(value, "display", {"auto", "drm", "window"},
                     {{"headless:", "directory"}, {"drm:", "card"}});
}

std::string checkOptionalPath(std::string_view value)
{
    if (value.find('\0') != std::string_view::npos)
        return "a path cannot contain a NUL character";
    return {};
}

std::string checkPath(std::string_view value)
{
    if (value.empty())
        return "needs a file path";
    return checkOptionalPath(value);
}

std::string checkButtonAction(std::string_view value)
{
    ButtonAction action{};
    if (parseButtonAction(value, action))
        return {};
    return "unknown action " + excerpt(value);
}

std::string checkOverlayName(std::string_view value)
{
    if (value.empty())
        return "needs \"none\" or an overlay name";
    return checkOptionalPath(value);
}

std::string checkOverlayRule(std::string_view value)
{
    OverlayRule rule{};
    return parseOverlayRule(value, rule) ? ""
                                         : "needs one of person, birthday, day, weather, global";
}

std::string checkDayRule(std::string_view value)
{
    DayRule rule;
    std::string problem;
    if (!parseDayRule(value, rule, problem))
        return problem;
    return checkOverlayName(rule.overlay);
}

std::string checkForecastSource(std::string_view value)
{
    if (value.empty())
        return "";
    if (value.starts_with("http://") || value.starts_with("https://"))
        return checkText(value);
    if (value.starts_with("file:") && value.size() > 5)
        return checkOptionalPath(value.substr(5));
    return "needs \"\" (none), an http:// or https:// URL, or file:PATH";
}

std::string checkSerial(std::string_view value)
{
    if (!value.empty() && value.front() != '/')
        return "needs \"\" (none) or an absolute device path";
    return checkOptionalPath(value);
}

std::string checkDisplayMode(std::string_view value)
{
    if (value.empty() || value == "preferred")
        return {};
    // The parser names the whole value in its message; "7680x4320@240.000" is the longest mode.
    constexpr std::size_t kLongestMode = 24;
    platform::DisplayModeRequest mode;
    std::string error;
    if (value.size() <= kLongestMode && platform::parseDisplayMode(value, mode, error))
        return {};
    return error.empty() ? "unknown mode " + excerpt(value) : error;
}

std::string checkDirectory(std::string_view value)
{
    if (value.empty())
        return "needs a directory";
    return checkOptionalPath(value);
}

}  // namespace firmware::config_schema
