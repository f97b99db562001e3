#pragma once
// LineAssembler: turns the raw bytes a technician's terminal sends into complete text lines.

#include <cstddef>
#include <memory>
#include <string_view>

namespace firmware {

/// What the assembler found in the byte stream.
enum class LineEventKind {
    Line,     ///< a complete non-empty line of printable ASCII
    TooLong,  ///< the line exceeded the maximum length; the rest of it is discarded
    Binary,   ///< the line held a byte outside printable ASCII; the whole line is discarded
};

struct LineEvent {
    LineEventKind kind = LineEventKind::Line;
    /// The line without its CR/LF, for Line events (empty otherwise). It points into the
    /// assembler's buffer and is valid only during the handler call.
    std::string_view text;
};

/// Assembles lines from bytes in whatever chunks they arrive, with a buffer sized at construction.
///
/// - CR, LF and CRLF each end a line; empty lines are ignored (so CRLF is simply CR + LF).
/// - A line holds printable ASCII 0x20..0x7E; TAB is accepted and stored as a space.
/// - Backspace (0x08) and DEL (0x7F) delete the previous character, as typed on a serial terminal.
/// - A line longer than maxLineLength is reported once as TooLong, and its bytes are discarded up
///   to the end of that line; the next line is assembled normally.
/// - A line with any other byte (control characters, ESC sequences, UTF-8, NUL) is reported once as
///   Binary and discarded up to its end, so garbage never reaches a command.
///
/// feed() and finish() never allocate and never throw; the handler is called for each event with
/// a `const LineEvent&` and must not throw either.
class LineAssembler {
public:
    /// Throws std::runtime_error when maxLineLength is 0.
    explicit LineAssembler(std::size_t maxLineLength);

    template <typename Handler>
    void feed(const char* data, std::size_t size, Handler&& handler) noexcept
    {
        LineEvent event;
        while (scan(data, size, event))
            handler(static_cast<const LineEvent&>(event));
    }

    /// Ends the input (end of stream): a pending unterminated line is delivered as if ended.
    template <typename Handler>
    void finish(Handler&& handler) noexcept
    {
        LineEvent event;
        if (endLine(event))
            handler(static_cast<const LineEvent&>(event));
    }

    /// Forgets the pending partial line and any discard state.
    void reset() noexcept;

    std::size_t maxLineLength() const noexcept { return capacity_; }
    /// Characters of the unterminated line assembled so far.
    std::size_t pendingLength() const noexcept { return length_; }

private:
    /// Consumes bytes until one event is found (true) or the input is used up (false).
    bool scan(const char*& data, std::size_t& size, LineEvent& event) noexcept;
    /// Ends the current line; true with a Line event when it is not empty and not discarded.
    bool endLine(LineEvent& event) noexcept;

    std::unique_ptr<char[]> buffer_;
    std::size_t capacity_;
    std::size_t length_ = 0;
    bool discarding_ = false;  ///< an error was reported for this line; skip to its end
};

}  // namespace firmware
