// The diagnostics shell on a serial console, through a pseudo-terminal: what a technician at a
// terminal emulator sees.
#include "alloc_counter.hpp"
#include "firmware/command_shell.hpp"
#include "platform/serial_console.hpp"
#include "pseudo_terminal.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

using firmware::Args;
using firmware::CommandShell;
using firmware::Reply;
using firmware::ShellOptions;
using platform::SerialConsole;

namespace {

/// The shell as the firmware sets it up for a serial port: prompt, CR LF line ends.
struct SerialShell {
    testing_support::PseudoTerminal terminal;
    // The firmware gives the console the shell's line limit, so echo stops where the shell cuts.
    SerialConsole console{terminal.slave, {.maxLineLength = 32}};
    CommandShell shell{
        ShellOptions{.maxLineLength = 32, .readBudget = 256, .prompt = true, .crlf = true}};
    SerialShell()
    {
        shell.add("version", "", "the firmware version",
                  [](const Args&, Reply& reply) { reply.line("mirror 0.1.0"); });
    }
    /// Polls like the frame loop would, a few frames' worth.
    void frames(int n)
    {
        for (int i = 0; i < n; ++i) {
            shell.poll(console);
            ::usleep(1000);
        }
    }
};

}  // namespace

TEST(SerialShell, EchoesTheCommandAndAnswersWithCrLf)
{
    SerialShell s;
    s.frames(1);
    EXPECT_EQ(s.terminal.screen(50), "> ");
    s.terminal.type("verz\x7fsion\r");
    s.frames(20);
    EXPECT_EQ(s.terminal.screen(50), "verz\b \bsion\r\nmirror 0.1.0\r\n> ");
}

TEST(SerialShell, ALongLineIsDroppedWithOneNotice)
{
    SerialShell s;
    s.frames(1);
    s.terminal.screen(50);
    s.terminal.type(std::string(100, 'a') + "\r");
    s.frames(20);
    EXPECT_EQ(s.terminal.screen(50),
              std::string(32, 'a') + "\r\nerror: line too long (max 32 characters)\r\n> ");
    s.terminal.type("version\r");
    s.frames(20);
    EXPECT_EQ(s.terminal.screen(50), "version\r\nmirror 0.1.0\r\n> ");
}

TEST(SerialShell, AFloodOfRandomBytesIsReadInBoundedPiecesWithoutAllocating)
{
    SerialShell s;
    s.frames(1);
    constexpr std::size_t kFlood = 1 << 20;
    std::vector<char> noise(kFlood);
    std::mt19937 random(7);
    for (char& c : noise)
        c = static_cast<char>(random() & 0xFF);
    std::thread flood([&] {
        for (std::size_t sent = 0; sent < kFlood;) {
            const ssize_t n = ::write(s.terminal.master, noise.data() + sent,
                                      std::min<std::size_t>(4096, kFlood - sent));
            if (n <= 0)
                break;
            sent += static_cast<std::size_t>(n);
        }
    });
    // The terminal shows whatever comes back (error lines), as a UART always drains: the shell
    // reads the next line only once its reply to the last one is out.
    std::atomic<bool> flooding{true};
    std::thread screen([&] {
        // Waits with a timeout, never in a blocking read: the flood ends with nothing more to
        // read, and the screen must still see `flooding` go false.
        char sink[4096];
        while (flooding.load()) {
            pollfd ready{s.terminal.master, POLLIN, 0};
            if (::poll(&ready, 1, 10) > 0 && ::read(s.terminal.master, sink, sizeof sink) <= 0)
                ::usleep(100);
        }
    });
    std::size_t received = 0;
    std::size_t largest = 0;
    testing_support::AllocationCounts counts;
    {
        testing_support::AllocationScope scope;
        while (received < kFlood) {
            const auto result = s.shell.poll(s.console);
            received += result.bytesRead;
            largest = std::max(largest, result.bytesRead);
            if (result.bytesRead == 0)
                ::usleep(100);
        }
        counts = scope.counts();
    }
    flood.join();
    for (int i = 0; i < 100 && s.shell.pendingOutput(0) > 0; ++i)
        s.frames(1);
    flooding = false;
    screen.join();
    EXPECT_EQ(received, kFlood);
    EXPECT_LE(largest, 256u);
    if (testing_support::allocationCountingAvailable()) {
        EXPECT_EQ(counts.cxxNew, 0);
        EXPECT_EQ(counts.ownMalloc, 0);
    }
    // The technician presses Enter and is answered again.
    s.terminal.type("\rversion\r");
    std::string seen;
    for (int i = 0; i < 200 && seen.find("mirror 0.1.0\r\n> ") == std::string::npos; ++i) {
        s.frames(1);
        seen += s.terminal.screen(50);
    }
    EXPECT_NE(seen.find("mirror 0.1.0\r\n> "), std::string::npos);
}

TEST(SerialShell, AReplyLongerThanTheOutputQueueArrivesWhole)
{
    // 2000 lines, about 30 KB: more than the serial console's 16 KB output queue and the old
    // 4 KB reply. The shell hands the console only what its queue takes, frame after frame.
    SerialShell s;
    s.shell.add("flood", "", "many lines", [](const Args&, Reply& reply) {
        for (int i = 0; i < 2000; ++i)
            reply.printf("line %04d of the reply\n", i);
    });
    s.frames(1);
    std::string seen = s.terminal.screen(50);
    s.terminal.type("flood\r");
    for (int i = 0; i < 2000 && seen.find("line 1999 of the reply\r\n> ") == std::string::npos;
         ++i) {
        s.frames(1);
        seen += s.terminal.screen(0);
    }
    std::size_t lines = 0;
    for (std::size_t at = 0; (at = seen.find(" of the reply\r\n", at)) != std::string::npos; ++at)
        ++lines;
    EXPECT_EQ(lines, 2000u);
    EXPECT_EQ(s.console.droppedBytes(), 0u);
    EXPECT_NE(seen.find("line 0000 of the reply\r\nline 0001"), std::string::npos);
}
