#include "firmware/command_shell.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using firmware::Args;
using firmware::CommandShell;
using firmware::Reply;
using firmware::ShellOptions;

namespace {

/// A console fed from a string, at most `maxChunk` bytes per read; collects what is written.
class FakeConsole : public platform::Console {
public:
    explicit FakeConsole(std::string in = {}) : input(std::move(in)) {}

    const char* description() const noexcept override { return "fake"; }
    long read(char* buffer, std::size_t capacity) noexcept override
    {
        requested += capacity;
        if (position == input.size())
            return closeAtEnd ? -1 : 0;
        const std::size_t n = std::min({capacity, input.size() - position, maxChunk});
        std::memcpy(buffer, input.data() + position, n);
        position += n;
        return static_cast<long>(n);
    }
    void write(std::string_view text) noexcept override { output.append(text); }

    std::string input;
    std::size_t position = 0;
    std::size_t maxChunk = static_cast<std::size_t>(-1);
    bool closeAtEnd = false;
    std::size_t requested = 0;  ///< sum of read capacities asked for
    std::string output;
};

/// Runs one line through execute() and returns what was written.
std::string run(CommandShell& shell, std::string_view line)
{
    FakeConsole console;
    shell.execute(line, console);
    return console.output;
}

/// Feeds `input` through poll() until it is used up and returns what was written.
std::string pollAll(CommandShell& shell, std::string input)
{
    FakeConsole console(std::move(input));
    for (int i = 0; i < 1000 && console.position < console.input.size(); ++i)
        shell.poll(console);
    return console.output;
}

/// A command that echoes its words, for checking what handlers receive.
void addEcho(CommandShell& shell)
{
    shell.add("echo", "echo [WORD...]", "print the words back", [](const Args& args, Reply& reply) {
        reply.printf("echo: %zu", args.size());
        for (std::size_t i = 1; i < args.size(); ++i)
            reply.printf(" [%.*s]", static_cast<int>(args[i].size()), args[i].data());
        reply.line("");
    });
}

std::vector<std::string> splitLines(const std::string& text)
{
    std::vector<std::string> lines;
    std::size_t start = 0;
    for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
        lines.push_back(text.substr(start, end - start));
    if (start < text.size())
        lines.push_back(text.substr(start));
    return lines;
}

bool isPrintableLine(std::string_view line)
{
    return std::all_of(line.begin(), line.end(), [](char c) { return c >= 0x20 && c <= 0x7E; });
}

}  // namespace

// --- Args ---------------------------------------------------------------------------------------

TEST(Args, SplitsOnSpacesAndTabs)
{
    Args args;
    ASSERT_EQ(args.parse("  set \t log.level   debug  "), Args::Parse::Ok);
    ASSERT_EQ(args.size(), 3u);
    EXPECT_EQ(args[0], "set");
    EXPECT_EQ(args[1], "log.level");
    EXPECT_EQ(args[2], "debug");
    EXPECT_EQ(args[3], "");  // past the end
    EXPECT_EQ(std::vector<std::string_view>(args.begin(), args.end()),
              (std::vector<std::string_view>{"set", "log.level", "debug"}));
}

TEST(Args, BlankLineIsEmpty)
{
    Args args;
    EXPECT_EQ(args.parse(""), Args::Parse::Empty);
    EXPECT_EQ(args.parse(" \t  "), Args::Parse::Empty);
    EXPECT_EQ(args.size(), 0u);
}

TEST(Args, AtMostEightWords)
{
    Args args;
    EXPECT_EQ(args.parse("a b c d e f g h"), Args::Parse::Ok);
    EXPECT_EQ(args.size(), 8u);
    EXPECT_EQ(args.parse("a b c d e f g h i"), Args::Parse::TooMany);
    EXPECT_EQ(args.parse("a b c d e f g h   "), Args::Parse::Ok);
}

// --- Reply --------------------------------------------------------------------------------------

TEST(Reply, PrintfAndLineAppend)
{
    Reply reply;
    EXPECT_TRUE(reply.empty());
    reply.printf("frames %d, fps %.1f\n", 42, 29.97);
    reply.line("ok");
    reply.append("tail");
    EXPECT_EQ(reply.text(), "frames 42, fps 30.0\nok\ntail");
    EXPECT_FALSE(reply.truncated());
    reply.clear();
    EXPECT_TRUE(reply.empty());
}

TEST(Reply, HoldsFarMoreThanTheOldFourKilobytes)
{
    Reply reply;
    const std::string chunk(100, 'x');
    for (int i = 0; i < 1000; ++i)
        reply.printf("%s\n", chunk.c_str());
    EXPECT_FALSE(reply.truncated());
    EXPECT_EQ(reply.text().size(), 101'000u);
}

TEST(Reply, BeyondItsCapacityEndsWithAMarker)
{
    Reply reply(1000);
    const std::string chunk(100, 'x');
    for (int i = 0; i < 100; ++i)
        reply.printf("%s\n", chunk.c_str());
    EXPECT_TRUE(reply.truncated());
    const std::string text(reply.text());
    EXPECT_LE(text.size(), 1000u + 13u);
    EXPECT_EQ(text.substr(text.size() - 13), "\n[truncated]\n");
    // Later appends are ignored; the marker stays last.
    reply.line("more");
    reply.append("more");
    reply.printf("%s", "more");
    EXPECT_EQ(std::string(reply.text()), text);

    Reply huge(1000);
    huge.append(std::string(3000, 'y'));
    EXPECT_TRUE(huge.truncated());
    EXPECT_EQ(huge.text().size(), 1000u + 13u);
    Reply formatted(1000);
    formatted.printf("%s", std::string(3000, 'y').c_str());
    EXPECT_EQ(formatted.text(), huge.text());
}

TEST(Reply, StoresOnlyPrintableText)
{
    Reply reply;
    reply.printf("a\tb\rc%cd\n", 0x01);
    reply.append(std::string("\x7f\xff\0e", 4));
    EXPECT_EQ(reply.text(), "a b?c?d\n???e");
}

// --- Registry and execute -----------------------------------------------------------------------

TEST(CommandShell, RunsACommandWithItsArguments)
{
    CommandShell shell;
    addEcho(shell);
    EXPECT_TRUE(shell.hasCommand("echo"));
    EXPECT_FALSE(shell.hasCommand("ech"));
    EXPECT_EQ(run(shell, "echo"), "echo: 1\n");
    EXPECT_EQ(run(shell, "  echo a\tbb   c "), "echo: 4 [a] [bb] [c]\n");
    EXPECT_EQ(run(shell, "echo 1 2 3 4 5 6 7"), "echo: 8 [1] [2] [3] [4] [5] [6] [7]\n");
}

TEST(CommandShell, TooManyArguments)
{
    CommandShell shell;
    addEcho(shell);
    EXPECT_EQ(run(shell, "echo 1 2 3 4 5 6 7 8"), "error: too many arguments (at most 8 words)\n");
}

TEST(CommandShell, BlankLineSaysNothing)
{
    CommandShell shell;
    EXPECT_EQ(run(shell, ""), "");
    EXPECT_EQ(run(shell, "   \t "), "");
}

TEST(CommandShell, UnknownCommandIsQuoted)
{
    CommandShell shell;
    EXPECT_EQ(run(shell, "xyz"), "error: unknown command 'xyz' (try 'help')\n");
    EXPECT_EQ(run(shell, "xyz with args"), "error: unknown command 'xyz' (try 'help')\n");
    EXPECT_EQ(run(shell, "it's\\"), "error: unknown command 'it\\'s\\\\' (try 'help')\n");
    EXPECT_EQ(run(shell, std::string("a\x01\xff\x7f", 4)),
              "error: unknown command 'a\\x01\\xff\\x7f' (try 'help')\n");
    // At most 32 characters of the name are quoted.
    EXPECT_EQ(run(shell, std::string(32, 'n')),
              "error: unknown command '" + std::string(32, 'n') + "' (try 'help')\n");
    EXPECT_EQ(run(shell, std::string(5000, 'n')),
              "error: unknown command '" + std::string(32, 'n') + "...' (try 'help')\n");
    // Even all-escaped, the line stays short.
    EXPECT_EQ(
        run(shell, std::string(100, '\x01')), "error: unknown command '" + [] {
            std::string s;
            for (int i = 0; i < 32; ++i)
                s += "\\x01";
            return s;
        }() + "...' (try 'help')\n");
}

TEST(CommandShell, CommandNamesAreCaseSensitive)
{
    CommandShell shell;
    EXPECT_EQ(run(shell, "HELP"), "error: unknown command 'HELP' (try 'help')\n");
}

TEST(CommandShell, HelpListsCommandsAligned)
{
    CommandShell shell;
    addEcho(shell);
    shell.add("snapshot", "[PATH]", "write a PNG of the next frame", [](const Args&, Reply&) {});
    shell.add("quit", "", "stop the mirror", [](const Args&, Reply&) {});
    EXPECT_EQ(run(shell, "help"),
              "commands:\n"
              "  help [COMMAND]   list the commands, or describe one\n"
              "  echo [WORD...]   print the words back\n"
              "  snapshot [PATH]  write a PNG of the next frame\n"
              "  quit             stop the mirror\n");
}

TEST(CommandShell, HelpDescribesOneCommand)
{
    CommandShell shell;
    addEcho(shell);
    EXPECT_EQ(run(shell, "help echo"), "usage: echo [WORD...]\n  print the words back\n");
    EXPECT_EQ(run(shell, "help help"),
              "usage: help [COMMAND]\n  list the commands, or describe one\n");
    EXPECT_EQ(run(shell, "help nope"), "error: unknown command 'nope' (try 'help')\n");
    EXPECT_EQ(run(shell, "help echo echo"),
              "error: unexpected argument 'echo'; usage: help [COMMAND]\n");
}

TEST(Arity, FromTheUsageLine)
{
    auto arity = [](std::string_view usage) {
        const firmware::Arity a = firmware::Arity::fromUsage(usage);
        return std::to_string(a.min) + ".." + std::to_string(a.max);
    };
    EXPECT_EQ(arity("status"), "0..0");
    EXPECT_EQ(arity("status [--json]"), "0..1");
    EXPECT_EQ(arity("log [error|warn|info|debug] [N]"), "0..2");
    EXPECT_EQ(arity("overlay [next|prev|off|list|NAME|N|mode global|per_face]"), "0..2");
    EXPECT_EQ(arity("set KEY VALUE"), "2..2");
    EXPECT_EQ(arity("snapshot PATH [NOTE]"), "1..2");
    EXPECT_EQ(arity("echo [WORD...]"), "0..7");
    EXPECT_EQ(arity("sum N..."), "1..7");
}

TEST(CommandShell, EveryArgumentCountErrorGivesTheUsage)
{
    CommandShell shell;
    int runs = 0;
    shell.add("status", "status [--json]", "state", [&](const Args&, Reply&) { ++runs; });
    shell.add("quit", "", "stop", [&](const Args&, Reply&) { ++runs; });
    shell.add("set", "set KEY VALUE", "change", [&](const Args&, Reply&) { ++runs; });
    EXPECT_EQ(run(shell, "quit now"), "error: unexpected argument 'now'; usage: quit\n");
    EXPECT_EQ(run(shell, "status --json now"),
              "error: unexpected argument 'now'; usage: status [--json]\n");
    EXPECT_EQ(run(shell, "set x"), "error: missing argument; usage: set KEY VALUE\n");
    EXPECT_EQ(runs, 0);
    EXPECT_EQ(run(shell, "status --json"), "");
    EXPECT_EQ(runs, 1);
}

TEST(CommandShell, HandlersReportBadWordsWithTheUsage)
{
    CommandShell shell;
    shell.add("log", "log [N]", "lines", [](const Args& args, Reply& reply) {
        long n = 20;
        if (args.size() == 2 && !args.number(1, 1, 200, n))
            reply.usageError("N must be 1..200, got '%.*s'", Args::shown(args[1]), args[1].data());
        else
            reply.printf("%ld\n", n);
    });
    EXPECT_EQ(run(shell, "log 0"), "error: N must be 1..200, got '0'; usage: log [N]\n");
    EXPECT_EQ(run(shell, "log -1"), "error: N must be 1..200, got '-1'; usage: log [N]\n");
    EXPECT_EQ(run(shell, "log 2x"), "error: N must be 1..200, got '2x'; usage: log [N]\n");
    EXPECT_EQ(run(shell, "log 200"), "200\n");
    Args args;
    args.parse("x on 7");
    EXPECT_EQ(args.choice(1, {"off", "on"}), 1);
    EXPECT_EQ(args.choice(2, {"off", "on"}), -1);
    EXPECT_EQ(args.choice(5, {"off", "on"}), -1);
    long v = 0;
    EXPECT_TRUE(args.number(2, -7, 7, v));
    EXPECT_EQ(v, 7);
    EXPECT_FALSE(args.number(2, 8, 9, v));
    EXPECT_FALSE(args.number(3, 0, 9, v));
}

TEST(CommandShell, HelpKeepsWithinEightyColumns)
{
    CommandShell shell;
    shell.add("overlay", "overlay [next|prev|off|list|NAME|N|mode global|per_face]",
              "what the faces wear: show, change (by name or by the number `overlay list` "
              "prints), list the catalogue, one choice for all or one per face",
              [](const Args&, Reply&) {});
    shell.add("status", "status [--json]",
              "uptime, frames, fps, per-stage p50/p99 ms, source, display; --json for tools",
              [](const Args&, Reply&) {});
    for (const char* command : {"help", "help overlay", "help status"})
        for (const std::string& line : splitLines(run(shell, command)))
            EXPECT_LE(line.size(), CommandShell::kHelpColumns) << command << ": " << line;
    EXPECT_EQ(run(shell, "help"),
              "commands:\n"
              "  help [COMMAND]   list the commands, or describe one\n"
              "  overlay [next|prev|off|list|NAME|N|mode global|per_face]\n"
              "                   what the faces wear: show, change (by name or by the number\n"
              "                   `overlay list` prints), list the catalogue, one choice for\n"
              "                   all or one per face\n"
              "  status [--json]  uptime, frames, fps, per-stage p50/p99 ms, source, display;\n"
              "                   --json for tools\n");
}

TEST(CommandShell, ReplyWithoutNewlineIsEnded)
{
    CommandShell shell;
    shell.add("bare", "", "no newline", [](const Args&, Reply& reply) { reply.append("x"); });
    shell.add("silent", "", "no reply", [](const Args&, Reply&) {});
    EXPECT_EQ(run(shell, "bare"), "x\n");
    EXPECT_EQ(run(shell, "silent"), "");
}

/// A console whose output takes `room` bytes, then nothing until the test drains it (a UART's
/// queue at 9600 baud); writing more than it said it takes is a test failure.
class SlowConsole : public FakeConsole {
public:
    using FakeConsole::FakeConsole;
    std::size_t writable() noexcept override { return room; }
    void write(std::string_view text) noexcept override
    {
        EXPECT_LE(text.size(), room);
        room -= std::min(room, text.size());
        FakeConsole::write(text);
    }
    std::size_t room = 100;
};

TEST(CommandShell, ALongReplyArrivesWhole)
{
    // 1000 lines (about 24 KB): the old 4096-byte reply stopped after about 170 of them.
    CommandShell shell;
    shell.add("flood", "", "much text", [](const Args&, Reply& reply) {
        for (int i = 0; i < 1000; ++i)
            reply.printf("line %d of a long reply\n", i);
    });
    const std::vector<std::string> lines = splitLines(run(shell, "flood"));
    ASSERT_EQ(lines.size(), 1000u);
    EXPECT_EQ(lines.back(), "line 999 of a long reply");
}

TEST(CommandShell, ALongReplyIsStreamedAsTheConsoleDrains)
{
    CommandShell shell(ShellOptions{.prompt = true, .crlf = true});
    shell.add("flood", "", "much text", [](const Args&, Reply& reply) {
        for (int i = 0; i < 300; ++i)
            reply.printf("line %d\n", i);
    });
    addEcho(shell);
    SlowConsole console("flood\recho after\r");
    shell.poll(console);
    // Each poll sends what the console takes now (half of it, CR LF may double the text), and
    // the next command waits for the reply to be out.
    EXPECT_LE(console.output.size(), 102u);
    EXPECT_EQ(console.output.find("echo:"), std::string::npos);
    for (int i = 0; i < 200 && console.output.find("echo: 2 [after]") == std::string::npos; ++i) {
        console.room = 100;  // the UART sent what was queued
        shell.poll(console);
    }
    const std::string expectedEnd = "line 298\r\nline 299\r\n> echo: 2 [after]\r\n> ";
    ASSERT_GE(console.output.size(), expectedEnd.size());
    EXPECT_EQ(console.output.substr(console.output.size() - expectedEnd.size()), expectedEnd);
    EXPECT_EQ(console.output.substr(0, 22), "> line 0\r\nline 1\r\nline");
    std::size_t count = 0;
    for (std::size_t at = 0; (at = console.output.find("\r\nline ", at)) != std::string::npos; ++at)
        ++count;
    EXPECT_EQ(count, 299u);
}

TEST(CommandShell, AClosedInputStillGetsItsLastReply)
{
    CommandShell shell;
    addEcho(shell);
    SlowConsole console("echo a b c d\n");
    console.closeAtEnd = true;
    console.room = 4;
    CommandShell::PollResult result = shell.poll(console);
    EXPECT_FALSE(result.closed);  // input ended, but the reply is not out yet
    for (int i = 0; i < 100 && !result.closed; ++i) {
        console.room = 4;
        result = shell.poll(console);
    }
    EXPECT_TRUE(result.closed);
    EXPECT_EQ(console.output, "echo: 5 [a] [b] [c] [d]\n");
}

TEST(CommandShell, ThrowingHandlerBecomesAnErrorLine)
{
    CommandShell shell;
    shell.add("boom", "", "throws", [](const Args&, Reply& reply) {
        reply.line("partial");
        throw std::runtime_error("bad thing");
    });
    shell.add("boom2", "", "throws", [](const Args&, Reply&) { throw 42; });
    EXPECT_EQ(run(shell, "boom"), "error: boom failed: bad thing\n");
    EXPECT_EQ(run(shell, "boom2"), "error: boom2 failed\n");
}

TEST(CommandShell, RegistrationIsValidated)
{
    CommandShell shell;
    const auto noop = [](const Args&, Reply&) {};
    EXPECT_THROW(shell.add("help", "", "again", noop), std::runtime_error);
    EXPECT_THROW(shell.add("", "", "empty", noop), std::runtime_error);
    EXPECT_THROW(shell.add("two words", "", "space", noop), std::runtime_error);
    EXPECT_THROW(shell.add("quote'", "", "quote", noop), std::runtime_error);
    EXPECT_THROW(shell.add("ok", "", "two\nlines", noop), std::runtime_error);
    EXPECT_THROW(shell.add("ok", "ok\t[X]", "tab", noop), std::runtime_error);
    EXPECT_THROW(shell.add("ok", "", "no handler", CommandShell::Handler()), std::runtime_error);
    EXPECT_NO_THROW(shell.add("ok", "ok [X]", "fine", noop));
    EXPECT_NO_THROW(shell.add("log.level-2_x", "", "fine", noop));
    EXPECT_EQ(run(shell, "help ok"), "usage: ok [X]\n  fine\n");
    EXPECT_EQ(run(shell, "help log.level-2_x"), "usage: log.level-2_x\n  fine\n");
}

TEST(CommandShell, RejectsBadOptions)
{
    EXPECT_THROW(CommandShell(ShellOptions{.maxLineLength = 0}), std::runtime_error);
    EXPECT_THROW(CommandShell(ShellOptions{.readBudget = 0}), std::runtime_error);
    EXPECT_EQ(CommandShell(std::size_t{80}).options().maxLineLength, 80u);
}

// --- poll
// -----------------------------------------------------------------------------------------

TEST(CommandShell, PollRunsLinesEndedAnyWay)
{
    CommandShell shell;
    addEcho(shell);
    EXPECT_EQ(pollAll(shell, "echo a\recho b\necho c\r\n\r\n\necho d"),
              "echo: 2 [a]\necho: 2 [b]\necho: 2 [c]\n");
}

TEST(CommandShell, PollInTinyChunks)
{
    CommandShell shell;
    addEcho(shell);
    FakeConsole console("echo x\r\nech\bho y\r\n");
    console.maxChunk = 1;
    for (int i = 0; i < 100; ++i)
        shell.poll(console);
    EXPECT_EQ(console.output, "echo: 2 [x]\necho: 2 [y]\n");
}

TEST(CommandShell, PollBackspaceEditsTheLine)
{
    CommandShell shell;
    addEcho(shell);
    EXPECT_EQ(pollAll(shell, "ecjo\b\bho  fixed\x7f\x7f\x7f\x7f\x7fok\n"), "echo: 2 [ok]\n");
}

TEST(CommandShell, PollTooLongThenRecovers)
{
    CommandShell shell(ShellOptions{.maxLineLength = 16});
    addEcho(shell);
    EXPECT_EQ(pollAll(shell, "echo " + std::string(100, 'a') + "\necho fine\n"),
              "error: line too long (max 16 characters)\necho: 2 [fine]\n");
}

TEST(CommandShell, PollBinaryThenRecovers)
{
    CommandShell shell;
    addEcho(shell);
    EXPECT_EQ(pollAll(shell, std::string("echo \x00\x01\x02 zz\x80\n", 13) + "echo fine\n"),
              "error: binary data ignored\necho: 2 [fine]\n");
}

TEST(CommandShell, PollReadsAtMostTheBudget)
{
    CommandShell shell;
    addEcho(shell);
    std::string input;
    while (input.size() < 10000)
        input += "echo x\n";
    FakeConsole console(input);
    const CommandShell::PollResult first = shell.poll(console);
    EXPECT_EQ(first.bytesRead, 4096u);
    EXPECT_LE(console.requested, 4096u);
    EXPECT_EQ(console.position, 4096u);
    EXPECT_EQ(first.events, 4096u / 7);
    EXPECT_FALSE(first.closed);
    shell.poll(console);
    shell.poll(console);
    EXPECT_EQ(console.position, input.size());
    EXPECT_EQ(splitLines(console.output).size(), input.size() / 7);
}

TEST(CommandShell, PollAtEndOfInputRunsTheLastLine)
{
    CommandShell shell;
    addEcho(shell);
    FakeConsole console("echo a\necho last");
    console.closeAtEnd = true;
    CommandShell::PollResult result = shell.poll(console);
    EXPECT_TRUE(result.closed);
    EXPECT_EQ(result.events, 2u);
    EXPECT_EQ(console.output, "echo: 2 [a]\necho: 2 [last]\n");
    result = shell.poll(console);  // closed stays closed, nothing runs twice
    EXPECT_TRUE(result.closed);
    EXPECT_EQ(result.events, 0u);
    EXPECT_EQ(console.output, "echo: 2 [a]\necho: 2 [last]\n");
}

TEST(CommandShell, PromptOption)
{
    CommandShell shell(ShellOptions{.prompt = true});
    addEcho(shell);
    FakeConsole console("echo a\nnope\n \n");
    shell.poll(console);
    EXPECT_EQ(console.output, "> echo: 2 [a]\n> error: unknown command 'nope' (try 'help')\n> > ");
    const std::size_t before = console.output.size();
    shell.poll(console);  // idle: no new prompt
    EXPECT_EQ(console.output.size(), before);

    CommandShell quiet;  // the default (pipes): no prompt at all
    FakeConsole idle;
    quiet.poll(idle);
    EXPECT_EQ(idle.output, "");
}

TEST(CommandShell, CrlfOption)
{
    CommandShell shell(ShellOptions{.crlf = true});
    shell.add("two", "", "two lines", [](const Args&, Reply& reply) { reply.append("a\nb"); });
    EXPECT_EQ(pollAll(shell, "two\r\nhelp two\r\n\x01\r\n"),
              "a\r\nb\r\nusage: two\r\n  two lines\r\nerror: binary data ignored\r\n");
}

TEST(CommandShell, ANotificationTakesThePromptsPlaceAndPromptsAgain)
{
    // A serial terminal (prompt, CR LF) waiting at its prompt, and a pipe on standard input.
    CommandShell shell;
    shell.setChannelStyle(1, true, true);
    addEcho(shell);
    FakeConsole serial("echo a\r\n");
    shell.poll(serial, 1);
    ASSERT_EQ(serial.output, "> echo: 2 [a]\r\n> ");
    shell.notify(serial, 1, "snapshot: /tmp/s.png\ntwo lines");
    EXPECT_EQ(serial.output, "> echo: 2 [a]\r\n> \rsnapshot: /tmp/s.png\r\ntwo lines\r\n> ");

    FakeConsole pipe;
    shell.poll(pipe, 0);
    shell.notify(pipe, 0, "card: trained\n");
    EXPECT_EQ(pipe.output, "card: trained\n");
    shell.notify(pipe, 0, "");
    EXPECT_EQ(pipe.output, "card: trained\n");
}

TEST(CommandShell, PollAndExecuteDoNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting is not available in this build";
    CommandShell shell(ShellOptions{.maxLineLength = 64, .prompt = true});
    addEcho(shell);
    std::string input =
        "help\necho a b c\nhelp echo\nnope 'x'\n" + std::string(100, 'L') + "\nbin\x01\n\n";
    input += "1 2 3 4 5 6 7 8 9\r\n";
    FakeConsole console(input);
    console.output.reserve(1 << 16);
    testing_support::AllocationCounts counts;
    {
        testing_support::AllocationScope scope;
        shell.poll(console);
        shell.execute("echo direct", console);
        counts = scope.counts();
    }
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
    EXPECT_EQ(counts.foreignMalloc, 0);
    EXPECT_NE(console.output.find("error: too many arguments"), std::string::npos);
    EXPECT_NE(console.output.find("echo: 2 [direct]"), std::string::npos);
}

// --- Fuzz ---------------------------------------------------------------------------------------

namespace {

/// Random input for poll(): each read returns a random-sized chunk (sometimes nothing waiting).
/// Checks every written line as it arrives, so 10 MB of garbage needs little memory.
class FuzzConsole : public platform::Console {
public:
    FuzzConsole(std::mt19937& rng, std::set<std::string> known)
        : rng_(rng), known_(std::move(known))
    {
    }

    const char* description() const noexcept override { return "fuzz"; }
    long read(char* buffer, std::size_t capacity) noexcept override
    {
        largestRequest = std::max(largestRequest, capacity);
        if (pending.empty() || std::uniform_int_distribution<int>(0, 15)(rng_) == 0)
            return 0;
        const std::size_t size = std::min(
            {capacity, pending.size(), std::uniform_int_distribution<std::size_t>(1, 4096)(rng_)});
        std::memcpy(buffer, pending.data(), size);
        pending.erase(0, size);
        deliveredThisPoll += size;
        return static_cast<long>(size);
    }
    void write(std::string_view text) noexcept override
    {
        for (char c : text) {
            if (c != '\n') {
                line_ += c;
                continue;
            }
            ++lines;
            const bool ok = isPrintableLine(line_) &&
                            (line_.rfind("error: ", 0) == 0 || line_.rfind("echo: ", 0) == 0 ||
                             known_.count(line_) > 0);
            if (!ok && bad.size() < 5)
                bad.push_back(line_);
            line_.clear();
        }
    }

    std::string pending;                ///< bytes the next reads deliver
    std::size_t largestRequest = 0;     ///< largest read capacity asked for
    std::size_t deliveredThisPoll = 0;  ///< bytes handed to the shell since the poll began
    std::size_t lines = 0;
    std::vector<std::string> bad;

private:
    std::mt19937& rng_;
    std::set<std::string> known_;
    std::string line_;
};

/// Every line help can print, so the fuzz check can recognise it.
std::set<std::string> knownReplies(CommandShell& shell)
{
    std::set<std::string> known;
    for (const char* command : {"help", "help help", "help echo"})
        for (const std::string& line : splitLines(run(shell, command)))
            known.insert(line);
    return known;
}

/// Polls until the console has delivered everything, checking the per-poll bound.
void drain(CommandShell& shell, FuzzConsole& console, std::size_t& maxPerPoll)
{
    for (int guard = 0; !console.pending.empty() && guard < 100000; ++guard) {
        console.deliveredThisPoll = 0;
        const CommandShell::PollResult result = shell.poll(console);
        EXPECT_EQ(result.bytesRead, console.deliveredThisPoll);
        maxPerPoll = std::max({maxPerPoll, result.bytesRead, console.largestRequest});
    }
}

}  // namespace

TEST(CommandShellFuzz, TenMegabytesOfRandomBytes)
{
    std::mt19937 rng(20240611);
    CommandShell shell;
    addEcho(shell);
    FuzzConsole console(rng, knownReplies(shell));
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_int_distribution<std::size_t> burst(1, 64 * 1024);
    std::size_t total = 0;
    std::size_t maxPerPoll = 0;
    while (total < 10u * 1024 * 1024) {
        const std::size_t n = burst(rng);
        for (std::size_t i = 0; i < n; ++i)
            console.pending += static_cast<char>(byte(rng));
        total += n;
        drain(shell, console, maxPerPoll);
        ASSERT_TRUE(console.pending.empty());
    }
    EXPECT_LE(maxPerPoll, 4096u);
    EXPECT_GT(console.lines, 1000u);
    EXPECT_TRUE(console.bad.empty()) << "first bad line: '" << console.bad.front() << "'";
}

TEST(CommandShellFuzz, RandomPrintableLines)
{
    std::mt19937 rng(7);
    CommandShell shell(ShellOptions{.maxLineLength = 96});
    addEcho(shell);
    FuzzConsole console(rng, knownReplies(shell));
    const std::vector<std::string> vocabulary = {"help", "echo", "status", "quit", "'",   "\\",
                                                 "\"",   "%s",   "%n",     "--",   "help"};
    std::uniform_int_distribution<int> printable(0x20, 0x7E);
    std::uniform_int_distribution<int> pick(0, 99);
    std::uniform_int_distribution<int> tokens(0, 12);
    std::uniform_int_distribution<int> tokenLength(1, 40);
    std::uniform_int_distribution<std::size_t> word(0, vocabulary.size() - 1);
    const std::vector<std::string> endings = {"\n", "\r", "\r\n", "\n\n"};
    std::size_t maxPerPoll = 0;
    for (int batch = 0; batch < 200; ++batch) {
        for (int line = 0; line < 100; ++line) {
            const int n = tokens(rng);
            for (int t = 0; t < n; ++t) {
                console.pending += std::string(1 + pick(rng) % 3, pick(rng) < 80 ? ' ' : '\t');
                if (pick(rng) < 40) {
                    console.pending += vocabulary[word(rng)];
                } else {
                    const int length = tokenLength(rng);
                    for (int i = 0; i < length; ++i) {
                        char c = static_cast<char>(printable(rng));
                        console.pending += c == ' ' ? '_' : c;
                    }
                }
                if (pick(rng) < 2)
                    console.pending += pick(rng) < 50 ? '\b' : '\x7f';
            }
            console.pending += endings[static_cast<std::size_t>(pick(rng)) % endings.size()];
        }
        drain(shell, console, maxPerPoll);
    }
    EXPECT_LE(maxPerPoll, 4096u);
    EXPECT_GT(console.lines, 10000u);
    EXPECT_TRUE(console.bad.empty()) << "first bad line: '" << console.bad.front() << "'";
}
