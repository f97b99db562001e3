#pragma once
// AutomaticOverlays: what the calendar and the weather offer the faces (§6.2 of the
// dissertation: special hats for special days, a hat for the forecast). Resolves `[days]` and
// `[weather]` against the catalogue at start-up (a name the catalogue lacks is one warning and
// that rule is left out), runs the WeatherService, and once a second tells the OverlaySelection
// what the day and the weather offer (OverlaySelection::setAutomatic).

#include "firmware/command_shell.hpp"
#include "firmware/config.hpp"
#include "firmware/day_calendar.hpp"
#include "firmware/overlay_selection.hpp"
#include "firmware/weather_forecast.hpp"
#include "firmware/weather_service.hpp"

#include <cstdint>
#include <ctime>
#include <memory>
#include <vector>

namespace firmware {

class AutomaticOverlays {
public:
    /// `selection` gives the catalogue's names (not kept). A weather source the service refuses
    /// is one error line and no forecast.
    AutomaticOverlays(const Config& config, const OverlaySelection& selection);

    /// Offers today's and the weather's overlays to `selection`; recomputed at most once a
    /// second of wall-clock time. No allocation.
    void apply(OverlaySelection& selection) noexcept;
    /// `day: ...` and `weather: ...` lines for `status` and `overlay`.
    void format(const OverlaySelection& selection, Reply& reply) const noexcept;

private:
    void decide(OverlaySelection& selection, std::time_t now) noexcept;

    DayCalendar calendar_;
    std::vector<int> dayOverlay_;  ///< per calendar rule, its catalogue index
    std::vector<WeatherOverlay> weatherKinds_;
    std::vector<int> weatherOverlay_;  ///< per kind, its catalogue index (-1: none)
    std::unique_ptr<WeatherService> weather_;
    std::time_t decidedAt_ = 0;
    const DayRule* today_ = nullptr;
    int todayIndex_ = -1;
};

}  // namespace firmware
