#include "platform/serial_console.hpp"

#include "alloc_counter.hpp"
#include "pseudo_terminal.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using platform::SerialConsole;
using platform::SerialConsoleOptions;

namespace {

using Pty = testing_support::PseudoTerminal;

/// Reads until `expected` bytes came or nothing more arrives for a while.
std::string readAll(SerialConsole& console, std::size_t expected)
{
    std::string in;
    char buffer[256];
    for (int idle = 0; in.size() < expected && idle < 1000;) {
        const long n = console.read(buffer, sizeof buffer);
        if (n > 0) {
            in.append(buffer, static_cast<std::size_t>(n));
            idle = 0;
        } else {
            ++idle;
            ::usleep(1000);
        }
    }
    return in;
}

}  // namespace

TEST(SerialConsole, MissingPortThrowsOneLineNamingIt)
{
    try {
        SerialConsole console("/dev/no-such-tty");
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("/dev/no-such-tty"), std::string::npos) << what;
        EXPECT_NE(what.find("No such file or directory"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

TEST(SerialConsole, RefusesANonTerminalAndAnOddRate)
{
    EXPECT_THROW(SerialConsole("/dev/null"), std::runtime_error);
    Pty pty;
    SerialConsoleOptions options;
    options.baud = 12345;
    EXPECT_THROW(SerialConsole(pty.slave, options), std::runtime_error);
}

TEST(SerialConsole, SetsRaw8N1AtTheRateAndRestoresOnClose)
{
    Pty pty;
    const int probe = ::open(pty.slave.c_str(), O_RDWR | O_NOCTTY);
    ASSERT_GE(probe, 0);
    termios before{};
    ASSERT_EQ(::tcgetattr(probe, &before), 0);
    ASSERT_TRUE(before.c_lflag & ICANON);
    {
        SerialConsole console(pty.slave);
        EXPECT_NE(std::string(console.description()).find(pty.slave), std::string::npos);
        termios t{};
        ASSERT_EQ(::tcgetattr(probe, &t), 0);
        EXPECT_FALSE(t.c_lflag & (ICANON | ECHO | ISIG));
        EXPECT_FALSE(t.c_iflag & (ICRNL | IXON));
        EXPECT_EQ(t.c_cflag & CSIZE, static_cast<tcflag_t>(CS8));
        EXPECT_FALSE(t.c_cflag & (PARENB | CSTOPB));
        EXPECT_EQ(::cfgetospeed(&t), static_cast<speed_t>(B115200));
    }
    termios after{};
    ASSERT_EQ(::tcgetattr(probe, &after), 0);
    EXPECT_TRUE(after.c_lflag & ICANON);
    ::close(probe);
}

TEST(SerialConsole, ReturnsTypedBytesUnchangedAndEchoesThem)
{
    Pty pty;
    SerialConsole console(pty.slave);
    char buffer[64];
    EXPECT_EQ(console.read(buffer, sizeof buffer), 0);  // nothing typed yet: no wait
    pty.type("status\r");
    EXPECT_EQ(readAll(console, 7), "status\r");
    EXPECT_EQ(pty.screen(), "status\r\n");
    // LF alone and CR LF each end one line on the screen.
    pty.type("a\nb\r\n");
    EXPECT_EQ(readAll(console, 5), "a\nb\r\n");
    EXPECT_EQ(pty.screen(), "a\r\nb\r\n");
}

TEST(SerialConsole, BackspaceRubsOutButNotPastTheLineStart)
{
    Pty pty;
    SerialConsole console(pty.slave);
    pty.type("ab\x7f\x08\x08x\r");
    EXPECT_EQ(readAll(console, 7), "ab\x7f\x08\x08x\r");
    EXPECT_EQ(pty.screen(), "ab\b \b\b \bx\r\n");
}

TEST(SerialConsole, StopsEchoingALineTooLongOrBinary)
{
    Pty pty;
    SerialConsoleOptions options;
    options.maxLineLength = 8;
    SerialConsole console(pty.slave, options);
    const std::string longLine(20, 'x');
    pty.type(longLine + "\rok\r");
    EXPECT_EQ(readAll(console, 24), longLine + "\rok\r");
    EXPECT_EQ(pty.screen(), std::string(8, 'x') + "\r\nok\r\n");
    pty.type("\x1b[A\x01junk\rhelp\r");
    readAll(console, 13);
    EXPECT_EQ(pty.screen(), "\r\nhelp\r\n");
}

TEST(SerialConsole, QueuesRepliesAndDropsWhatDoesNotFitWithoutBlocking)
{
    Pty pty;
    SerialConsoleOptions options;
    options.outputBuffer = 1024;
    SerialConsole console(pty.slave, options);
    console.write("hello\r\n");
    EXPECT_EQ(pty.screen(), "hello\r\n");
    // Nobody reads the terminal: the pty fills, then the queue, then output is dropped.
    const std::string block(4096, 'y');
    for (int i = 0; i < 64; ++i)
        console.write(block);
    EXPECT_GT(console.droppedBytes(), 0u);
    EXPECT_LE(console.pendingOutput(), 1024u);
    // The newest output survives: the end of the last block is still queued.
    console.write("answer\r\n");
    // Once the terminal reads again, the queue drains on the next polls.
    std::string seen = pty.screen();
    char buffer[16];
    for (int i = 0; i < 10 && console.pendingOutput() > 0; ++i) {
        console.read(buffer, sizeof buffer);
        seen += pty.screen();
    }
    EXPECT_EQ(console.pendingOutput(), 0u);
    EXPECT_EQ(seen.substr(seen.size() - 8), "answer\r\n");
}

TEST(SerialConsole, AMegabyteOfRandomBytesDoesNotStallOrAllocate)
{
    Pty pty;
    SerialConsole console(pty.slave);
    constexpr std::size_t kFlood = 1 << 20;
    std::vector<char> noise(kFlood);
    std::mt19937 random(42);
    for (char& c : noise)
        c = static_cast<char>(random() & 0xFF);

    // The terminal side floods from another thread (a pty takes only a few KiB at a time) and
    // never reads the echo, like a line with noise and no one listening.
    std::thread flood([&] {
        std::size_t sent = 0;
        while (sent < kFlood) {
            const ssize_t n = ::write(pty.master, noise.data() + sent,
                                      std::min<std::size_t>(4096, kFlood - sent));
            if (n <= 0)
                break;
            sent += static_cast<std::size_t>(n);
        }
    });

    constexpr std::size_t kBudget = 512;  // what a frame reads at most
    char buffer[kBudget];
    std::size_t received = 0;
    long largest = 0;
    long reads = 0;
    testing_support::AllocationCounts counts;
    {
        testing_support::AllocationScope scope;
        while (received < kFlood) {
            const long n = console.read(buffer, kBudget);
            if (n > 0) {
                received += static_cast<std::size_t>(n);
                largest = std::max(largest, n);
                ++reads;
            } else {
                ::usleep(100);
            }
        }
        counts = scope.counts();
    }
    flood.join();
    EXPECT_EQ(received, kFlood);
    EXPECT_LE(largest, static_cast<long>(kBudget));
    EXPECT_GE(reads, static_cast<long>(kFlood / kBudget));
    if (testing_support::allocationCountingAvailable()) {
        EXPECT_EQ(counts.cxxNew, 0);
        EXPECT_EQ(counts.ownMalloc, 0);
        EXPECT_EQ(counts.foreignMalloc, 0);
    }
    // Still a working console afterwards.
    pty.screen();
    pty.type("\rversion\r");
    EXPECT_EQ(readAll(console, 9), "\rversion\r");
}
