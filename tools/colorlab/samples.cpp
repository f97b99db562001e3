#include "samples.hpp"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

namespace colorlab {
namespace {

bool validName(const std::string& name)
{
    for (char c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') {
            return false;
        }
    }
    return !name.empty() && name != "." && name != "..";
}

bool parseInt(const std::string& text, int& value)
{
    try {
        std::size_t used = 0;
        const long v = std::stol(text, &used);
        if (used != text.size() || v < -1000000 || v > 1000000) {
            return false;
        }
        value = static_cast<int>(v);
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace

std::vector<Sample> readSampleFile(const std::string& path)
{
    std::ifstream in(path);
    if (!in) {
        throw SampleError(path + ": cannot read sample list: " + std::strerror(errno));
    }
    std::vector<Sample> samples;
    std::set<std::string> names;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        const std::string where = path + ":" + std::to_string(number);
        if (const auto hash = line.find('#'); hash != std::string::npos) {
            line.erase(hash);
        }
        std::istringstream fields(line);
        std::vector<std::string> words;
        for (std::string w; fields >> w;) {
            words.push_back(w);
        }
        if (words.empty()) {
            continue;
        }
        if (words.size() < 3 || words.size() > 4) {
            throw SampleError(where + ": expected `name x y [radius]`, got " +
                              std::to_string(words.size()) + " fields");
        }
        Sample s;
        s.name = words[0];
        s.origin = where;
        if (!validName(s.name)) {
            throw SampleError(where + ": sample name '" + s.name +
                              "' may only use letters, digits, '-', '_' and '.'");
        }
        if (!names.insert(s.name).second) {
            throw SampleError(where + ": sample name '" + s.name + "' is used twice");
        }
        if (!parseInt(words[1], s.x) || !parseInt(words[2], s.y)) {
            throw SampleError(where + ": sample '" + s.name + "': x and y must be integers");
        }
        if (words.size() == 4 &&
            (!parseInt(words[3], s.radius) || s.radius < 0 || s.radius > 100)) {
            throw SampleError(where + ": sample '" + s.name +
                              "': radius must be an integer 0..100");
        }
        samples.push_back(std::move(s));
    }
    if (in.bad()) {
        throw SampleError(path + ": cannot read sample list: " + std::strerror(errno));
    }
    if (samples.empty()) {
        throw SampleError(path + ": no samples (lines `name x y [radius]`)");
    }
    return samples;
}

void parseGrid(const std::string& spec, int& columns, int& rows)
{
    const auto x = spec.find_first_of("xX");
    if (x == std::string::npos || !parseInt(spec.substr(0, x), columns) ||
        !parseInt(spec.substr(x + 1), rows) || columns < 1 || rows < 1 || columns > 64 ||
        rows > 64) {
        throw SampleError("--grid " + spec + ": expected NxM with N and M in 1..64, e.g. 4x2");
    }
}

std::vector<Sample> gridSamples(int width, int height, int columns, int rows, int radius)
{
    std::vector<Sample> samples;
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < columns; ++c) {
            Sample s;
            char name[32];
            std::snprintf(name, sizeof name, "r%dc%d", r, c);
            s.name = name;
            s.x = (2 * c + 1) * width / (2 * columns);
            s.y = (2 * r + 1) * height / (2 * rows);
            s.radius = radius;
            s.origin = "--grid";
            samples.push_back(std::move(s));
        }
    }
    return samples;
}

void checkSamples(const std::vector<Sample>& samples, int width, int height)
{
    if (samples.empty()) {
        throw SampleError("no samples to measure");
    }
    const std::string frame = std::to_string(width) + "x" + std::to_string(height) + " frame";
    for (const Sample& s : samples) {
        const std::string at =
            "sample '" + s.name + "' at (" + std::to_string(s.x) + ", " + std::to_string(s.y) + ")";
        if (s.x < 0 || s.y < 0 || s.x >= width || s.y >= height) {
            throw SampleError(s.origin + ": " + at + " is outside the " + frame);
        }
        if (s.x - s.radius < 0 || s.y - s.radius < 0 || s.x + s.radius >= width ||
            s.y + s.radius >= height) {
            throw SampleError(s.origin + ": " + at + " with radius " + std::to_string(s.radius) +
                              " does not fit in the " + frame);
        }
    }
}

}  // namespace colorlab
