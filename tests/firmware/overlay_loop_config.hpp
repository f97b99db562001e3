#pragma once
// The config the frame-loop tests of overlays run with: a small headless display, no card, no
// summaries, near-instant fades (fades are OverlaySelection's tests; here no wall-clock waits)
// and no special day (on 24 December a face would otherwise start in the Santa hat).

#include "firmware/config.hpp"
#include "firmware/day_calendar.hpp"
#include "test_paths.hpp"

#include <cstdio>
#include <ctime>
#include <string>

inline firmware::Config overlayLoopConfig(const std::string& name, const std::string& initial)
{
    firmware::Config config;
    config.display.spec = "headless:" + testing_support::freshOutputDir(name);
    config.display.width = 640;
    config.display.height = 360;
    config.display.snapshotEvery = 0;
    config.card.enabled = false;
    config.log.summaryIntervalS = 0;
    config.overlay.fadeMs = 1;
    config.overlay.initial = initial;
    config.state.dir = testing_support::binaryDir() + "/test-output/" + name + "_state";
    config.days.dates.clear();
    return config;
}

/// "MM-DD" of today, local time (the calendar's and the birthdays' dates).
inline std::string todayMonthDay()
{
    const firmware::CalendarDay d = firmware::localDay(std::time(nullptr));
    char text[8];
    std::snprintf(text, sizeof text, "%02d-%02d", d.month, d.day);
    return text;
}
