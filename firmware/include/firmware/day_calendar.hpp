#pragma once
// DayCalendar: the special days of `[days] dates` and the overlay each one puts on the faces
// (§6.2 of the dissertation: "special hats for special days"). A rule is one string:
//
//   "MM-DD NAME"                      every year on that day ("12-25 santa_hat")
//   "MM-DD..MM-DD NAME"               every year from the first to the second day, both included;
//                                     it may run over the new year ("12-31..01-01 party_hat")
//   "YYYY-MM-DD NAME"                 that one day
//   "YYYY-MM-DD..YYYY-MM-DD NAME"     those days
//
// A yearly 02-29 falls on 28 February in years without a 29th (a leap-day birthday is kept on the
// last day of February). The first rule in the config's order that covers a day wins. Dates are
// the appliance's local dates (its time zone).

#include <ctime>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace firmware {

struct CalendarDay {
    int year = 1970;
    int month = 1;  ///< 1-12
    int day = 1;    ///< 1-31
    friend bool operator==(CalendarDay, CalendarDay) = default;
};

/// The local date of `t`.
CalendarDay localDay(std::time_t t) noexcept;
bool isLeapYear(int year) noexcept;
int daysInMonth(int year, int month) noexcept;

struct DayRule {
    int year = 0;  ///< 0: every year; else the dated rule's years (fromYear..toYear)
    int toYear = 0;
    int fromMonth = 1, fromDay = 1, toMonth = 1, toDay = 1;
    std::string overlay;
    std::string text;  ///< as configured, for messages

    bool covers(CalendarDay date) const noexcept;
};

/// Parses one rule; false with one line in `problem` ("'13-01 x': month 13 is not 1-12").
bool parseDayRule(std::string_view text, DayRule& rule, std::string& problem);

/// Whether the yearly date month-day is `date` (29 February kept on the 28th without a leap day).
bool isYearlyDate(int month, int day, CalendarDay date) noexcept;

class DayCalendar {
public:
    DayCalendar() = default;
    explicit DayCalendar(std::vector<DayRule> rules) : rules_(std::move(rules)) {}

    /// The first rule covering `date`, or null.
    const DayRule* ruleFor(CalendarDay date) const noexcept;
    std::span<const DayRule> rules() const noexcept { return rules_; }

private:
    std::vector<DayRule> rules_;
};

}  // namespace firmware
