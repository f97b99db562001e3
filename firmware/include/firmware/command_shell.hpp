#pragma once
// CommandShell: the diagnostics command line a field technician uses over a Console.

#include "firmware/line_assembler.hpp"
#include "platform/console.hpp"

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace firmware {

/// The words of one command line, split on spaces and tabs; args[0] is the command name.
/// The views point into the line and are valid only while the command runs.
class Args {
public:
    static constexpr std::size_t kMaxTokens = 8;  ///< the command name and up to 7 arguments

    enum class Parse {
        Ok,
        Empty,    ///< blank line: nothing to run
        TooMany,  ///< more than kMaxTokens words; the first kMaxTokens are kept
    };

    Parse parse(std::string_view line) noexcept;

    std::size_t size() const noexcept { return count_; }
    /// The i-th word, or "" past the end.
    std::string_view operator[](std::size_t i) const noexcept
    {
        return i < count_ ? tokens_[i] : std::string_view();
    }
    const std::string_view* begin() const noexcept { return tokens_.data(); }
    const std::string_view* end() const noexcept { return tokens_.data() + count_; }

private:
    std::array<std::string_view, kMaxTokens> tokens_{};
    std::size_t count_ = 0;
};

/// A command's reply: a fixed-size text buffer, appended to printf-style, never allocating.
///
/// Text beyond the capacity is cut, and the reply then ends with a line "[truncated]" and ignores
/// further appends. Bytes other than printable ASCII and '\n' are stored as '?' (TAB as a space),
/// so whatever a command prints, the technician's terminal only ever receives plain text.
class Reply {
public:
    static constexpr std::size_t kCapacity = 4096;  ///< bytes of text(), marker included
    static constexpr std::string_view kTruncatedMarker = "[truncated]";

    void printf(const char* format, ...) noexcept __attribute__((format(printf, 2, 3)));
    void append(std::string_view text) noexcept;
    /// Appends the text and a newline.
    void line(std::string_view text) noexcept;
    void clear() noexcept;

    std::string_view text() const noexcept { return {buffer_.data(), size_}; }
    bool empty() const noexcept { return size_ == 0; }
    bool truncated() const noexcept { return truncated_; }

private:
    /// Room for the content, keeping space for "\n[truncated]\n".
    static constexpr std::size_t kContentCapacity = kCapacity - kTruncatedMarker.size() - 2;

    void commit(std::size_t length) noexcept;
    void truncate() noexcept;

    std::array<char, kCapacity + 1> buffer_{};  // + 1 for vsnprintf's terminating NUL
    std::size_t size_ = 0;
    bool truncated_ = false;
};

struct ShellOptions {
    std::size_t maxLineLength = 256;  ///< longer lines are rejected with one error line
    std::size_t readBudget = 4096;    ///< bytes read per poll(), so a flood cannot stall a frame
    bool prompt = false;              ///< write "> " when ready for a command (terminals)
    bool crlf = false;                ///< end reply lines with CR LF (raw serial terminals)
};

/// The shell: a registry of commands built at start-up, then fed lines from a Console each frame.
///
/// Commands are registered with add() before the frame loop; a handler is called with the words
/// of the line and a Reply to fill, and must not throw (an exception is caught and reported as an
/// error line, but handlers are expected to report failures as "error: ..." reply lines). Invoking
/// a command does not allocate; execute() and poll() never allocate and never throw.
///
/// Built in: `help` lists the commands (usage and one-line help, aligned), `help CMD` describes
/// one. Every problem is answered with exactly one line starting with "error: ".
///
/// Not re-entrant: a handler must not call execute() or poll() of the same shell.
class CommandShell {
public:
    using Handler = std::function<void(const Args& args, Reply& reply)>;

    struct PollResult {
        std::size_t bytesRead = 0;  ///< at most ShellOptions::readBudget
        std::size_t events = 0;     ///< lines run and errors reported
        bool closed = false;        ///< the console reported end of input
    };

    /// Throws std::runtime_error when an option is out of range.
    explicit CommandShell(ShellOptions options = {});
    /// Default options with this maximum line length.
    explicit CommandShell(std::size_t maxLineLength)
        : CommandShell(ShellOptions{.maxLineLength = maxLineLength})
    {
    }
    CommandShell(const CommandShell&) = delete;
    CommandShell& operator=(const CommandShell&) = delete;

    /// Registers a command (start-up only). `usage` is the usage line, e.g. "snapshot [PATH]"
    /// (empty means the bare name; one not starting with the name gets it prepended, so
    /// "[PATH]" works too); `help` is one line. Throws std::runtime_error for a name that is
    /// empty, duplicate, or not made of letters, digits, '-', '_' and '.', for usage or help text
    /// that is not one line of printable ASCII, or for an empty handler.
    void add(std::string name, std::string usage, std::string help, Handler handler);

    /// Tokenises one line, runs its command and writes the reply to `out`.
    void execute(std::string_view line, platform::Console& out) noexcept;
    /// Consoles the shell serves at once (standard input and a serial port), each with its own
    /// line assembly, so input typed on one never splices into a line from the other.
    static constexpr std::size_t kChannels = 2;

    /// Reads what is waiting on the console now (at most readBudget bytes; the rest waits for
    /// the next call), assembles lines and executes each, writing replies and errors back.
    /// `channel` (< kChannels) keeps this console's partial line apart from the others'.
    PollResult poll(platform::Console& console, std::size_t channel = 0) noexcept;
    /// Terminal style of one channel (channel 0 takes ShellOptions::prompt and crlf): a serial
    /// terminal wants a prompt and CR LF line ends, a pipe on standard input neither.
    void setChannelStyle(std::size_t channel, bool prompt, bool crlf) noexcept;
    /// Writes a message that was not asked for just now (a snapshot written, a card trained) to
    /// the console of `channel`, in its style: over the waiting prompt (a carriage return first),
    /// its lines ended as the channel's are, and the prompt again after it.
    void notify(platform::Console& console, std::size_t channel, std::string_view text) noexcept;

    const ShellOptions& options() const noexcept { return options_; }
    bool hasCommand(std::string_view name) const noexcept { return find(name) != nullptr; }

private:
    struct Command {
        std::string name;
        std::string synopsis;  ///< the usage line, starting with the name
        std::string help;
        Handler handler;
    };

    const Command* find(std::string_view name) const noexcept;
    void help(const Args& args, Reply& reply) const noexcept;
    void replyUnknown(std::string_view name) noexcept;
    void handle(const LineEvent& event, platform::Console& out) noexcept;
    void send(platform::Console& out) noexcept;
    void writePrompt(platform::Console& out) noexcept;
    /// `text` with its line ends as the current channel's.
    void writeLines(platform::Console& out, std::string_view text) noexcept;

    ShellOptions options_;
    std::vector<LineAssembler> assemblers_;  ///< one per channel
    std::vector<Command> commands_;
    std::size_t synopsisWidth_ = 0;
    std::unique_ptr<char[]> readBuffer_;
    Args args_;
    Reply reply_;
    std::array<bool, kChannels> promptShown_{};
    struct Style {
        bool prompt = false;
        bool crlf = false;
    };
    std::array<Style, kChannels> styles_{};
    std::size_t channel_ = 0;  ///< the channel being served by poll() (0 for execute())
};

}  // namespace firmware
