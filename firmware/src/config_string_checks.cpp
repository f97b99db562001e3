// The forms the String keys accept. See config_string_checks.hpp.

#include "config_string_checks.hpp"

#include "config_value_text.hpp"
#include "firmware/button_actions.hpp"
#include "platform/display_mode.hpp"

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
            return quoted(value) + " needs a " + std::string(argument) + " after " + quoted(prefix);
        }
    }
    return "unknown " + std::string(what) + " " + quoted(value);
}

}  // namespace

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
    return "unknown action " + quoted(value);
}

std::string checkOverlayName(std::string_view value)
{
    if (value.empty())
        return "needs \"none\" or an overlay name";
    return checkOptionalPath(value);
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
    platform::DisplayModeRequest mode;
    std::string error;
    if (platform::parseDisplayMode(value, mode, error))
        return {};
    return error.empty() ? "unknown mode " + quoted(value) : error;
}

std::string checkDirectory(std::string_view value)
{
    if (value.empty())
        return "needs a directory";
    return checkOptionalPath(value);
}

}  // namespace firmware::config_schema
