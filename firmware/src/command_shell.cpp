#include "firmware/command_shell.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <exception>
#include <stdexcept>

namespace firmware {

namespace {

bool isBlank(char c)
{
    return c == ' ' || c == '\t';
}
bool isPrintable(char c)
{
    return c >= 0x20 && c <= 0x7E;
}

bool isNameChar(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
           c == '_' || c == '.';
}

bool isOneLine(const std::string& text)
{
    return std::all_of(text.begin(), text.end(), isPrintable);
}

/// Longest command name quoted back in an error, so a flood of junk cannot produce huge replies.
constexpr std::size_t kMaxQuotedName = 32;

/// Quotes up to kMaxQuotedName characters of `text` for an error line: backslash and quote are
/// escaped, other bytes outside printable ASCII become \xNN, and "..." marks a cut.
void quoteName(std::string_view text, char* out, std::size_t capacity) noexcept
{
    std::size_t n = 0;
    auto put = [&](char c) {
        if (n + 1 < capacity)
            out[n++] = c;
    };
    const std::size_t shown = std::min(text.size(), kMaxQuotedName);
    for (std::size_t i = 0; i < shown; ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c == '\'' || c == '\\') {
            put('\\');
            put(static_cast<char>(c));
        } else if (isPrintable(static_cast<char>(c))) {
            put(static_cast<char>(c));
        } else {
            static constexpr char kHex[] = "0123456789abcdef";
            put('\\');
            put('x');
            put(kHex[c >> 4]);
            put(kHex[c & 0xF]);
        }
    }
    if (text.size() > shown) {
        put('.');
        put('.');
        put('.');
    }
    out[n] = '\0';
}

}  // namespace

// --- Args -------------------------------------------------------------------------------------

Args::Parse Args::parse(std::string_view line) noexcept
{
    count_ = 0;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && isBlank(line[i]))
            ++i;
        if (i == line.size())
            break;
        const std::size_t start = i;
        while (i < line.size() && !isBlank(line[i]))
            ++i;
        if (count_ == kMaxTokens)
            return Parse::TooMany;
        tokens_[count_++] = line.substr(start, i - start);
    }
    return count_ == 0 ? Parse::Empty : Parse::Ok;
}

// --- Reply ------------------------------------------------------------------------------------

void Reply::clear() noexcept
{
    size_ = 0;
    truncated_ = false;
}

void Reply::commit(std::size_t length) noexcept
{
    for (std::size_t i = size_; i < size_ + length; ++i) {
        char& c = buffer_[i];
        if (c == '\t')
            c = ' ';
        else if (c != '\n' && !isPrintable(c))
            c = '?';
    }
    size_ += length;
}

void Reply::truncate() noexcept
{
    truncated_ = true;
    if (size_ > 0 && buffer_[size_ - 1] != '\n')
        buffer_[size_++] = '\n';
    for (char c : kTruncatedMarker)
        buffer_[size_++] = c;
    buffer_[size_++] = '\n';
}

void Reply::printf(const char* format, ...) noexcept
{
    if (truncated_)
        return;
    const std::size_t room = kContentCapacity - size_;
    va_list args;
    va_start(args, format);
    const int needed = std::vsnprintf(buffer_.data() + size_, room + 1, format, args);
    va_end(args);
    if (needed < 0)
        return;  // an invalid conversion: nothing sensible to show
    commit(std::min(static_cast<std::size_t>(needed), room));
    if (static_cast<std::size_t>(needed) > room)
        truncate();
}

void Reply::append(std::string_view text) noexcept
{
    if (truncated_)
        return;
    const std::size_t room = kContentCapacity - size_;
    const std::size_t length = std::min(text.size(), room);
    std::copy_n(text.data(), length, buffer_.data() + size_);
    commit(length);
    if (text.size() > room)
        truncate();
}

void Reply::line(std::string_view text) noexcept
{
    append(text);
    append("\n");
}

// --- CommandShell -----------------------------------------------------------------------------

CommandShell::CommandShell(ShellOptions options) : options_(options)
{
    for (std::size_t i = 0; i < kChannels; ++i)
        assemblers_.emplace_back(options.maxLineLength);
    styles_[0] = {options.prompt, options.crlf};
    if (options.readBudget == 0)
        throw std::runtime_error("command shell: the read budget must be at least 1 byte");
    readBuffer_ = std::make_unique<char[]>(options.readBudget);
    add("help", "help [COMMAND]", "list the commands, or describe one",
        [this](const Args& args, Reply& reply) { help(args, reply); });
}

void CommandShell::add(std::string name, std::string usage, std::string help, Handler handler)
{
    if (name.empty() || !std::all_of(name.begin(), name.end(), isNameChar))
        throw std::runtime_error("command shell: invalid command name '" + name +
                                 "' (letters, digits, '-', '_' and '.' only)");
    if (find(name))
        throw std::runtime_error("command shell: command '" + name + "' registered twice");
    if (!isOneLine(usage) || !isOneLine(help))
        throw std::runtime_error("command shell: usage and help of '" + name +
                                 "' must be one line of printable ASCII");
    if (!handler)
        throw std::runtime_error("command shell: command '" + name + "' has no handler");
    const bool startsWithName = usage.compare(0, name.size(), name) == 0 &&
                                (usage.size() == name.size() || usage[name.size()] == ' ');
    std::string synopsis = usage.empty() ? name : startsWithName ? usage : name + " " + usage;
    synopsisWidth_ = std::max(synopsisWidth_, synopsis.size());
    commands_.push_back(
        {std::move(name), std::move(synopsis), std::move(help), std::move(handler)});
}

const CommandShell::Command* CommandShell::find(std::string_view name) const noexcept
{
    for (const Command& command : commands_)
        if (command.name == name)
            return &command;
    return nullptr;
}

void CommandShell::help(const Args& args, Reply& reply) const noexcept
{
    if (args.size() > 2) {
        reply.line("error: usage: help [COMMAND]");
        return;
    }
    if (args.size() == 2) {
        const Command* command = find(args[1]);
        if (!command) {
            char quoted[kMaxQuotedName * 4 + 4];
            quoteName(args[1], quoted, sizeof quoted);
            reply.printf("error: unknown command '%s' (try 'help')\n", quoted);
            return;
        }
        reply.printf("usage: %s\n  %s\n", command->synopsis.c_str(), command->help.c_str());
        return;
    }
    reply.line("commands:");
    const int width = static_cast<int>(synopsisWidth_);
    for (const Command& command : commands_)
        reply.printf("  %-*s  %s\n", width, command.synopsis.c_str(), command.help.c_str());
}

void CommandShell::replyUnknown(std::string_view name) noexcept
{
    char quoted[kMaxQuotedName * 4 + 4];
    quoteName(name, quoted, sizeof quoted);
    reply_.printf("error: unknown command '%s' (try 'help')\n", quoted);
}

void CommandShell::execute(std::string_view line, platform::Console& out) noexcept
{
    reply_.clear();
    switch (args_.parse(line)) {
        case Args::Parse::Empty:
            break;
        case Args::Parse::TooMany:
            reply_.printf("error: too many arguments (at most %zu words)\n", Args::kMaxTokens);
            break;
        case Args::Parse::Ok:
            if (const Command* command = find(args_[0])) {
                try {
                    command->handler(args_, reply_);
                } catch (const std::exception& e) {
                    reply_.clear();
                    reply_.printf("error: %s failed: %s\n", command->name.c_str(), e.what());
                } catch (...) {
                    reply_.clear();
                    reply_.printf("error: %s failed\n", command->name.c_str());
                }
            } else {
                replyUnknown(args_[0]);
            }
            break;
    }
    send(out);
}

void CommandShell::handle(const LineEvent& event, platform::Console& out) noexcept
{
    switch (event.kind) {
        case LineEventKind::Line:
            execute(event.text, out);
            return;
        case LineEventKind::TooLong:
            reply_.clear();
            reply_.printf("error: line too long (max %zu characters)\n", options_.maxLineLength);
            break;
        case LineEventKind::Binary:
            reply_.clear();
            reply_.line("error: binary data ignored");
            break;
    }
    send(out);
}

void CommandShell::writeLines(platform::Console& out, std::string_view text) noexcept
{
    if (!styles_[channel_].crlf) {
        out.write(text);
        return;
    }
    for (std::size_t end; (end = text.find('\n')) != std::string_view::npos;) {
        out.write(text.substr(0, end));
        out.write("\r\n");
        text.remove_prefix(end + 1);
    }
    out.write(text);
}

void CommandShell::send(platform::Console& out) noexcept
{
    writeLines(out, reply_.text());
    // Every reply ends its last line, even when the command forgot to.
    if (!reply_.empty() && reply_.text().back() != '\n')
        out.write(styles_[channel_].crlf ? "\r\n" : "\n");
    writePrompt(out);
}

void CommandShell::notify(platform::Console& console, std::size_t channel,
                          std::string_view text) noexcept
{
    if (text.empty())
        return;
    channel_ = std::min(channel, kChannels - 1);
    const bool overPrompt = styles_[channel_].prompt && promptShown_[channel_];
    if (overPrompt)
        console.write("\r");  // the message takes the prompt's place at the start of the line
    writeLines(console, text);
    if (text.back() != '\n')
        console.write(styles_[channel_].crlf ? "\r\n" : "\n");
    if (overPrompt)
        writePrompt(console);
    channel_ = 0;
}

void CommandShell::writePrompt(platform::Console& out) noexcept
{
    if (styles_[channel_].prompt)
        out.write("> ");
}

CommandShell::PollResult CommandShell::poll(platform::Console& console,
                                            std::size_t channel) noexcept
{
    PollResult result;
    channel = std::min(channel, kChannels - 1);
    channel_ = channel;
    LineAssembler& assembler = assemblers_[channel];
    if (!promptShown_[channel]) {
        writePrompt(console);
        promptShown_[channel] = true;
    }
    auto onEvent = [&](const LineEvent& event) noexcept {
        handle(event, console);
        ++result.events;
    };
    while (result.bytesRead < options_.readBudget) {
        const std::size_t room = options_.readBudget - result.bytesRead;
        const long n = console.read(readBuffer_.get(), room);
        if (n < 0) {
            result.closed = true;
            assembler.finish(onEvent);
            break;
        }
        if (n == 0)
            break;
        // Trust no more than was asked for, whatever the console claims.
        const std::size_t got = std::min(static_cast<std::size_t>(n), room);
        result.bytesRead += got;
        assembler.feed(readBuffer_.get(), got, onEvent);
    }
    channel_ = 0;
    return result;
}

void CommandShell::setChannelStyle(std::size_t channel, bool prompt, bool crlf) noexcept
{
    if (channel < kChannels)
        styles_[channel] = {prompt, crlf};
}

}  // namespace firmware
