#pragma once
// The forms the String keys of the schema accept (KeySpec::check): each returns "" when the value
// is fine, else one line saying what is wrong. Private to the config schema.

#include <cstddef>
#include <string>
#include <string_view>

namespace firmware::config_schema {

/// The longest string value, in bytes (a path is at most 4096 bytes on Linux).
inline constexpr std::size_t kMaxStringBytes = 4096;
/// Every string value, before its key's own check: at most kMaxStringBytes, and printable (no
/// control character: a value with a line break or an escape sequence would split the problem's
/// line or reach the terminal raw).
std::string checkText(std::string_view value);

/// `[source] spec`: "auto", "demo", "synthetic", "libcamera[:ID]", "file:PATH", "v4l2:DEVICE".
std::string checkSourceSpec(std::string_view value);
/// `[display] spec`: "auto", "drm[:CARD]", "window", "headless:DIR".
std::string checkDisplaySpec(std::string_view value);
/// Any path, or empty for "the built-in one".
std::string checkOptionalPath(std::string_view value);
/// A file path, not empty.
std::string checkPath(std::string_view value);
/// A button action's name (parseButtonAction).
std::string checkButtonAction(std::string_view value);
/// "none" or an overlay's name, not empty.
std::string checkOverlayName(std::string_view value);
/// "" (no serial console) or an absolute device path.
std::string checkSerial(std::string_view value);
/// "", "preferred", "WxH" or "WxH@Hz" (platform::parseDisplayMode).
std::string checkDisplayMode(std::string_view value);
/// A rule of the overlay precedence: person, birthday, day, weather or global.
std::string checkOverlayRule(std::string_view value);
/// A special day: "MM-DD[..MM-DD] NAME" or "YYYY-MM-DD[..YYYY-MM-DD] NAME" (parseDayRule).
std::string checkDayRule(std::string_view value);
/// "" (no forecast), an http:// or https:// URL, or file:PATH.
std::string checkForecastSource(std::string_view value);
/// A directory path, not empty.
std::string checkDirectory(std::string_view value);

}  // namespace firmware::config_schema
