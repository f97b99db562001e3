// The calendar of special days: yearly and dated rules, ranges over the new year, 29 February.
#include "firmware/day_calendar.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using firmware::CalendarDay;
using firmware::DayCalendar;
using firmware::DayRule;

DayRule rule(const std::string& text)
{
    DayRule r;
    std::string problem;
    EXPECT_TRUE(firmware::parseDayRule(text, r, problem)) << problem;
    return r;
}

TEST(DayCalendar, YearlyDaysAndRangesOverTheNewYear)
{
    const DayCalendar calendar({rule("12-24..12-26 santa_hat"), rule("12-31..01-01 party_hat"),
                                rule("2026-12-25 graduation_cap"), rule("07-04 top_hat")});
    const auto overlay = [&](int y, int m, int d) {
        const DayRule* r = calendar.ruleFor({y, m, d});
        return r ? r->overlay : std::string("-");
    };
    EXPECT_EQ(overlay(2026, 12, 23), "-");
    EXPECT_EQ(overlay(2026, 12, 24), "santa_hat");
    EXPECT_EQ(overlay(2026, 12, 25), "santa_hat") << "the first rule that covers the day wins";
    EXPECT_EQ(overlay(2026, 12, 26), "santa_hat");
    EXPECT_EQ(overlay(2026, 12, 27), "-");
    EXPECT_EQ(overlay(2026, 12, 31), "party_hat");
    EXPECT_EQ(overlay(2027, 1, 1), "party_hat") << "over the new year";
    EXPECT_EQ(overlay(2027, 1, 2), "-");
    EXPECT_EQ(overlay(1999, 12, 31), "party_hat") << "every year";
    EXPECT_EQ(overlay(2030, 7, 4), "top_hat");

    const DayCalendar dated({rule("2026-12-30..2027-01-02 party_hat"), rule("2027-03-01 glasses")});
    EXPECT_EQ(dated.ruleFor({2026, 12, 29}), nullptr);
    ASSERT_NE(dated.ruleFor({2026, 12, 30}), nullptr);
    ASSERT_NE(dated.ruleFor({2027, 1, 2}), nullptr);
    EXPECT_EQ(dated.ruleFor({2027, 1, 3}), nullptr);
    EXPECT_EQ(dated.ruleFor({2028, 1, 1}), nullptr) << "a dated range is not yearly";
    EXPECT_EQ(dated.ruleFor({2028, 3, 1}), nullptr);
}

TEST(DayCalendar, TheTwentyNinthOfFebruaryIsKeptOnTheTwentyEighthWithoutALeapDay)
{
    const DayCalendar calendar({rule("02-29 party_hat")});
    EXPECT_NE(calendar.ruleFor({2028, 2, 29}), nullptr);
    EXPECT_EQ(calendar.ruleFor({2028, 2, 28}), nullptr) << "a leap year has its own 29th";
    EXPECT_NE(calendar.ruleFor({2027, 2, 28}), nullptr);
    EXPECT_EQ(calendar.ruleFor({2027, 3, 1}), nullptr);
    EXPECT_NE(calendar.ruleFor({2000, 2, 29}), nullptr);
    EXPECT_NE(calendar.ruleFor({2100, 2, 28}), nullptr) << "2100 has no leap day";
    EXPECT_TRUE(firmware::isYearlyDate(2, 29, {2026, 2, 28}));
    EXPECT_FALSE(firmware::isYearlyDate(2, 29, {2024, 2, 28}));
    EXPECT_TRUE(firmware::isYearlyDate(12, 31, {2026, 12, 31}));

    const DayCalendar feb({rule("02-20..02-29 top_hat")});
    EXPECT_NE(feb.ruleFor({2027, 2, 28}), nullptr);
    EXPECT_EQ(feb.ruleFor({2027, 3, 1}), nullptr);
    EXPECT_NE(feb.ruleFor({2028, 2, 29}), nullptr);
}

TEST(DayCalendar, ABadRuleIsOneLineSayingWhy)
{
    const std::pair<const char*, const char*> bad[] = {
        {"12-25", "a date and an overlay name"},
        {"12-25 santa hat", "one overlay name"},
        {"13-01 x", "month 13 is not 1-12"},
        {"04-31 x", "day 31 is not in month 4"},
        {"2027-02-29 x", "day 29 is not in month 2 of 2027"},
        {"12/25 x", "dates are MM-DD or YYYY-MM-DD"},
        {"12-24..2026-12-26 x", "both ends of a range"},
        {"2027-01-02..2026-12-30 x", "the range ends before it starts"},
        {"1-5 x", "dates are MM-DD"},
        {"+1-05 x", "dates are MM-DD"},
    };
    for (const auto& [text, why] : bad) {
        DayRule r;
        std::string problem;
        EXPECT_FALSE(firmware::parseDayRule(text, r, problem)) << text;
        EXPECT_NE(problem.find(why), std::string::npos) << text << ": " << problem;
        EXPECT_EQ(problem.find('\n'), std::string::npos);
    }
    DayRule r;
    std::string problem;
    EXPECT_TRUE(firmware::parseDayRule("2028-02-29 x", r, problem)) << problem;
    EXPECT_TRUE(firmware::parseDayRule("02-29   party_hat", r, problem)) << problem;
    EXPECT_EQ(r.overlay, "party_hat");
}

TEST(DayCalendar, LeapYearsAndMonths)
{
    EXPECT_TRUE(firmware::isLeapYear(2024));
    EXPECT_FALSE(firmware::isLeapYear(2026));
    EXPECT_FALSE(firmware::isLeapYear(1900));
    EXPECT_TRUE(firmware::isLeapYear(2000));
    EXPECT_EQ(firmware::daysInMonth(2026, 2), 28);
    EXPECT_EQ(firmware::daysInMonth(2028, 2), 29);
    EXPECT_EQ(firmware::daysInMonth(2026, 13), 0);
}

}  // namespace
