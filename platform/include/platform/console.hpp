#pragma once
// Console: a byte stream to a technician (stdin/stdout now; later a serial port).

#include <cstddef>
#include <limits>
#include <string_view>

namespace platform {

class Console {
public:
    virtual ~Console() = default;
    Console() = default;
    Console(const Console&) = delete;
    Console& operator=(const Console&) = delete;

    virtual const char* description() const noexcept = 0;
    /// Non-blocking read: bytes read (> 0), 0 when nothing is waiting, -1 when the stream closed.
    virtual long read(char* buffer, std::size_t capacity) noexcept = 0;
    /// Best-effort write of the whole text; drops output rather than block the frame loop.
    virtual void write(std::string_view text) noexcept = 0;
    /// Bytes write() takes now without dropping any; a long reply is sent in pieces this size
    /// as the console drains. Consoles that never drop say so with the largest size.
    virtual std::size_t writable() noexcept { return std::numeric_limits<std::size_t>::max(); }
};

}  // namespace platform
