#include "firmware/command_shell.hpp"

#include <algorithm>
#include <charconv>
#include <cstdarg>
#include <cstdio>
#include <cstring>
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

bool Args::number(std::size_t i, long lo, long hi, long& value) const noexcept
{
    const std::string_view word = (*this)[i];
    long v = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
    if (word.empty() || ec != std::errc() || end != word.data() + word.size() || v < lo || v > hi)
        return false;
    value = v;
    return true;
}

int Args::choice(std::size_t i, std::initializer_list<std::string_view> words) const noexcept
{
    int index = 0;
    for (const std::string_view word : words) {
        if (i < count_ && tokens_[i] == word)
            return index;
        ++index;
    }
    return -1;
}

// --- Arity ------------------------------------------------------------------------------------

Arity Arity::fromUsage(std::string_view usage) noexcept
{
    // Words after the name: a bare word is required; "[...]" is optional and takes as many words
    // as its longest '|' alternative; "..." after a word or group means any number.
    Arity arity;
    std::size_t i = usage.find(' ');
    if (i == std::string_view::npos)
        return arity;
    auto skipBlanks = [&] {
        while (i < usage.size() && usage[i] == ' ')
            ++i;
    };
    skipBlanks();
    while (i < usage.size()) {
        std::size_t end = i;
        std::size_t words = 1;
        const bool optional = usage[i] == '[';
        if (optional) {
            int depth = 0;
            std::size_t alternative = 1;
            words = 1;
            for (; end < usage.size(); ++end) {
                const char c = usage[end];
                depth += c == '[' ? 1 : c == ']' ? -1 : 0;
                if (depth == 1 && c == '|')
                    alternative = 1;
                else if (depth >= 1 && c == ' ')
                    words = std::max(words, ++alternative);
                if (depth == 0) {
                    ++end;
                    break;
                }
            }
        } else {
            while (end < usage.size() && usage[end] != ' ')
                ++end;
        }
        const std::string_view token = usage.substr(i, end - i);
        const bool repeated = token.ends_with("...") || token.ends_with("...]");
        arity.min += optional ? 0 : 1;
        arity.max = repeated ? Args::kMaxTokens - 1 : arity.max + words;
        i = end;
        skipBlanks();
    }
    arity.max = std::min(arity.max, Args::kMaxTokens - 1);
    return arity;
}

// --- Reply ------------------------------------------------------------------------------------

Reply::Reply(std::size_t capacity)
    : buffer_(std::make_unique<char[]>(capacity + kSlack)), capacity_(capacity)
{
}

void Reply::clear() noexcept
{
    sent_ = size_ = commandStart_ = 0;
    truncated_ = false;
}

void Reply::begin(std::string_view usage) noexcept
{
    if (sent_ == size_)
        sent_ = size_ = 0;
    commandStart_ = size_;
    usage_ = usage;
    truncated_ = false;
}

void Reply::dropCommand() noexcept
{
    size_ = std::max(commandStart_, sent_);
    truncated_ = false;
}

void Reply::consume(std::size_t n) noexcept
{
    sent_ = std::min(sent_ + n, size_);
    if (sent_ == size_)
        sent_ = size_ = commandStart_ = 0;
}

std::size_t Reply::room() noexcept
{
    if (sent_ > 0) {
        // Sent text is gone: move what is still to be sent to the front.
        std::memmove(buffer_.get(), buffer_.get() + sent_, size_ - sent_);
        size_ -= sent_;
        commandStart_ = commandStart_ > sent_ ? commandStart_ - sent_ : 0;
        sent_ = 0;
    }
    return size_ < capacity_ ? capacity_ - size_ : 0;
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
    if (size_ > sent_ && buffer_[size_ - 1] != '\n')
        buffer_[size_++] = '\n';
    for (char c : kTruncatedMarker)
        buffer_[size_++] = c;
    buffer_[size_++] = '\n';
}

void Reply::printf(const char* format, ...) noexcept
{
    if (truncated_)
        return;
    const std::size_t free = room();
    va_list args;
    va_start(args, format);
    const int needed = std::vsnprintf(buffer_.get() + size_, free + 1, format, args);
    va_end(args);
    if (needed < 0)
        return;  // an invalid conversion: nothing sensible to show
    commit(std::min(static_cast<std::size_t>(needed), free));
    if (static_cast<std::size_t>(needed) > free)
        truncate();
}

void Reply::usageError(const char* format, ...) noexcept
{
    if (truncated_)
        return;
    char problem[256];
    va_list args;
    va_start(args, format);
    std::vsnprintf(problem, sizeof problem, format, args);
    va_end(args);
    printf("error: %s; usage: %.*s\n", problem, static_cast<int>(usage_.size()), usage_.data());
}

void Reply::append(std::string_view text) noexcept
{
    if (truncated_)
        return;
    const std::size_t free = room();
    const std::size_t length = std::min(text.size(), free);
    std::copy_n(text.data(), length, buffer_.get() + size_);
    commit(length);
    if (text.size() > free)
        truncate();
}

void Reply::appendRaw(std::string_view text) noexcept
{
    room();
    const std::size_t length = std::min(text.size(), capacity_ + kSlack - size_);
    std::copy_n(text.data(), length, buffer_.get() + size_);
    size_ += length;
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
    if (options.writeBudget < 2 || options.replyCapacity < 256)
        throw std::runtime_error(
            "command shell: the write budget must be at least 2 bytes and the reply capacity at "
            "least 256");
    readBuffer_ = std::make_unique<char[]>(options.readBudget);
    for (std::size_t i = 0; i < kChannels; ++i)
        replies_.emplace_back(options.replyCapacity);
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
    const Arity arity = Arity::fromUsage(synopsis);
    commands_.push_back(
        {std::move(name), std::move(synopsis), std::move(help), arity, std::move(handler)});
}

const CommandShell::Command* CommandShell::find(std::string_view name) const noexcept
{
    for (const Command& command : commands_)
        if (command.name == name)
            return &command;
    return nullptr;
}

namespace {

/// Appends `text` word-wrapped to kHelpColumns, the first line after `firstIndent` columns
/// already used, continuation lines indented by `indent`.
void wrapped(Reply& reply, std::string_view text, std::size_t firstIndent, std::size_t indent,
             std::size_t columns) noexcept
{
    std::size_t column = firstIndent;
    bool first = true;
    while (!text.empty()) {
        const std::size_t space = text.find(' ');
        const std::string_view word = text.substr(0, space);
        text = space == std::string_view::npos ? std::string_view() : text.substr(space + 1);
        if (word.empty())
            continue;
        if (!first && column + 1 + word.size() > columns) {
            reply.printf("\n%*s", static_cast<int>(indent), "");
            column = indent;
            first = true;
        }
        if (!first) {
            reply.append(" ");
            ++column;
        }
        reply.append(word);
        column += word.size();
        first = false;
    }
    reply.append("\n");
}

/// Synopses up to this width share their line with the help text in `help`'s list.
constexpr std::size_t kSynopsisColumn = 22;

}  // namespace

void CommandShell::listCommands(Reply& reply) const noexcept
{
    reply.line("commands:");
    std::size_t width = 0;
    for (const Command& command : commands_)
        if (command.synopsis.size() <= kSynopsisColumn)
            width = std::max(width, command.synopsis.size());
    const std::size_t helpIndent = 2 + width + 2;
    for (const Command& command : commands_) {
        if (command.synopsis.size() <= width) {
            reply.printf("  %-*s  ", static_cast<int>(width), command.synopsis.c_str());
        } else {
            reply.printf("  %s\n%*s", command.synopsis.c_str(), static_cast<int>(helpIndent), "");
        }
        wrapped(reply, command.help, helpIndent, helpIndent, kHelpColumns);
    }
}

void CommandShell::help(const Args& args, Reply& reply) const noexcept
{
    if (args.size() == 2) {
        const Command* command = find(args[1]);
        if (!command) {
            char quoted[kMaxQuotedName * 4 + 4];
            quoteName(args[1], quoted, sizeof quoted);
            reply.printf("error: unknown command '%s' (try 'help')\n", quoted);
            return;
        }
        reply.printf("usage: %s\n  ", command->synopsis.c_str());
        wrapped(reply, command->help, 2, 2, kHelpColumns);
        return;
    }
    listCommands(reply);
}

void CommandShell::replyUnknown(std::string_view name) noexcept
{
    char quoted[kMaxQuotedName * 4 + 4];
    quoteName(name, quoted, sizeof quoted);
    reply().printf("error: unknown command '%s' (try 'help')\n", quoted);
}

/// Runs one line's command into the channel's reply.
void CommandShell::run(std::string_view line) noexcept
{
    Reply& out = reply();
    out.begin("");
    switch (args_.parse(line)) {
        case Args::Parse::Empty:
            return;
        case Args::Parse::TooMany:
            out.printf("error: too many arguments (at most %zu words)\n", Args::kMaxTokens);
            return;
        case Args::Parse::Ok:
            break;
    }
    const Command* command = find(args_[0]);
    if (!command) {
        replyUnknown(args_[0]);
        return;
    }
    out.begin(command->synopsis);
    const std::size_t given = args_.size() - 1;
    if (given < command->arity.min) {
        out.usageError("missing argument");
        return;
    }
    if (given > command->arity.max) {
        char quoted[kMaxQuotedName * 4 + 4];
        quoteName(args_[command->arity.max + 1], quoted, sizeof quoted);
        out.usageError("unexpected argument '%s'", quoted);
        return;
    }
    try {
        command->handler(args_, out);
    } catch (const std::exception& e) {
        out.dropCommand();
        out.printf("error: %s failed: %s\n", command->name.c_str(), e.what());
    } catch (...) {
        out.dropCommand();
        out.printf("error: %s failed\n", command->name.c_str());
    }
}

void CommandShell::execute(std::string_view line, platform::Console& out) noexcept
{
    run(line);
    finishReply(out);
}

void CommandShell::handle(const LineEvent& event, platform::Console& out) noexcept
{
    switch (event.kind) {
        case LineEventKind::Line:
            execute(event.text, out);
            return;
        case LineEventKind::TooLong:
            reply().begin("");
            reply().printf("error: line too long (max %zu characters)\n", options_.maxLineLength);
            break;
        case LineEventKind::Binary:
            reply().begin("");
            reply().line("error: binary data ignored");
            break;
    }
    finishReply(out);
}

void CommandShell::drain(platform::Console& out) noexcept
{
    Reply& pending = reply();
    const bool crlf = styles_[channel_].crlf;
    std::size_t budget = options_.writeBudget;
    while (!pending.empty() && budget > 0) {
        // CR LF doubles a text of newlines at most: send no more than half of what fits.
        const std::size_t fits = std::min(out.writable(), budget);
        const std::size_t piece = std::min(pending.text().size(), crlf ? fits / 2 : fits);
        if (piece == 0)
            return;
        std::string_view text = pending.text().substr(0, piece);
        pending.consume(piece);
        budget -= piece;
        if (!crlf) {
            out.write(text);
            continue;
        }
        for (std::size_t end; (end = text.find('\n')) != std::string_view::npos;) {
            out.write(text.substr(0, end));
            out.write("\r\n");
            text.remove_prefix(end + 1);
        }
        out.write(text);
    }
}

void CommandShell::finishReply(platform::Console& out) noexcept
{
    Reply& pending = reply();
    // Every reply ends its last line, even when the command forgot to.
    if (!pending.empty() && pending.text().back() != '\n' && pending.size_ > pending.commandStart_)
        pending.appendRaw("\n");
    if (styles_[channel_].prompt)
        pending.appendRaw("> ");
    drain(out);
}

void CommandShell::notify(platform::Console& console, std::size_t channel,
                          std::string_view text) noexcept
{
    if (text.empty())
        return;
    channel_ = std::min(channel, kChannels - 1);
    Reply& pending = reply();
    const bool overPrompt = styles_[channel_].prompt && promptShown_[channel_];
    if (overPrompt)
        pending.appendRaw("\r");  // the message takes the prompt's place at the start of the line
    pending.begin("");
    pending.append(text);
    if (text.back() != '\n')
        pending.appendRaw("\n");
    if (overPrompt)
        pending.appendRaw("> ");
    drain(console);
    channel_ = 0;
}

std::size_t CommandShell::pendingOutput(std::size_t channel) const noexcept
{
    return channel < kChannels ? replies_[channel].text().size() : 0;
}

CommandShell::PollResult CommandShell::poll(platform::Console& console,
                                            std::size_t channel) noexcept
{
    PollResult result;
    channel = std::min(channel, kChannels - 1);
    channel_ = channel;
    LineAssembler& assembler = assemblers_[channel];
    if (!promptShown_[channel]) {
        if (styles_[channel].prompt)
            reply().appendRaw("> ");
        promptShown_[channel] = true;
    }
    drain(console);
    auto onEvent = [&](const LineEvent& event) noexcept {
        handle(event, console);
        ++result.events;
    };
    // The next command waits until the last reply is out: a console is a conversation.
    while (!closed_[channel] && reply().empty() && result.bytesRead < options_.readBudget) {
        const std::size_t room = options_.readBudget - result.bytesRead;
        const long n = console.read(readBuffer_.get(), room);
        if (n < 0) {
            closed_[channel] = true;
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
    // A closed input is reported once its last reply is out.
    result.closed = closed_[channel] && reply().empty();
    channel_ = 0;
    return result;
}

void CommandShell::setChannelStyle(std::size_t channel, bool prompt, bool crlf) noexcept
{
    if (channel < kChannels)
        styles_[channel] = {prompt, crlf};
}

}  // namespace firmware
