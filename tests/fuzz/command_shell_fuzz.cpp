// The diagnostics shell as a technician's terminal reaches it: the input is what arrives on the
// console (two channels: bytes before the first NUL on the serial port, the rest on stdin). The
// commands echo their words, print a reply longer than its buffer and throw, so the reply's
// truncation and the shell's error lines are reached; all it writes must be printable text.
#include "firmware/command_shell.hpp"
#include "fuzz_input.hpp"

#include <cstdlib>
#include <string_view>

namespace {

class ScriptedConsole final : public platform::Console {
public:
    explicit ScriptedConsole(std::string_view input) : input_(input) {}
    const char* description() const noexcept override { return "fuzz"; }
    long read(char* buffer, std::size_t capacity) noexcept override
    {
        if (input_.empty())
            return -1;
        const std::size_t n = std::min(capacity, input_.size());
        input_.copy(buffer, n);
        input_.remove_prefix(n);
        return static_cast<long>(n);
    }
    void write(std::string_view text) noexcept override
    {
        for (const char c : text)
            if ((c < 0x20 || c > 0x7E) && c != '\n' && c != '\r')
                std::abort();  // only plain text reaches the terminal
    }

private:
    std::string_view input_;
};

void addCommands(firmware::CommandShell& s)
{
    s.add("echo", "echo [WORD...]", "print the words back",
          [](const firmware::Args& args, firmware::Reply& reply) {
              for (const std::string_view word : args)
                  reply.printf("%.*s ", static_cast<int>(word.size()), word.data());
              reply.line("");
          });
    s.add("flood", "[WORD]", "print a reply longer than the buffer",
          [](const firmware::Args& args, firmware::Reply& reply) {
              const std::string word(args[1]);
              for (int i = 0; i < 300; ++i)
                  reply.printf("line %d of %s\n", i, word.c_str());
          });
    s.add("fail", "", "throws", [](const firmware::Args&, firmware::Reply&) {
        throw std::runtime_error("a handler that throws");
    });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string_view input = fuzz::text(data, size);
    const std::size_t split = std::min(input.find('\0'), input.size());
    ScriptedConsole serial(input.substr(0, split));
    ScriptedConsole stdinConsole(input.substr(std::min(split + 1, input.size())));
    // A shell per input, so each input is replayed exactly (no partial line left from the last).
    firmware::CommandShell s(firmware::ShellOptions{
        .maxLineLength = 64, .readBudget = 97, .prompt = true, .crlf = false});
    addCommands(s);
    s.setChannelStyle(1, true, true);
    for (bool open = true; open;) {
        open = false;
        open |= !s.poll(serial, 1).closed;
        open |= !s.poll(stdinConsole, 0).closed;
    }
    s.notify(stdinConsole, 0, "a message\nof two lines");
    return 0;
}
