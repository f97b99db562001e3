#include "firmware/weather_forecast.hpp"

#include <nlohmann/json.hpp>

namespace firmware {

namespace {

constexpr int kMaxDepth = 64;

// nlohmann's parser recurses once per nesting level: a hostile answer of a million '[' would
// exhaust the stack before it fails, so the depth is checked first (outside strings).
bool withinDepth(std::string_view text) noexcept
{
    int depth = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxDepth)
                return false;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return true;
}

// The integer at `object[key]` (a whole number), or at `object[key][0]` when it is an array.
bool codeAt(const nlohmann::json& object, const char* key, bool first, int& code)
{
    if (!object.is_object())
        return false;
    const auto it = object.find(key);
    if (it == object.end())
        return false;
    const nlohmann::json* v = &*it;
    if (first) {
        if (!v->is_array() || v->empty())
            return false;
        v = &(*v)[0];
    }
    if (v->is_number_integer() || v->is_number_unsigned()) {
        const auto n = v->get<long long>();
        code = n < -1 || n > 1000 ? 1000 : static_cast<int>(n);
        return true;
    }
    if (v->is_number_float()) {
        const double d = v->get<double>();
        if (d != static_cast<double>(static_cast<long long>(d)) || d < -1 || d > 1000)
            return false;
        code = static_cast<int>(d);
        return true;
    }
    return false;
}

}  // namespace

bool parseForecast(std::string_view json, int& code, std::string& problem)
{
    if (!withinDepth(json)) {
        problem = "nested deeper than " + std::to_string(kMaxDepth);
        return false;
    }
    const nlohmann::json doc = nlohmann::json::parse(json, nullptr, false);
    if (doc.is_discarded()) {
        problem = "not JSON";
        return false;
    }
    int c = -1;
    const bool found =
        (doc.contains("current") && codeAt(doc["current"], "weather_code", false, c)) ||
        (doc.contains("current_weather") &&
         codeAt(doc["current_weather"], "weathercode", false, c)) ||
        (doc.contains("daily") && (codeAt(doc["daily"], "weather_code", true, c) ||
                                   codeAt(doc["daily"], "weathercode", true, c)));
    if (!found) {
        problem =
            "the answer has no weather code (current.weather_code, "
            "current_weather.weathercode or daily.weather_code)";
        return false;
    }
    if (c < 0 || c > 99) {
        problem = "the weather code " + std::to_string(c) + " is not a WMO code (0-99)";
        return false;
    }
    code = c;
    return true;
}

std::string forecastCacheText(int code, std::int64_t fetchedUnix)
{
    return "{\"current\":{\"weather_code\":" + std::to_string(code) +
           "},\"fetched_unix\":" + std::to_string(fetchedUnix) + "}\n";
}

std::int64_t fetchedUnixOf(std::string_view cacheJson)
{
    if (!withinDepth(cacheJson))
        return 0;
    const nlohmann::json doc = nlohmann::json::parse(cacheJson, nullptr, false);
    if (doc.is_discarded() || !doc.is_object())
        return 0;
    const auto it = doc.find("fetched_unix");
    return it != doc.end() && it->is_number_integer() ? it->get<std::int64_t>() : 0;
}

int weatherKindFor(std::span<const WeatherOverlay> kinds, int code) noexcept
{
    if (code < 0)
        return -1;
    for (std::size_t k = 0; k < kinds.size(); ++k)
        for (const int c : kinds[k].codes)
            if (c == code)
                return static_cast<int>(k);
    return -1;
}

const std::string& overlayForWeather(std::span<const WeatherOverlay> kinds, int code) noexcept
{
    static const std::string kNone;
    const int k = weatherKindFor(kinds, code);
    return k < 0 ? kNone : kinds[static_cast<std::size_t>(k)].overlay;
}

const char* weatherCodeText(int code) noexcept
{
    // WMO 4677 as Open-Meteo uses it.
    if (code == 0)
        return "clear sky";
    if (code >= 1 && code <= 3)
        return "partly cloudy";
    if (code == 45 || code == 48)
        return "fog";
    if (code >= 51 && code <= 57)
        return "drizzle";
    if ((code >= 61 && code <= 67) || (code >= 80 && code <= 82))
        return "rain";
    if ((code >= 71 && code <= 77) || code == 85 || code == 86)
        return "snow";
    if (code >= 95 && code <= 99)
        return "thunderstorm";
    return code < 0 ? "no forecast" : "other";
}

}  // namespace firmware
