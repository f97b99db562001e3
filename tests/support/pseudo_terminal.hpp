#pragma once
// A pseudo-terminal for console tests: the code under test opens the slave by path (as it would
// /dev/ttyS0), the test plays the technician's terminal on the master.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

namespace testing_support {

class PseudoTerminal {
public:
    PseudoTerminal()
    {
        master = ::posix_openpt(O_RDWR | O_NOCTTY);
        EXPECT_GE(master, 0) << std::strerror(errno);
        if (master >= 0 && ::grantpt(master) == 0 && ::unlockpt(master) == 0)
            slave = ::ptsname(master);
        EXPECT_FALSE(slave.empty()) << "no pseudo-terminal: " << std::strerror(errno);
    }
    ~PseudoTerminal()
    {
        if (master >= 0)
            ::close(master);
    }
    PseudoTerminal(const PseudoTerminal&) = delete;
    PseudoTerminal& operator=(const PseudoTerminal&) = delete;

    /// Types `bytes` (a few KiB at most: the pty's buffer).
    void type(std::string_view bytes) const
    {
        ASSERT_EQ(::write(master, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
    }

    /// Types all of `bytes`, however many, reading what comes back meanwhile into `screen` so
    /// neither side's buffer fills up.
    void typeAll(std::string_view bytes, std::string& screen) const
    {
        for (std::size_t sent = 0; sent < bytes.size();) {
            pollfd p{master, POLLIN | POLLOUT, 0};
            if (::poll(&p, 1, 100) < 0)
                return;
            if (p.revents & POLLIN)
                readInto(screen);
            if (p.revents & POLLOUT) {
                const ssize_t n = ::write(master, bytes.data() + sent,
                                          std::min<std::size_t>(4096, bytes.size() - sent));
                if (n > 0)
                    sent += static_cast<std::size_t>(n);
            }
        }
    }

    /// What was sent to the terminal: waits up to `firstByteWaitMs` for the first byte, then
    /// reads until nothing more comes for 50 ms.
    std::string screen(int firstByteWaitMs = 1000) const
    {
        std::string out;
        pollfd p{master, POLLIN, 0};
        int timeoutMs = firstByteWaitMs;
        while (::poll(&p, 1, timeoutMs) > 0 && (p.revents & POLLIN)) {
            if (!readInto(out))
                break;
            timeoutMs = 50;
        }
        return out;
    }

    /// Reads into `screen` until `text` shows up at or after `from`, or `seconds` passed.
    bool waitFor(std::string& screen, std::string_view text, std::size_t from, int seconds) const
    {
        for (int i = 0; i < seconds * 20; ++i) {
            if (screen.find(text, from) != std::string::npos)
                return true;
            pollfd p{master, POLLIN, 0};
            if (::poll(&p, 1, 50) > 0 && (p.revents & POLLIN))
                readInto(screen);
        }
        return screen.find(text, from) != std::string::npos;
    }

    int master = -1;
    std::string slave;  ///< the path the code under test opens

private:
    bool readInto(std::string& out) const
    {
        char buffer[4096];
        const ssize_t n = ::read(master, buffer, sizeof buffer);
        if (n <= 0)
            return false;
        out.append(buffer, static_cast<std::size_t>(n));
        return true;
    }
};

}  // namespace testing_support
