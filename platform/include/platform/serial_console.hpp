#pragma once
// SerialConsole: the diagnostics console on a serial port (a technician's terminal on a UART).

#include "platform/console.hpp"

#include <termios.h>

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

namespace platform {

/// The rates a serial console can be set to: the standard ones termios names (B9600 ... B4000000).
inline constexpr std::array<int, 18> kSerialBaudRates = {
    9600,   19200,   38400,   57600,   115200,  230400,  460800,  500000,  576000,
    921600, 1000000, 1152000, 1500000, 2000000, 2500000, 3000000, 3500000, 4000000};

struct SerialConsoleOptions {
    int baud = 115200;                 ///< one of kSerialBaudRates
    std::size_t maxLineLength = 256;   ///< characters echoed per line; the rest is not echoed
    std::size_t outputBuffer = 16384;  ///< replies queued while the UART drains them
    bool echo = true;                  ///< echo typed characters (a human at a terminal)
};

/// A Console on a serial port, opened from a path such as /dev/ttyS0 or /dev/ttyAMA0, set to the
/// configured rate, 8 data bits, no parity, 1 stop bit, raw (no line discipline processing), no
/// flow control, modem lines ignored (CLOCAL), and non-blocking. The previous settings are
/// restored when the console is destroyed.
///
/// The far end is a person at a terminal emulator, which does not echo locally, so the console
/// echoes what is typed: printable characters as they come, Enter (CR, LF or CRLF) as CR LF,
/// Backspace and DEL by rubbing out the last echoed character (never past the start of the line).
/// Echo stops for the rest of a line once it is longer than maxLineLength or holds any other byte
/// (escape sequences, binary noise), the lines the shell rejects. read() still returns every byte
/// unchanged: the line policy (what is a command, what is rejected with which notice) belongs to
/// the shell reading it.
///
/// Nothing blocks and nothing allocates after construction: read() makes one non-blocking read()
/// of at most `capacity` bytes, so a flood is taken in bounded pieces; write() queues into a
/// fixed ring of outputBuffer bytes that is flushed as far as the UART accepts on every read()
/// and write(); when it is full the oldest queued output is dropped (and counted), so the answer
/// to the latest command survives a backlog. A hang-up (the other end of a pty
/// closed, a USB adapter gone) reads as "nothing waiting" and is reported in lastError().
class SerialConsole final : public Console {
public:
    /// Throws std::runtime_error with one line when the path cannot be opened, is not a terminal,
    /// or the rate is not supported.
    explicit SerialConsole(const std::string& path, SerialConsoleOptions options = {});
    ~SerialConsole() override;

    const char* description() const noexcept override { return description_; }
    long read(char* buffer, std::size_t capacity) noexcept override;
    void write(std::string_view text) noexcept override;
    /// Room left in the output queue after flushing what the port takes now.
    std::size_t writable() noexcept override;

    /// Writes as much queued output as the port takes now.
    void flush() noexcept;

    /// Output bytes dropped so far because the queue was full or the port failed.
    std::size_t droppedBytes() const noexcept { return dropped_; }
    /// Bytes waiting in the output queue.
    std::size_t pendingOutput() const noexcept { return queued_; }
    /// The last read or write failure ("" when none).
    const char* lastError() const noexcept { return lastError_; }

private:
    void echo(const char* data, std::size_t size) noexcept;
    void queue(const char* data, std::size_t size) noexcept;
    void setError(const char* what, int error) noexcept;

    int fd_ = -1;
    termios saved_{};
    SerialConsoleOptions options_;
    std::unique_ptr<char[]> ring_;
    std::size_t head_ = 0;    ///< index of the oldest queued byte
    std::size_t queued_ = 0;  ///< bytes in the ring
    std::size_t dropped_ = 0;
    std::size_t echoedLength_ = 0;  ///< characters echoed on the current line
    bool lineRejected_ = false;     ///< too long or binary: echo nothing until the line ends
    bool lastWasCr_ = false;
    char description_[96] = "";
    char lastError_[128] = "";
};

/// The termios speed constant for a rate in baud, or 0 when it is not one of kSerialBaudRates.
speed_t serialSpeed(int baud) noexcept;

}  // namespace platform
