#include "platform/stdin_console.hpp"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace platform {

namespace {

void requireOpen(int fd, const char* role)
{
    if (fd < 0 || ::fcntl(fd, F_GETFL) < 0) {
        const int error = fd < 0 ? EBADF : errno;
        throw std::runtime_error(std::string("stdin console: ") + role + " fd " +
                                 std::to_string(fd) + " is not open: " + std::strerror(error));
    }
}

/// poll() with a zero timeout; the revents, or POLLNVAL-like failure as -1.
int pollNow(int fd, short events) noexcept
{
    pollfd p{fd, events, 0};
    for (;;) {
        const int r = ::poll(&p, 1, 0);
        if (r >= 0)
            return r == 0 ? 0 : p.revents;
        if (errno != EINTR)
            return -1;
    }
}

/// Writes to a non-socket fd with SIGPIPE blocked on this thread, consuming a SIGPIPE the write
/// raised (but not one that was already pending for someone else), so a closed reader cannot kill
/// the process whatever the process-wide SIGPIPE disposition is.
ssize_t writeWithoutSigpipe(int fd, const char* data, std::size_t size) noexcept
{
    sigset_t pipeOnly;
    sigemptyset(&pipeOnly);
    sigaddset(&pipeOnly, SIGPIPE);
    sigset_t pending;
    sigemptyset(&pending);
    sigpending(&pending);
    const bool wasPending = sigismember(&pending, SIGPIPE) == 1;
    sigset_t previous;
    pthread_sigmask(SIG_BLOCK, &pipeOnly, &previous);

    ssize_t n;
    do {
        n = ::write(fd, data, size);
    } while (n < 0 && errno == EINTR);
    const int error = errno;

    if (n < 0 && error == EPIPE && !wasPending) {
        const timespec zero{0, 0};
        while (sigtimedwait(&pipeOnly, nullptr, &zero) < 0 && errno == EINTR) {
        }
    }
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
    errno = error;
    return n;
}

}  // namespace

StdinConsole::StdinConsole(int inFd, int outFd) : inFd_(inFd), outFd_(outFd)
{
    requireOpen(inFd, "input");
    requireOpen(outFd, "output");
    struct stat st {};
    outIsSocket_ = ::fstat(outFd, &st) == 0 && S_ISSOCK(st.st_mode);
}

void StdinConsole::setError(const char* what, int error) noexcept
{
    char text[96];
    std::snprintf(lastError_, sizeof lastError_, "stdin: %s: %s", what,
                  strerror_r(error, text, sizeof text));
}

long StdinConsole::read(char* buffer, std::size_t capacity) noexcept
{
    if (closed_)
        return -1;
    if (capacity == 0)
        return 0;
    const int revents = pollNow(inFd_, POLLIN);
    if (revents < 0 || (revents & POLLNVAL)) {
        closed_ = true;
        setError("poll", revents < 0 ? errno : EBADF);
        return -1;
    }
    // POLLHUP/POLLERR without POLLIN: read() then reports the EOF or the error without blocking.
    if ((revents & (POLLIN | POLLHUP | POLLERR)) == 0)
        return 0;
    for (;;) {
        const ssize_t n = ::read(inFd_, buffer, capacity);
        if (n > 0)
            return static_cast<long>(n);
        if (n == 0) {
            closed_ = true;
            std::snprintf(lastError_, sizeof lastError_, "stdin: end of input");
            return -1;
        }
        if (errno == EINTR)
            continue;
        if (errno == EAGAIN || errno == EWOULDBLOCK)
            return 0;  // someone else set O_NONBLOCK and took the data first
        closed_ = true;
        setError("read", errno);
        return -1;
    }
}

long StdinConsole::writeSome(const char* data, std::size_t size) noexcept
{
    if (outIsSocket_) {
        ssize_t n;
        do {
            n = ::send(outFd_, data, size, MSG_NOSIGNAL | MSG_DONTWAIT);
        } while (n < 0 && errno == EINTR);
        return static_cast<long>(n);
    }
    return static_cast<long>(writeWithoutSigpipe(outFd_, data, size));
}

std::size_t StdinConsole::writable() noexcept
{
    const int revents = pollNow(outFd_, POLLOUT);
    // A broken output takes everything (write() drops and counts it): a reply must not wait for
    // a reader that went away.
    if (revents < 0 || (revents & (POLLERR | POLLHUP | POLLNVAL)))
        return std::numeric_limits<std::size_t>::max();
    // After POLLOUT a pipe takes PIPE_BUF bytes without blocking.
    return (revents & POLLOUT) ? PIPE_BUF : 0;
}

void StdinConsole::write(std::string_view text) noexcept
{
    const char* data = text.data();
    std::size_t left = text.size();
    while (left > 0) {
        const int revents = pollNow(outFd_, POLLOUT);
        if (revents < 0 || (revents & POLLOUT) == 0) {
            if (revents < 0 || (revents & (POLLERR | POLLHUP | POLLNVAL)))
                setError("write", revents < 0 ? errno : EPIPE);
            break;
        }
        const std::size_t piece = std::min<std::size_t>(left, PIPE_BUF);
        const long n = writeSome(data, piece);
        if (n <= 0) {
            if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK)
                setError("write", errno);
            break;
        }
        data += n;
        left -= static_cast<std::size_t>(n);
    }
    dropped_ += left;
}

}  // namespace platform
