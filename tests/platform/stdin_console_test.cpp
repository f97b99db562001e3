#include "platform/stdin_console.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

using platform::StdinConsole;

namespace {

/// Both ends of a pipe or socket pair, closed at the end of the test.
struct FdPair {
    int fd[2] = {-1, -1};
    ~FdPair()
    {
        closeEnd(0);
        closeEnd(1);
    }
    void closeEnd(int i)
    {
        if (fd[i] >= 0)
            ::close(fd[i]);
        fd[i] = -1;
    }
};

void makePipe(FdPair& p)
{
    ASSERT_EQ(::pipe(p.fd), 0) << std::strerror(errno);
}
void makeSocketPair(FdPair& p)
{
    ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, p.fd), 0) << std::strerror(errno);
}

void setNonBlocking(int fd, bool on)
{
    const int flags = ::fcntl(fd, F_GETFL);
    ::fcntl(fd, F_SETFL, on ? flags | O_NONBLOCK : flags & ~O_NONBLOCK);
}

/// Everything readable from `fd` right now (the test's own end, made non-blocking for this).
std::string drain(int fd)
{
    setNonBlocking(fd, true);
    std::string out;
    char buffer[4096];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n <= 0)
            break;
        out.append(buffer, static_cast<std::size_t>(n));
    }
    setNonBlocking(fd, false);
    return out;
}

/// Fills a pipe until it takes no more; returns the bytes written.
std::size_t fill(int fd)
{
    setNonBlocking(fd, true);
    const std::string block(4096, 'f');
    std::size_t total = 0;
    for (;;) {
        const ssize_t n = ::write(fd, block.data(), block.size());
        if (n <= 0)
            break;
        total += static_cast<std::size_t>(n);
    }
    setNonBlocking(fd, false);
    return total;
}

/// A console that blocks fails these tests by never finishing: the alarm ends the process then,
/// instead of hanging the test run.
class StdinConsoleTest : public ::testing::Test {
protected:
    void SetUp() override { ::alarm(20); }
    void TearDown() override { ::alarm(0); }
};

}  // namespace

TEST_F(StdinConsoleTest, DescribesItself)
{
    FdPair p;
    makePipe(p);
    StdinConsole console(p.fd[0], p.fd[1]);
    EXPECT_STREQ(console.description(), "stdin");
    EXPECT_FALSE(console.closed());
    EXPECT_EQ(console.droppedBytes(), 0u);
    EXPECT_STREQ(console.lastError(), "");
}

TEST_F(StdinConsoleTest, RejectsClosedDescriptors)
{
    FdPair p;
    makePipe(p);
    const int closedFd = p.fd[1];
    p.closeEnd(1);
    EXPECT_THROW(StdinConsole(p.fd[0], closedFd), std::runtime_error);
    EXPECT_THROW(StdinConsole(-1, p.fd[0]), std::runtime_error);
    try {
        StdinConsole console(closedFd, p.fd[0]);
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("Bad file descriptor"), std::string::npos) << e.what();
    }
}

TEST_F(StdinConsoleTest, ReadReturnsZeroWhenNothingWaits)
{
    FdPair p;
    makePipe(p);
    StdinConsole console(p.fd[0], p.fd[1]);
    char buffer[64];
    EXPECT_EQ(console.read(buffer, sizeof buffer), 0);
    EXPECT_EQ(console.read(buffer, 0), 0);
    EXPECT_FALSE(console.closed());
}

TEST_F(StdinConsoleTest, ReadDeliversWhatWaitsUpToCapacity)
{
    FdPair p;
    makePipe(p);
    StdinConsole console(p.fd[0], p.fd[1]);
    ASSERT_EQ(::write(p.fd[1], "status\nhelp\n", 12), 12);
    char buffer[8];
    ASSERT_EQ(console.read(buffer, 8), 8);
    EXPECT_EQ(std::string(buffer, 8), "status\nh");
    ASSERT_EQ(console.read(buffer, 8), 4);
    EXPECT_EQ(std::string(buffer, 4), "elp\n");
    EXPECT_EQ(console.read(buffer, 8), 0);
}

TEST_F(StdinConsoleTest, EndOfInputClosesTheConsole)
{
    FdPair p;
    makePipe(p);
    ASSERT_EQ(::write(p.fd[1], "quit", 4), 4);
    FdPair other;  // an output that stays open while the input pipe's write end goes away
    makePipe(other);
    StdinConsole reader(p.fd[0], other.fd[1]);
    p.closeEnd(1);
    char buffer[16];
    ASSERT_EQ(reader.read(buffer, sizeof buffer), 4);  // data before the end is still delivered
    EXPECT_FALSE(reader.closed());
    EXPECT_EQ(reader.read(buffer, sizeof buffer), -1);
    EXPECT_TRUE(reader.closed());
    EXPECT_STREQ(reader.lastError(), "stdin: end of input");
    EXPECT_EQ(reader.read(buffer, sizeof buffer), -1);  // stays closed
}

TEST_F(StdinConsoleTest, DevNullIsAnImmediateEnd)
{
    const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
    ASSERT_GE(null, 0);
    {
        StdinConsole console(null, null);
        char buffer[16];
        EXPECT_EQ(console.read(buffer, sizeof buffer), -1);
        EXPECT_TRUE(console.closed());
        console.write("nobody listens\n");
        EXPECT_EQ(console.droppedBytes(), 0u);
    }
    ::close(null);
}

TEST_F(StdinConsoleTest, LeavesFileStatusFlagsAlone)
{
    FdPair p;
    makePipe(p);
    const int inFlags = ::fcntl(p.fd[0], F_GETFL);
    const int outFlags = ::fcntl(p.fd[1], F_GETFL);
    StdinConsole console(p.fd[0], p.fd[1]);
    char buffer[16];
    console.write("x\n");
    console.read(buffer, sizeof buffer);
    console.read(buffer, sizeof buffer);
    EXPECT_EQ(::fcntl(p.fd[0], F_GETFL), inFlags);
    EXPECT_EQ(::fcntl(p.fd[1], F_GETFL), outFlags);
    EXPECT_EQ(inFlags & O_NONBLOCK, 0);
}

TEST_F(StdinConsoleTest, WriteDeliversText)
{
    FdPair p;
    makePipe(p);
    StdinConsole console(p.fd[0], p.fd[1]);
    console.write("error: binary data ignored\n");
    console.write("");
    console.write("> ");
    EXPECT_EQ(drain(p.fd[0]), "error: binary data ignored\n> ");
    EXPECT_EQ(console.droppedBytes(), 0u);
}

TEST_F(StdinConsoleTest, WriteToAFullPipeDropsInsteadOfBlocking)
{
    FdPair p;
    makePipe(p);
    StdinConsole console(p.fd[0], p.fd[1]);
    const std::size_t capacity = fill(p.fd[1]);
    ASSERT_GT(capacity, 0u);
    console.write("hello\n");
    EXPECT_EQ(console.droppedBytes(), 6u);
    console.write("again");
    EXPECT_EQ(console.droppedBytes(), 11u);
    EXPECT_EQ(drain(p.fd[0]).size(), capacity);  // nothing of ours got in
}

TEST_F(StdinConsoleTest, WriteMoreThanFitsWritesAPrefixAndDropsTheRest)
{
    FdPair p;
    makePipe(p);
    StdinConsole console(p.fd[0], p.fd[1]);
    std::string text;
    for (int i = 0; text.size() < 1024 * 1024; ++i)
        text += "line " + std::to_string(i) + "\n";
    console.write(text);
    const std::string got = drain(p.fd[0]);
    EXPECT_GT(got.size(), 0u);
    EXPECT_LT(got.size(), text.size());
    EXPECT_EQ(got.size() + console.droppedBytes(), text.size());
    EXPECT_EQ(got, text.substr(0, got.size()));
    // With room again, later text goes through.
    console.write("after\n");
    EXPECT_EQ(drain(p.fd[0]), "after\n");
}

TEST_F(StdinConsoleTest, BrokenPipeRaisesNoSigpipe)
{
    FdPair p;
    makePipe(p);
    FdPair input;
    makePipe(input);
    StdinConsole console(input.fd[0], p.fd[1]);
    p.closeEnd(0);
    // The default action would end this test process if the console let a SIGPIPE through.
    struct sigaction previous {};
    struct sigaction byDefault {};
    byDefault.sa_handler = SIG_DFL;
    ASSERT_EQ(::sigaction(SIGPIPE, &byDefault, &previous), 0);
    sigset_t maskBefore;
    pthread_sigmask(SIG_SETMASK, nullptr, &maskBefore);

    console.write("status\n");
    console.write("more\n");

    EXPECT_EQ(console.droppedBytes(), 12u);
    EXPECT_NE(std::string(console.lastError()).find("Broken pipe"), std::string::npos)
        << console.lastError();
    sigset_t pending;
    sigpending(&pending);
    EXPECT_EQ(sigismember(&pending, SIGPIPE), 0);
    sigset_t maskAfter;
    pthread_sigmask(SIG_SETMASK, nullptr, &maskAfter);
    EXPECT_EQ(sigismember(&maskAfter, SIGPIPE), sigismember(&maskBefore, SIGPIPE));
    ::sigaction(SIGPIPE, &previous, nullptr);
}

TEST_F(StdinConsoleTest, BrokenPipeLeavesAnEarlierPendingSigpipe)
{
    FdPair p;
    makePipe(p);
    StdinConsole console(p.fd[0], p.fd[1]);
    p.closeEnd(0);
    // Someone else's SIGPIPE, pending while blocked: the console must not swallow it.
    sigset_t pipeOnly;
    sigemptyset(&pipeOnly);
    sigaddset(&pipeOnly, SIGPIPE);
    sigset_t previous;
    pthread_sigmask(SIG_BLOCK, &pipeOnly, &previous);
    ::raise(SIGPIPE);
    console.write("x\n");
    sigset_t pending;
    sigpending(&pending);
    EXPECT_EQ(sigismember(&pending, SIGPIPE), 1);
    const timespec zero{0, 0};
    EXPECT_EQ(sigtimedwait(&pipeOnly, nullptr, &zero), SIGPIPE);
    sigset_t mask;
    pthread_sigmask(SIG_SETMASK, nullptr, &mask);
    EXPECT_EQ(sigismember(&mask, SIGPIPE), 1);  // the caller's mask is kept
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

TEST_F(StdinConsoleTest, SocketPairBothWays)
{
    FdPair s;
    makeSocketPair(s);
    StdinConsole console(s.fd[0], s.fd[0]);
    char buffer[32];
    EXPECT_EQ(console.read(buffer, sizeof buffer), 0);
    ASSERT_EQ(::write(s.fd[1], "help\r\n", 6), 6);
    ASSERT_EQ(console.read(buffer, sizeof buffer), 6);
    EXPECT_EQ(std::string(buffer, 6), "help\r\n");
    console.write("commands:\n");
    EXPECT_EQ(drain(s.fd[1]), "commands:\n");
    EXPECT_EQ(console.droppedBytes(), 0u);
}

TEST_F(StdinConsoleTest, SocketPeerGoneIsEndOfInputAndNoSigpipe)
{
    FdPair s;
    makeSocketPair(s);
    StdinConsole console(s.fd[0], s.fd[0]);
    struct sigaction previous {};
    struct sigaction byDefault {};
    byDefault.sa_handler = SIG_DFL;
    ASSERT_EQ(::sigaction(SIGPIPE, &byDefault, &previous), 0);
    s.closeEnd(1);
    char buffer[32];
    EXPECT_EQ(console.read(buffer, sizeof buffer), -1);
    EXPECT_TRUE(console.closed());
    console.write("bye\n");
    EXPECT_EQ(console.droppedBytes(), 4u);
    ::sigaction(SIGPIPE, &previous, nullptr);
}

TEST_F(StdinConsoleTest, FullSocketDropsInsteadOfBlocking)
{
    FdPair s;
    makeSocketPair(s);
    StdinConsole console(s.fd[0], s.fd[0]);
    const std::string block(64 * 1024, 'b');
    std::size_t offered = 0;
    // The socket buffer is finite: eventually writes are dropped, and nothing blocks.
    while (console.droppedBytes() == 0 && offered < 64u * 1024 * 1024) {
        console.write(block);
        offered += block.size();
    }
    EXPECT_GT(console.droppedBytes(), 0u);
    EXPECT_EQ(drain(s.fd[1]).size() + console.droppedBytes(), offered);
}
