#include "automatic_overlays.hpp"

#include "firmware/log.hpp"

#include <chrono>
#include <exception>
#include <tuple>

namespace firmware {

namespace {

std::vector<int> asCodes(const std::vector<std::int64_t>& codes)
{
    return {codes.begin(), codes.end()};
}

}  // namespace

AutomaticOverlays::AutomaticOverlays(const Config& config, const OverlaySelection& selection)
{
    // The days: each rule was checked by the config; only the names are checked here.
    std::vector<DayRule> rules;
    for (const std::string& text : config.days.dates) {
        DayRule rule;
        std::string problem;
        if (!parseDayRule(text, rule, problem)) {
            MIRROR_LOG_WARN("days.dates: %s; ignored", problem.c_str());
            continue;
        }
        const int index = selection.find(rule.overlay);
        if (index < 0 && rule.overlay != "none") {
            MIRROR_LOG_WARN("days.dates: '%s': the catalogue has no overlay '%s'; ignored",
                            text.c_str(), rule.overlay.c_str());
            continue;
        }
        rules.push_back(std::move(rule));
        dayOverlay_.push_back(index);
    }
    calendar_ = DayCalendar(std::move(rules));

    const WeatherConfig& w = config.weather;
    for (const auto& [kind, name, codes] :
         {std::tuple{"sun", &w.sun, &w.sunCodes}, std::tuple{"rain", &w.rain, &w.rainCodes},
          std::tuple{"snow", &w.snow, &w.snowCodes}}) {
        int index = -1;
        if (*name != "none" && (index = selection.find(*name)) < 0)
            MIRROR_LOG_WARN("weather.%s: the catalogue has no overlay '%s'; none for it", kind,
                            name->c_str());
        weatherKinds_.push_back({kind, index >= 0 ? *name : std::string(), asCodes(*codes)});
        weatherOverlay_.push_back(index);
    }
    if (!w.source.empty()) {
        WeatherServiceOptions o;
        o.source = w.source;
        o.interval = std::chrono::minutes(w.intervalMinutes);
        o.timeout = std::chrono::seconds(w.timeoutSeconds);
        o.cacheDir = config.state.dir;
        try {
            weather_ = std::make_unique<WeatherService>(o);
        } catch (const std::exception& e) {
            MIRROR_LOG_ERROR("weather: %s; no forecast", e.what());
        }
    }
    // localtime_r reads the time zone once; do it here, not in the frame loop.
    (void)localDay(std::time(nullptr));
}

void AutomaticOverlays::apply(OverlaySelection& selection) noexcept
{
    const std::time_t now = std::time(nullptr);
    if (now == decidedAt_)
        return;
    decidedAt_ = now;
    decide(selection, now);
}

void AutomaticOverlays::decide(OverlaySelection& selection, std::time_t now) noexcept
{
    today_ = calendar_.ruleFor(localDay(now));
    todayIndex_ = -1;
    if (today_ != nullptr)
        todayIndex_ = dayOverlay_[static_cast<std::size_t>(today_ - calendar_.rules().data())];
    selection.setAutomatic(OverlayRule::Day, todayIndex_);
    const int kind = weather_ ? weatherKindFor(weatherKinds_, weather_->code()) : -1;
    selection.setAutomatic(OverlayRule::Weather,
                           kind < 0 ? -1 : weatherOverlay_[static_cast<std::size_t>(kind)]);
}

void AutomaticOverlays::format(const OverlaySelection& selection, Reply& reply) const noexcept
{
    if (today_ != nullptr)
        reply.printf("day: %s (%s)\n", selection.name(todayIndex_), today_->text.c_str());
    else
        reply.printf("day: none (%zu special days configured)\n", calendar_.rules().size());
    if (weather_) {
        char line[400];
        weather_->describe(line, sizeof line, static_cast<std::int64_t>(std::time(nullptr)));
        reply.printf("weather: %s: %s\n", selection.name(selection.automatic(OverlayRule::Weather)),
                     line);
    } else {
        reply.printf("weather: none (no [weather] source)\n");
    }
}

}  // namespace firmware
