#pragma once
// The weather forecast as the mirror uses it (§6.2 of the dissertation: "a hat that conveys the
// weather forecast (sun hat vs. rain hat)"): one WMO weather code (0 clear sky ... 99 thunderstorm
// with hail, the code of Open-Meteo's `current` and `daily` answers) read from a forecast
// service's JSON, and the overlay the config maps it to.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace firmware {

/// The weather code of an Open-Meteo answer (https://open-meteo.com/en/docs):
/// `current.weather_code` when present, else the older `current_weather.weathercode`, else today's
/// `daily.weather_code[0]` (or `daily.weathercode[0]`). Also this module's own cache, which has
/// the same `current.weather_code`. False with one line in `problem` for anything else: not JSON,
/// nested deeper than 64, no code, a code outside 0..99.
bool parseForecast(std::string_view json, int& code, std::string& problem);

/// The cache file's text: `{"current":{"weather_code":N},"fetched_unix":T}` (parseForecast reads
/// it; fetchedUnixOf gives T back, 0 when absent).
std::string forecastCacheText(int code, std::int64_t fetchedUnix);
std::int64_t fetchedUnixOf(std::string_view cacheJson);

/// A weather kind the config maps to an overlay (`[weather] sun`, `rain`, `snow` and their
/// `*_codes`).
struct WeatherOverlay {
    std::string kind;        ///< "sun", "rain" or "snow"
    std::string overlay;     ///< a catalogue name; "" = none
    std::vector<int> codes;  ///< the WMO codes that mean it
};

/// The first kind listing `code`, -1 when none does or code < 0.
int weatherKindFor(std::span<const WeatherOverlay> kinds, int code) noexcept;
/// The overlay for `code` (the first kind listing it), "" when none does or code < 0.
const std::string& overlayForWeather(std::span<const WeatherOverlay> kinds, int code) noexcept;

/// What a WMO code says in a few words ("clear sky", "rain", "snow fall" ...), for `status`.
const char* weatherCodeText(int code) noexcept;

}  // namespace firmware
