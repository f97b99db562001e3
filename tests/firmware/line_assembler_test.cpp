#include "firmware/line_assembler.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using firmware::LineAssembler;
using firmware::LineEvent;
using firmware::LineEventKind;

namespace {

/// Events rendered as strings: a line as itself, errors as "<too long>" / "<binary>".
struct Collector {
    std::vector<std::string> events;
    void operator()(const LineEvent& e)
    {
        switch (e.kind) {
            case LineEventKind::Line:
                events.emplace_back(e.text);
                break;
            case LineEventKind::TooLong:
                events.emplace_back("<too long>");
                break;
            case LineEventKind::Binary:
                events.emplace_back("<binary>");
                break;
        }
    }
};

std::vector<std::string> feedAll(LineAssembler& a, std::string_view bytes)
{
    Collector c;
    a.feed(bytes.data(), bytes.size(), c);
    return c.events;
}

std::vector<std::string> feedAll(std::size_t maxLength, std::string_view bytes)
{
    LineAssembler a(maxLength);
    return feedAll(a, bytes);
}

using Events = std::vector<std::string>;

}  // namespace

TEST(LineAssembler, RejectsZeroLength)
{
    EXPECT_THROW(LineAssembler(0), std::runtime_error);
}

TEST(LineAssembler, LfCrAndCrlfEndLines)
{
    EXPECT_EQ(feedAll(64, "a\nb\rc\r\nd\n"), (Events{"a", "b", "c", "d"}));
    EXPECT_EQ(feedAll(64, "one\r\ntwo\r\n"), (Events{"one", "two"}));
}

TEST(LineAssembler, EmptyLinesAreIgnored)
{
    EXPECT_EQ(feedAll(64, "\n\n\r\n\r\r\nx\n\n"), (Events{"x"}));
}

TEST(LineAssembler, UnterminatedLineWaitsForItsEnd)
{
    LineAssembler a(64);
    EXPECT_TRUE(feedAll(a, "stat").empty());
    EXPECT_EQ(a.pendingLength(), 4u);
    EXPECT_EQ(feedAll(a, "us\r"), (Events{"status"}));
    EXPECT_EQ(a.pendingLength(), 0u);
}

TEST(LineAssembler, ByteByByteEqualsWhole)
{
    const std::string input = "help\r\nstatus now\n\x7fx\bq\n";
    LineAssembler a(64);
    Collector c;
    for (char ch : input)
        a.feed(&ch, 1, c);
    EXPECT_EQ(c.events, feedAll(64, input));
    EXPECT_EQ(c.events, (Events{"help", "status now", "q"}));
}

TEST(LineAssembler, FinishDeliversThePendingLine)
{
    LineAssembler a(64);
    Collector c;
    a.feed("quit", 4, c);
    a.finish(c);
    a.finish(c);  // nothing pending any more
    EXPECT_EQ(c.events, (Events{"quit"}));
}

TEST(LineAssembler, TabBecomesSpace)
{
    EXPECT_EQ(feedAll(64, "help\tstatus\n"), (Events{"help status"}));
}

TEST(LineAssembler, BackspaceAndDelDeleteThePreviousCharacter)
{
    EXPECT_EQ(feedAll(64, "stattus\b\b\bus\n"), (Events{"status"}));
    EXPECT_EQ(feedAll(64, "hepp\x7f\x7flp\n"), (Events{"help"}));
    // Deleting past the start does nothing; a line deleted to nothing is empty and ignored.
    EXPECT_EQ(feedAll(64, "\b\b\x7fok\n"), (Events{"ok"}));
    EXPECT_EQ(feedAll(64, "ab\b\b\nc\n"), (Events{"c"}));
}

TEST(LineAssembler, BackspaceMakesRoomInAFullLine)
{
    // Deleting keeps the line within the limit, so a corrected full line is accepted.
    EXPECT_EQ(feedAll(4, "abcd\bx\n"), (Events{"abcx"}));
}

TEST(LineAssembler, ExactlyMaxLengthIsAccepted)
{
    EXPECT_EQ(feedAll(5, "12345\n"), (Events{"12345"}));
}

TEST(LineAssembler, TooLongIsReportedOnceThenRecovers)
{
    EXPECT_EQ(feedAll(5, "123456789012345678901234567890\nok\n"), (Events{"<too long>", "ok"}));
    // Across chunks: one report for the whole long line.
    LineAssembler a(5);
    Collector c;
    for (int i = 0; i < 100; ++i)
        a.feed("abcdefgh", 8, c);
    a.feed("\r\nnext\r\n", 8, c);
    EXPECT_EQ(c.events, (Events{"<too long>", "next"}));
}

TEST(LineAssembler, BinaryIsReportedOncePerLineThenRecovers)
{
    EXPECT_EQ(feedAll(64, std::string("st\x01\x02\x03us\n", 8) + "ok\n"),
              (Events{"<binary>", "ok"}));
    EXPECT_EQ(feedAll(64, std::string("a\0b\nc\n", 6)), (Events{"<binary>", "c"}));
    EXPECT_EQ(feedAll(64, "\x1b[A\n\x1b[B\n"), (Events{"<binary>", "<binary>"}));  // arrow keys
    EXPECT_EQ(feedAll(64, "caf\xc3\xa9\nok\n"), (Events{"<binary>", "ok"}));       // UTF-8
    // Once a line is rejected it stays rejected: neither backspace nor length brings it back.
    EXPECT_EQ(feedAll(4, "a\x01\b\b123456789\nz\n"), (Events{"<binary>", "z"}));
    EXPECT_EQ(feedAll(4, "123456\x01\nz\n"), (Events{"<too long>", "z"}));
}

TEST(LineAssembler, ResetForgetsThePartialLine)
{
    LineAssembler a(8);
    EXPECT_EQ(feedAll(a, "123456789"), (Events{"<too long>"}));
    a.reset();
    EXPECT_EQ(feedAll(a, "ok\n"), (Events{"ok"}));
}

TEST(LineAssembler, LinesAreAlwaysPrintableAndBounded)
{
    std::mt19937 rng(1234);
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_int_distribution<std::size_t> chunk(1, 512);
    LineAssembler a(32);
    std::vector<char> data(1 << 20);
    for (char& c : data)
        c = static_cast<char>(byte(rng));
    std::size_t lines = 0;
    bool ok = true;
    auto check = [&](const LineEvent& e) {
        if (e.kind != LineEventKind::Line)
            return;
        ++lines;
        ok = ok && !e.text.empty() && e.text.size() <= 32;
        for (char c : e.text)
            ok = ok && c >= 0x20 && c <= 0x7E;
    };
    for (std::size_t i = 0; i < data.size();) {
        const std::size_t n = std::min(chunk(rng), data.size() - i);
        a.feed(data.data() + i, n, check);
        i += n;
    }
    EXPECT_TRUE(ok);

    // Mostly printable noise does form lines, and they stay within the rules.
    std::uniform_int_distribution<int> printable(0x20, 0x7E);
    std::uniform_int_distribution<int> pick(0, 99);
    for (char& c : data) {
        const int p = pick(rng);
        c = p < 3   ? '\n'
            : p < 4 ? '\r'
            : p < 5 ? '\b'
            : p < 6 ? '\x7f'
            : p < 7 ? '\t'
                    : char(printable(rng));
    }
    for (std::size_t i = 0; i < data.size();) {
        const std::size_t n = std::min(chunk(rng), data.size() - i);
        a.feed(data.data() + i, n, check);
        i += n;
    }
    EXPECT_TRUE(ok);
    EXPECT_GT(lines, 1000u);
}

TEST(LineAssembler, FeedDoesNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting is not available in this build";
    LineAssembler a(16);
    std::size_t events = 0;
    const std::string input = "help\r\nx\x01y\n0123456789abcdefghij\nstatus\b\bus\n";
    testing_support::AllocationCounts counts;
    {
        testing_support::AllocationScope scope;
        for (int i = 0; i < 100; ++i)
            a.feed(input.data(), input.size(), [&](const LineEvent&) noexcept { ++events; });
        counts = scope.counts();
    }
    EXPECT_EQ(events, 400u);
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
}
