#pragma once
// FakeSystemd: plays systemd's side of sd_notify(3) for a test: a datagram socket named by
// NOTIFY_SOCKET, and the watchdog variables.

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

namespace testing_support {

/// Plays systemd: a datagram socket named by NOTIFY_SOCKET, and the watchdog variables.
class FakeSystemd {
public:
    explicit FakeSystemd(const char* watchdogUsec, long watchdogPid = ::getpid())
    {
        // One socket per test process (ctest runs the tests as parallel processes), in /tmp so
        // the path stays within sun_path's 108 bytes wherever the build tree is.
        path_ = "/tmp/mirror-notify-test-" + std::to_string(::getpid());
        ::unlink(path_.c_str());
        fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
        sockaddr_un address{};
        address.sun_family = AF_UNIX;
        std::strncpy(address.sun_path, path_.c_str(), sizeof address.sun_path - 1);
        EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address), 0)
            << std::strerror(errno);
        ::setenv("NOTIFY_SOCKET", path_.c_str(), 1);
        if (watchdogUsec) {
            ::setenv("WATCHDOG_USEC", watchdogUsec, 1);
            ::setenv("WATCHDOG_PID", std::to_string(watchdogPid).c_str(), 1);
        }
    }
    ~FakeSystemd()
    {
        ::unsetenv("NOTIFY_SOCKET");
        ::unsetenv("WATCHDOG_USEC");
        ::unsetenv("WATCHDOG_PID");
        ::close(fd_);
        ::unlink(path_.c_str());
    }
    std::vector<std::string> messages() const
    {
        std::vector<std::string> out;
        char buffer[512];
        for (ssize_t n; (n = ::recv(fd_, buffer, sizeof buffer, 0)) > 0;)
            out.emplace_back(buffer, static_cast<std::size_t>(n));
        return out;
    }

private:
    std::string path_;
    int fd_ = -1;
};

}  // namespace testing_support
