#include "firmware/day_calendar.hpp"

#include <charconv>
#include <cstdio>
#include <tuple>

namespace firmware {

namespace {

// "MM-DD" or "YYYY-MM-DD": year 0 for the first form.
bool parseDate(std::string_view s, int& year, int& month, int& day) noexcept
{
    const auto number = [](std::string_view digits, int& out) {
        if (digits.empty())
            return false;
        for (const char c : digits)
            if (c < '0' || c > '9')
                return false;
        return std::from_chars(digits.data(), digits.data() + digits.size(), out).ec == std::errc{};
    };
    if (s.size() == 5 && s[2] == '-') {
        year = 0;
        return number(s.substr(0, 2), month) && number(s.substr(3, 2), day);
    }
    if (s.size() == 10 && s[4] == '-' && s[7] == '-')
        return number(s.substr(0, 4), year) && number(s.substr(5, 2), month) &&
               number(s.substr(8, 2), day);
    return false;
}

// month * 100 + day of a yearly date in `year` (02-29 -> 02-28 without a leap day).
int yearlyKey(int year, int month, int day) noexcept
{
    if (month == 2 && day == 29 && !isLeapYear(year))
        day = 28;
    return month * 100 + day;
}

}  // namespace

CalendarDay localDay(std::time_t t) noexcept
{
    std::tm tm{};
    localtime_r(&t, &tm);
    return {tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday};
}

bool isLeapYear(int year) noexcept
{
    return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

int daysInMonth(int year, int month) noexcept
{
    static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (month < 1 || month > 12)
        return 0;
    return month == 2 && isLeapYear(year) ? 29 : kDays[month - 1];
}

bool isYearlyDate(int month, int day, CalendarDay date) noexcept
{
    return yearlyKey(date.year, month, day) == date.month * 100 + date.day;
}

bool DayRule::covers(CalendarDay date) const noexcept
{
    if (year != 0) {
        const long d = date.year * 10000L + date.month * 100L + date.day;
        return d >= year * 10000L + fromMonth * 100L + fromDay &&
               d <= toYear * 10000L + toMonth * 100L + toDay;
    }
    const int d = date.month * 100 + date.day;
    const int from = yearlyKey(date.year, fromMonth, fromDay);
    const int to = yearlyKey(date.year, toMonth, toDay);
    return from <= to ? (d >= from && d <= to) : (d >= from || d <= to);  // over the new year
}

bool parseDayRule(std::string_view text, DayRule& rule, std::string& problem)
{
    const auto fail = [&](const char* format, int a = 0, int b = 0, int c = 0) {
        char why[160];
        std::snprintf(why, sizeof why, format, a, b, c);
        problem.assign(1, '\'');
        problem.append(text);
        problem.append("': ");
        problem.append(why);
        return false;
    };
    const std::size_t space = text.find(' ');
    if (space == std::string_view::npos)
        return fail("a date and an overlay name, e.g. \"12-25 santa_hat\"");
    const std::string_view dates = text.substr(0, space);
    std::string_view name = text.substr(space + 1);
    while (!name.empty() && name.front() == ' ')
        name.remove_prefix(1);
    if (name.empty() || name.find(' ') != std::string_view::npos)
        return fail("one overlay name after the date");
    const std::size_t dots = dates.find("..");
    const std::string_view first = dates.substr(0, dots);
    const std::string_view last = dots == std::string_view::npos ? first : dates.substr(dots + 2);
    DayRule r;
    int y1 = 0, y2 = 0;
    if (!parseDate(first, y1, r.fromMonth, r.fromDay) || !parseDate(last, y2, r.toMonth, r.toDay))
        return fail("dates are MM-DD or YYYY-MM-DD, a range FROM..TO");
    if ((y1 == 0) != (y2 == 0))
        return fail("both ends of a range are yearly (MM-DD) or both dated (YYYY-MM-DD)");
    for (const auto& [y, m, d] :
         {std::tuple{y1, r.fromMonth, r.fromDay}, std::tuple{y2, r.toMonth, r.toDay}}) {
        if (m < 1 || m > 12)
            return fail("month %d is not 1-12", m);
        // A yearly date may be 02-29 (kept on the 28th in other years).
        const int most = y == 0 ? daysInMonth(2000, m) : daysInMonth(y, m);
        if (d < 1 || d > most)
            return y != 0 ? fail("day %d is not in month %d of %d", d, m, y)
                          : fail("day %d is not in month %d", d, m);
    }
    r.year = y1;
    r.toYear = y2;
    if (y1 != 0 &&
        y1 * 10000L + r.fromMonth * 100L + r.fromDay > y2 * 10000L + r.toMonth * 100L + r.toDay)
        return fail("the range ends before it starts");
    r.overlay = std::string(name);
    r.text = std::string(text);
    rule = std::move(r);
    return true;
}

const DayRule* DayCalendar::ruleFor(CalendarDay date) const noexcept
{
    for (const DayRule& r : rules_)
        if (r.covers(date))
            return &r;
    return nullptr;
}

}  // namespace firmware
