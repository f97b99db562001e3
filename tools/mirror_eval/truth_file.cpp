#include "truth_file.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace mirror_eval {

namespace {

std::string trim(const std::string& s)
{
    std::size_t a = 0, b = s.size();
    while (a < b && std::isspace(static_cast<unsigned char>(s[a])))
        ++a;
    while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1])))
        --b;
    return s.substr(a, b - a);
}

std::vector<std::string> splitFields(const std::string& line)
{
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(trim(line.substr(start, comma - start)));
        if (comma == std::string::npos)
            return fields;
        start = comma + 1;
    }
}

}  // namespace

std::vector<TruthRow> parseTruth(std::istream& in, const std::string& name)
{
    static const char* const kFieldNames[8] = {"x0", "y0", "x1", "y1", "x2", "y2", "x3", "y3"};
    std::vector<TruthRow> rows;
    std::string line;
    int lineNo = 0;
    bool seenContent = false;
    while (std::getline(in, line)) {
        ++lineNo;
        const std::string text = trim(line);
        if (text.empty() || text[0] == '#')
            continue;
        auto fail = [&](const std::string& what) {
            throw std::runtime_error(name + ":" + std::to_string(lineNo) + ": " + what);
        };
        if (!seenContent) {
            seenContent = true;
            if (text.size() >= 5 && text.compare(0, 5, "frame") == 0)
                continue;  // the header
        }
        const std::vector<std::string> f = splitFields(text);
        if (f.size() != 9)
            fail("expected 9 comma-separated fields frame,x0,y0,x1,y1,x2,y2,x3,y3, got " +
                 std::to_string(f.size()));
        TruthRow row;
        char* end = nullptr;
        errno = 0;
        const long frame = std::strtol(f[0].c_str(), &end, 10);
        if (f[0].empty() || *end != '\0' || errno != 0 || frame < 0)
            fail("frame number '" + f[0] + "' is not a whole number >= 0");
        if (frame != static_cast<long>(rows.size()))
            fail("frame " + f[0] + " out of order (expected " + std::to_string(rows.size()) +
                 ": one row per frame, from 0)");
        row.frame = static_cast<int>(frame);
        int empty = 0;
        for (int k = 1; k < 9; ++k)
            empty += f[k].empty();
        if (empty == 8) {
            row.hasCard = false;
        } else if (empty > 0) {
            fail(
                "some corner fields empty: give all 8 numbers, or leave all 8 empty for a frame "
                "without a card");
        } else {
            row.hasCard = true;
            for (int k = 0; k < 8; ++k) {
                errno = 0;
                const double v = std::strtod(f[k + 1].c_str(), &end);
                if (*end != '\0' || errno != 0 || !std::isfinite(v))
                    fail(std::string(kFieldNames[k]) + " '" + f[k + 1] + "' is not a number");
                float& dst = (k % 2 == 0) ? row.quad[k / 2].x : row.quad[k / 2].y;
                dst = static_cast<float>(v);
            }
        }
        rows.push_back(row);
    }
    if (in.bad())
        throw std::runtime_error(name + ": read error");
    if (rows.empty())
        throw std::runtime_error(name + ": no truth rows (expected frame,x0,y0,...,x3,y3 lines)");
    return rows;
}

std::vector<TruthRow> loadTruth(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error("truth " + path + ": cannot open (missing or unreadable)");
    return parseTruth(in, path);
}

}  // namespace mirror_eval
