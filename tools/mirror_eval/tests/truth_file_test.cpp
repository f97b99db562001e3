// Truth CSV parsing: good files (header, comments, CRLF, frames without card) and one clear
// FILE:LINE error for each kind of malformed row.

#include "truth_file.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>

namespace {

using mirror_eval::parseTruth;

std::string errorOf(const std::string& text)
{
    std::istringstream in(text);
    try {
        parseTruth(in, "t.csv");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(TruthFile, ParsesRowsWithAndWithoutCard)
{
    std::istringstream in(
        "frame,x0,y0,x1,y1,x2,y2,x3,y3\r\n"
        "# made by hand\n"
        "0,-8.5,-8.5,727.5,-8.5,727.5,487.5,-8.5,487.5\r\n"
        "\n"
        "1, 10.25 ,20,110,22,108,90,12,88\n"
        "2,,,,,,,,\n");
    const auto rows = parseTruth(in, "t.csv");
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_TRUE(rows[0].hasCard);
    EXPECT_FLOAT_EQ(rows[0].quad[0].x, -8.5f);
    EXPECT_FLOAT_EQ(rows[0].quad[2].y, 487.5f);
    EXPECT_EQ(rows[1].frame, 1);
    EXPECT_FLOAT_EQ(rows[1].quad[0].x, 10.25f);
    EXPECT_FLOAT_EQ(rows[1].quad[3].y, 88.f);
    EXPECT_FALSE(rows[2].hasCard);
}

TEST(TruthFile, HeaderIsOptional)
{
    std::istringstream in("0,1,2,3,4,5,6,7,8\n");
    EXPECT_EQ(parseTruth(in, "t.csv").size(), 1u);
}

TEST(TruthFile, MalformedRowsNameFileAndLine)
{
    EXPECT_EQ(errorOf("frame,x0\n0,1,2,3,4,5,6,7\n"),
              "t.csv:2: expected 9 comma-separated fields frame,x0,y0,x1,y1,x2,y2,x3,y3, got 8");
    EXPECT_EQ(errorOf("0,1,2,3,4,5,6,7,8,9\n").substr(0, 44),
              "t.csv:1: expected 9 comma-separated fields f");
    EXPECT_EQ(errorOf("0,1,2,3,4,5,6,7,8\n1,1,2,3,abc,5,6,7,8\n"),
              "t.csv:2: y1 'abc' is not a number");
    EXPECT_EQ(errorOf("0,1,2,3,4,5,6,7,nan\n"), "t.csv:1: y3 'nan' is not a number");
    EXPECT_EQ(errorOf("0,1,2,3,4,,6,7,8\n"),
              "t.csv:1: some corner fields empty: give all 8 numbers, or leave all 8 empty for a "
              "frame without a card");
    EXPECT_EQ(errorOf("0,1,2,3,4,5,6,7,8\n2,1,2,3,4,5,6,7,8\n"),
              "t.csv:2: frame 2 out of order (expected 1: one row per frame, from 0)");
    EXPECT_EQ(errorOf("x,1,2,3,4,5,6,7,8\n"),
              "t.csv:1: frame number 'x' is not a whole number >= 0");
    EXPECT_EQ(errorOf("frame,x0,y0,x1,y1,x2,y2,x3,y3\n"),
              "t.csv: no truth rows (expected frame,x0,y0,...,x3,y3 lines)");
    EXPECT_EQ(errorOf(""), "t.csv: no truth rows (expected frame,x0,y0,...,x3,y3 lines)");
}

TEST(TruthFile, MissingFileIsOneClearError)
{
    try {
        mirror_eval::loadTruth("/nonexistent/truth.csv");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "truth /nonexistent/truth.csv: cannot open (missing or unreadable)");
    }
}

}  // namespace
