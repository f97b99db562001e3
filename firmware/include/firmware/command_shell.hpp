#pragma once
// CommandShell: the diagnostics command line a field technician uses over a Console.

#include "firmware/line_assembler.hpp"
#include "platform/console.hpp"

#include <array>
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace firmware {

/// The words of one command line, split on spaces and tabs; args[0] is the command name.
/// The views point into the line and are valid only while the command runs.
///
/// The one argument parser of every command: the shell checks the number of arguments against the
/// command's usage line before the handler runs, and a handler reads its words with word(),
/// number() and choice(), answering a word it cannot use with Reply::usageError().
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

    /// The i-th word as a whole number in lo..hi (decimal, optional '-'); false when it is not.
    bool number(std::size_t i, long lo, long hi, long& value) const noexcept;
    /// For quoting a word in an error as "%.*s": its length, at most 32 characters.
    static int shown(std::string_view word) noexcept
    {
        return static_cast<int>(word.size() < 32 ? word.size() : 32);
    }
    /// The position of the i-th word among `words`, or -1.
    int choice(std::size_t i, std::initializer_list<std::string_view> words) const noexcept;

private:
    std::array<std::string_view, kMaxTokens> tokens_{};
    std::size_t count_ = 0;
};

/// How many arguments (words after the name) a command takes, as its usage line says:
/// "log [LEVEL] [N]" takes 0..2, "overlay [next|NAME|mode global|per_face]" 0..2 (an optional
/// group counts as its longest alternative), "echo [WORD...]" any number.
struct Arity {
    std::size_t min = 0;
    std::size_t max = 0;
    static Arity fromUsage(std::string_view usage) noexcept;
};

/// A command's reply, appended to printf-style into a buffer sized once at construction, never
/// allocating afterwards. The shell keeps one per console and sends it as fast as that console
/// takes it (Console::writable()), so a reply is never cut: the buffer holds the longest reply
/// any command gives (ShellOptions::replyCapacity). Should one still not fit, it ends with a line
/// "[truncated]" and ignores the rest of that command's output.
///
/// Bytes other than printable ASCII and '\n' are stored as '?' (TAB as a space), so whatever a
/// command prints, the technician's terminal only ever receives plain text.
class Reply {
public:
    static constexpr std::size_t kDefaultCapacity = 256 * 1024;
    static constexpr std::string_view kTruncatedMarker = "[truncated]";

    explicit Reply(std::size_t capacity = kDefaultCapacity);

    void printf(const char* format, ...) noexcept __attribute__((format(printf, 2, 3)));
    void append(std::string_view text) noexcept;
    /// Appends the text and a newline.
    void line(std::string_view text) noexcept;
    /// One error line naming the problem and the command's usage:
    /// "error: N must be 1..200, got '0'; usage: log [LEVEL] [N]".
    void usageError(const char* format, ...) noexcept __attribute__((format(printf, 2, 3)));
    void clear() noexcept;

    /// The text not yet sent.
    std::string_view text() const noexcept { return {buffer_.get() + sent_, size_ - sent_}; }
    bool empty() const noexcept { return size_ == sent_; }
    /// Whether the current command's output was cut (see the class comment).
    bool truncated() const noexcept { return truncated_; }
    std::size_t capacity() const noexcept { return capacity_; }

private:
    friend class CommandShell;

    /// A new command's output begins (after whatever is still unsent): its usage for errors.
    void begin(std::string_view usage) noexcept;
    /// Drops the current command's output (a handler that threw).
    void dropCommand() noexcept;
    /// Text the shell itself writes (the prompt, a carriage return): not sanitised.
    void appendRaw(std::string_view text) noexcept;
    /// `n` bytes of text() were sent.
    void consume(std::size_t n) noexcept;
    /// Room for `n` more bytes, moving the unsent text to the front if that makes it.
    std::size_t room() noexcept;
    void commit(std::size_t length) noexcept;
    void truncate() noexcept;

    /// Room beyond the capacity: vsnprintf's NUL, the marker, the shell's prompt and line ends.
    static constexpr std::size_t kSlack = kTruncatedMarker.size() + 16;

    std::unique_ptr<char[]> buffer_;
    std::size_t capacity_;  ///< bytes of text a command may write
    std::size_t sent_ = 0;
    std::size_t size_ = 0;
    std::size_t commandStart_ = 0;
    std::string_view usage_;
    bool truncated_ = false;
};

struct ShellOptions {
    std::size_t maxLineLength = 256;  ///< longer lines are rejected with one error line
    std::size_t readBudget = 4096;    ///< bytes read per poll(), so a flood cannot stall a frame
    std::size_t writeBudget = 64 * 1024;                  ///< reply bytes sent per poll() at most
    std::size_t replyCapacity = Reply::kDefaultCapacity;  ///< the longest reply, per console
    bool prompt = false;  ///< write "> " when ready for a command (terminals)
    bool crlf = false;    ///< end reply lines with CR LF (raw serial terminals)
};

/// The shell: a registry of commands built at start-up, then fed lines from a Console each frame.
///
/// Commands are registered with add() before the frame loop; a handler is called with the words
/// of the line and a Reply to fill, and must not throw (an exception is caught and reported as an
/// error line, but handlers are expected to report failures as "error: ..." reply lines). Invoking
/// a command does not allocate; execute() and poll() never allocate and never throw.
///
/// The shell checks each command's number of arguments against its usage line (Arity) and
/// answers a wrong count with "error: ...; usage: ..." without running the handler.
///
/// Replies are streamed: each console's pending reply goes out as fast as that console takes it
/// (at most writeBudget bytes a poll), and the console's next command is read only once its
/// reply is out, so a long reply (`config`, `log 200`) arrives whole even on a 9600 baud line.
///
/// Built in: `help` lists the commands (usage and one-line help, within 80 columns), `help CMD`
/// describes one. Every problem is answered with exactly one line starting with "error: ".
///
/// Not re-entrant: a handler must not call execute() or poll() of the same shell.
class CommandShell {
public:
    using Handler = std::function<void(const Args& args, Reply& reply)>;

    /// The widest line `help` prints (a serial terminal's 80 columns).
    static constexpr std::size_t kHelpColumns = 80;

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
    /// "[PATH]" works too); it also says how many arguments the command takes (Arity).
    /// `help` is one line. Throws std::runtime_error for a name that is empty, duplicate, or not
    /// made of letters, digits, '-', '_' and '.', for usage or help text that is not one line of
    /// printable ASCII, or for an empty handler.
    void add(std::string name, std::string usage, std::string help, Handler handler);

    /// Tokenises one line, runs its command and writes the reply to `out` (channel 0), as far as
    /// `out` takes it now; the rest follows on the next poll() of channel 0.
    void execute(std::string_view line, platform::Console& out) noexcept;
    /// Consoles the shell serves at once (standard input and a serial port), each with its own
    /// line assembly, so input typed on one never splices into a line from the other.
    static constexpr std::size_t kChannels = 2;

    /// Sends what is left of the console's last reply, then, once it is all out, reads what is
    /// waiting on the console now (at most readBudget bytes; the rest waits for the next call),
    /// assembles lines and executes each, writing replies and errors back.
    /// `channel` (< kChannels) keeps this console's partial line and reply apart from the others'.
    PollResult poll(platform::Console& console, std::size_t channel = 0) noexcept;
    /// Terminal style of one channel (channel 0 takes ShellOptions::prompt and crlf): a serial
    /// terminal wants a prompt and CR LF line ends, a pipe on standard input neither.
    void setChannelStyle(std::size_t channel, bool prompt, bool crlf) noexcept;
    /// Writes a message that was not asked for just now (a snapshot written, a card trained) to
    /// the console of `channel`, in its style: over the waiting prompt (a carriage return first),
    /// its lines ended as the channel's are, and the prompt again after it. It follows a reply
    /// still being sent.
    void notify(platform::Console& console, std::size_t channel, std::string_view text) noexcept;
    /// Bytes of reply still to send on `channel`.
    std::size_t pendingOutput(std::size_t channel) const noexcept;

    const ShellOptions& options() const noexcept { return options_; }
    bool hasCommand(std::string_view name) const noexcept { return find(name) != nullptr; }

private:
    struct Command {
        std::string name;
        std::string synopsis;  ///< the usage line, starting with the name
        std::string help;
        Arity arity;
        Handler handler;
    };

    const Command* find(std::string_view name) const noexcept;
    void help(const Args& args, Reply& reply) const noexcept;
    void listCommands(Reply& reply) const noexcept;
    void replyUnknown(std::string_view name) noexcept;
    void run(std::string_view line) noexcept;
    void handle(const LineEvent& event, platform::Console& out) noexcept;
    /// Ends the reply's last line, adds the prompt and sends what `out` takes now.
    void finishReply(platform::Console& out) noexcept;
    /// Sends as much of the channel's reply as `out` takes now (within the write budget).
    void drain(platform::Console& out) noexcept;
    Reply& reply() noexcept { return replies_[channel_]; }

    ShellOptions options_;
    std::vector<LineAssembler> assemblers_;  ///< one per channel
    std::vector<Command> commands_;
    std::unique_ptr<char[]> readBuffer_;
    Args args_;
    std::vector<Reply> replies_;  ///< one per channel: what is still to be sent there
    std::array<bool, kChannels> promptShown_{};
    std::array<bool, kChannels> closed_{};
    struct Style {
        bool prompt = false;
        bool crlf = false;
    };
    std::array<Style, kChannels> styles_{};
    std::size_t channel_ = 0;  ///< the channel being served by poll() (0 for execute())
};

}  // namespace firmware
