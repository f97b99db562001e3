#pragma once
// StdinConsole: the diagnostics console on the process's stdin and stdout (or any two fds).

#include "platform/console.hpp"

#include <cstddef>
#include <string_view>

namespace platform {

/// A Console on two file descriptors, by default 0 and 1, that never blocks the frame loop.
///
/// The descriptors are borrowed: they are not closed by the destructor, and their file status
/// flags are never changed. O_NONBLOCK lives on the open file description, which stdin/stdout
/// share with the parent shell and its other children, so instead each read() and write() first
/// asks poll() with a zero timeout whether the fd is ready.
///
/// read() returns the bytes that are waiting now, 0 when nothing is, and -1 once the input
/// reached end of file or failed; the console then reports closed() and stops touching the fd.
///
/// write() writes what the output accepts now, in pieces of at most PIPE_BUF bytes (after POLLOUT
/// a Linux pipe takes that much without blocking), and drops the rest, counting the dropped bytes.
/// A reader that went away never raises SIGPIPE: sockets are written with MSG_NOSIGNAL, other fds
/// with SIGPIPE blocked on the calling thread and any SIGPIPE the write raised consumed again.
class StdinConsole final : public Console {
public:
    /// Throws std::runtime_error when either fd is not open.
    explicit StdinConsole(int inFd = 0, int outFd = 1);

    const char* description() const noexcept override { return "stdin"; }
    long read(char* buffer, std::size_t capacity) noexcept override;
    void write(std::string_view text) noexcept override;
    /// PIPE_BUF when the output is ready now, 0 when it is full; everything when it is broken.
    std::size_t writable() noexcept override;

    /// True once the input reached end of file or failed; read() returns -1 from then on.
    bool closed() const noexcept { return closed_; }
    /// Output bytes dropped so far because the output fd was full or broken.
    std::size_t droppedBytes() const noexcept { return dropped_; }
    /// Why the input closed or the last write failed; "" when nothing failed.
    const char* lastError() const noexcept { return lastError_; }

private:
    long writeSome(const char* data, std::size_t size) noexcept;
    void setError(const char* what, int error) noexcept;

    int inFd_;
    int outFd_;
    bool outIsSocket_ = false;
    bool closed_ = false;
    std::size_t dropped_ = 0;
    char lastError_[128] = "";
};

}  // namespace platform
