#pragma once
// The text files of model building (.wfm, .asf, .pts) as a source of data lines: blank lines and
// `#` comments skipped (the first comment before a data line remembered: the .wfm names its next
// unit there), each data line split into whitespace-separated fields, every problem one line
// "NAME:LINE: what" thrown as `Error`.

#include <istream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace aam {

template <typename Error>
class FieldLines {
public:
    FieldLines(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

    /// The next data line split into fields, or nothing at the end of the file.
    std::optional<std::vector<std::string>> next()
    {
        std::string line;
        comment_.clear();
        bool sawComment = false;
        while (std::getline(in_, line)) {
            ++number_;
            const auto start = line.find_first_not_of(" \t\r");
            if (start == std::string::npos)
                continue;
            if (line[start] == '#') {
                if (!sawComment)
                    comment_ = trimmed(line.substr(start + 1));
                sawComment = true;
                continue;
            }
            std::istringstream fields(line);
            std::vector<std::string> out;
            for (std::string f; fields >> f;)
                out.push_back(f);
            return out;
        }
        return std::nullopt;
    }

    /// The next data line, which must exist: `what` says what was expected.
    std::vector<std::string> expect(const std::string& what)
    {
        auto fields = next();
        if (!fields)
            fail("file ends where " + what + " was expected");
        return *fields;
    }

    [[noreturn]] void fail(const std::string& what) const
    {
        throw Error(name_ + ":" + std::to_string(number_) + ": " + what);
    }

    /// The first comment before the last data line ("" when there was none).
    const std::string& comment() const noexcept { return comment_; }

private:
    static std::string trimmed(const std::string& s)
    {
        const auto a = s.find_first_not_of(" \t\r");
        const auto b = s.find_last_not_of(" \t\r");
        return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
    }

    std::istream& in_;
    std::string name_;
    int number_ = 0;
    std::string comment_;
};

/// Fields joined by single spaces, to quote a line back in a message.
inline std::string joinedFields(const std::vector<std::string>& fields)
{
    std::string s;
    for (const auto& f : fields)
        s += (s.empty() ? "" : " ") + f;
    return s;
}

}  // namespace aam
