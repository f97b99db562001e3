#include "platform/serial_console.hpp"

#include <errno.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <stdexcept>

namespace platform {

speed_t serialSpeed(int baud) noexcept
{
    // termios names each standard rate by its own constant, in the order of kSerialBaudRates.
    static constexpr speed_t kSpeeds[] = {
        B9600,   B19200,   B38400,   B57600,   B115200,  B230400,  B460800,  B500000,  B576000,
        B921600, B1000000, B1152000, B1500000, B2000000, B2500000, B3000000, B3500000, B4000000};
    static_assert(std::size(kSpeeds) == kSerialBaudRates.size());
    const auto* found = std::find(kSerialBaudRates.begin(), kSerialBaudRates.end(), baud);
    return found == kSerialBaudRates.end() ? 0 : kSpeeds[found - kSerialBaudRates.begin()];
}

namespace {

[[noreturn]] void fail(const std::string& path, const char* why, int error)
{
    throw std::runtime_error("serial console: " + path + ": " + why +
                             (error ? std::string(": ") + std::strerror(error) : std::string()));
}

}  // namespace

SerialConsole::SerialConsole(const std::string& path, SerialConsoleOptions options)
    : options_(options)
{
    const speed_t speed = serialSpeed(options.baud);
    if (speed == 0)
        fail(path, ("unsupported baud rate " + std::to_string(options.baud)).c_str(), 0);
    if (options.outputBuffer == 0)
        fail(path, "the output buffer must be at least 1 byte", 0);
    // O_NOCTTY: a service must not acquire the port as its controlling terminal (a hang-up
    // would then send it SIGHUP). O_NONBLOCK: open does not wait for carrier on modem lines.
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0)
        fail(path, "cannot open", errno);
    if (!::isatty(fd_)) {
        ::close(fd_);
        fail(path, "not a terminal device", 0);
    }
    if (::tcgetattr(fd_, &saved_) != 0) {
        const int error = errno;
        ::close(fd_);
        fail(path, "cannot read the port settings", error);
    }
    termios t = saved_;
    ::cfmakeraw(&t);  // no echo, no canonical lines, no CR/LF translation, 8 bits, no parity
    t.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS);
    t.c_cflag |= CLOCAL | CREAD;
    t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    t.c_cc[VMIN] = 0;
    t.c_cc[VTIME] = 0;
    ::cfsetispeed(&t, speed);
    ::cfsetospeed(&t, speed);
    if (::tcsetattr(fd_, TCSANOW, &t) != 0) {
        const int error = errno;
        ::close(fd_);
        fail(path, "cannot configure the port", error);
    }
    // Whatever the line picked up before we listened (boot noise) is not a command.
    ::tcflush(fd_, TCIFLUSH);
    ring_ = std::make_unique<char[]>(options.outputBuffer);
    std::snprintf(description_, sizeof description_, "serial %s %d 8N1", path.c_str(),
                  options.baud);
}

SerialConsole::~SerialConsole()
{
    if (fd_ >= 0) {
        flush();
        ::tcsetattr(fd_, TCSANOW, &saved_);
        ::close(fd_);
    }
}

void SerialConsole::setError(const char* what, int error) noexcept
{
    char text[96];
    std::snprintf(lastError_, sizeof lastError_, "%s: %s: %s", description_, what,
                  strerror_r(error, text, sizeof text));
}

long SerialConsole::read(char* buffer, std::size_t capacity) noexcept
{
    flush();
    if (capacity == 0)
        return 0;
    for (;;) {
        const ssize_t n = ::read(fd_, buffer, capacity);
        if (n > 0) {
            if (options_.echo)
                echo(buffer, static_cast<std::size_t>(n));
            return static_cast<long>(n);
        }
        if (n == 0)
            return 0;  // VMIN = 0: nothing waiting (a tty has no end of file)
        if (errno == EINTR)
            continue;
        if (errno != EAGAIN && errno != EWOULDBLOCK)
            setError("read", errno);  // EIO: hung up; the port may come back
        return 0;
    }
}

void SerialConsole::echo(const char* data, std::size_t size) noexcept
{
    // The echo of one read() call, sent with one queue() call per run of plain characters.
    std::size_t runStart = 0;
    auto endRun = [&](std::size_t i) {
        if (i > runStart)
            queue(data + runStart, i - runStart);
    };
    for (std::size_t i = 0; i < size; ++i) {
        const auto c = static_cast<unsigned char>(data[i]);
        const bool wasCr = lastWasCr_;
        lastWasCr_ = c == '\r';
        const bool plain = (c >= 0x20 && c <= 0x7E) || c == '\t';
        if (plain && !lineRejected_ && echoedLength_ < options_.maxLineLength) {
            ++echoedLength_;
            if (c == '\t') {  // shown as the space the shell makes of it
                endRun(i);
                queue(" ", 1);
                runStart = i + 1;
            }
            continue;
        }
        endRun(i);
        runStart = i + 1;
        if (c == '\r' || c == '\n') {
            if (!(c == '\n' && wasCr))
                queue("\r\n", 2);
            echoedLength_ = 0;
            lineRejected_ = false;
        } else if (c == 0x08 || c == 0x7F) {
            if (echoedLength_ > 0 && !lineRejected_) {
                --echoedLength_;
                queue("\b \b", 3);
            }
        } else {
            // Too long, or a byte the shell rejects the line for (escape sequences, binary
            // noise): like the shell, drop the rest of the line, so a flood is not echoed.
            lineRejected_ = true;
        }
    }
    endRun(size);
    flush();
}

void SerialConsole::queue(const char* data, std::size_t size) noexcept
{
    // When the port cannot keep up, the oldest output goes: the technician needs the answer to
    // what they just typed, not the backlog of a flood.
    const std::size_t capacity = options_.outputBuffer;
    if (size > capacity) {
        dropped_ += size - capacity;
        data += size - capacity;
        size = capacity;
    }
    const std::size_t room = capacity - queued_;
    if (size > room) {
        const std::size_t discard = size - room;
        head_ = (head_ + discard) % capacity;
        queued_ -= discard;
        dropped_ += discard;
    }
    std::size_t tail = (head_ + queued_) % capacity;
    for (std::size_t done = 0; done < size;) {
        const std::size_t piece = std::min(size - done, capacity - tail);
        std::memcpy(ring_.get() + tail, data + done, piece);
        done += piece;
        tail = (tail + piece) % capacity;
    }
    queued_ += size;
}

void SerialConsole::flush() noexcept
{
    const std::size_t capacity = options_.outputBuffer;
    while (queued_ > 0) {
        const std::size_t piece = std::min(queued_, capacity - head_);
        const ssize_t n = ::write(fd_, ring_.get() + head_, piece);
        if (n > 0) {
            head_ = (head_ + static_cast<std::size_t>(n)) % capacity;
            queued_ -= static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
            // Hung up: what is queued can never be delivered; keep room for what comes next.
            setError("write", errno);
            dropped_ += queued_;
            queued_ = 0;
            head_ = 0;
        }
        return;
    }
    head_ = 0;
}

std::size_t SerialConsole::writable() noexcept
{
    flush();
    return options_.outputBuffer - queued_;
}

void SerialConsole::write(std::string_view text) noexcept
{
    queue(text.data(), text.size());
    flush();
}

}  // namespace platform
