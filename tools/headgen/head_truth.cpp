// The headgen truth file (head_truth.hpp): key-value lines, every number written with enough
// digits to read back what was rendered to a thousandth of a pixel or degree.
#include "head_truth.hpp"

#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace headgen {

void writeHeadTruth(std::ostream& out, const HeadTruth& t)
{
    out << "# headgen truth: tools/headgen/README.md\n" << std::fixed << std::setprecision(4);
    out << "source " << t.source << "\n";
    out << "pose " << t.pose.yawDeg << ' ' << t.pose.pitchDeg << ' ' << t.pose.rollDeg << ' '
        << t.pose.scale << ' ' << t.pose.translation.x() << ' ' << t.pose.translation.y() << "\n";
    out << "animation";
    for (float v : t.pose.animation)
        out << ' ' << v;
    out << "\nbox " << t.box[0] << ' ' << t.box[1] << ' ' << t.box[2] << ' ' << t.box[3] << "\n";
    out << "hand " << (t.hand.present ? 1 : 0) << ' ' << t.hand.palm.x() << ' ' << t.hand.palm.y()
        << ' ' << t.hand.width << ' ' << t.hand.angleDeg << "\n";
    for (std::size_t i = 0; i < t.vertices.size(); ++i) {
        const TruthVertex& v = t.vertices[i];
        out << "vertex " << i << ' ' << v.candide << ' ' << v.image.x() << ' ' << v.image.y() << ' '
            << (v.seen ? 1 : 0) << "\n";
    }
}

namespace {

[[noreturn]] void fail(const std::string& name, int line, const std::string& what)
{
    throw std::runtime_error(name + ":" + std::to_string(line) + ": " + what);
}

/// Reads exactly `n` numbers after the keyword.
std::vector<double> numbers(std::istringstream& in, std::size_t n, const std::string& key,
                            const std::string& name, int line)
{
    std::vector<double> v(n);
    for (double& x : v) {
        if (!(in >> x))
            fail(name, line, key + ": expected " + std::to_string(n) + " numbers");
    }
    std::string extra;
    if (in >> extra)
        fail(name, line, key + ": more than " + std::to_string(n) + " numbers");
    return v;
}

}  // namespace

HeadTruth readHeadTruth(std::istream& in, const std::string& name)
{
    HeadTruth t;
    bool pose = false, animation = false, box = false;
    std::string text;
    for (int line = 1; std::getline(in, text); ++line) {
        std::istringstream fields(text);
        std::string key;
        if (!(fields >> key) || key[0] == '#')
            continue;
        if (key == "source") {
            fields >> t.source;
        } else if (key == "pose") {
            const auto v = numbers(fields, 6, key, name, line);
            t.pose.yawDeg = v[0], t.pose.pitchDeg = v[1], t.pose.rollDeg = v[2];
            t.pose.scale = v[3], t.pose.translation = {v[4], v[5]};
            pose = true;
        } else if (key == "animation") {
            const auto v = numbers(fields, t.pose.animation.size(), key, name, line);
            for (std::size_t i = 0; i < v.size(); ++i)
                t.pose.animation[i] = static_cast<float>(v[i]);
            animation = true;
        } else if (key == "box") {
            const auto v = numbers(fields, 4, key, name, line);
            t.box = {v[0], v[1], v[2], v[3]};
            box = true;
        } else if (key == "hand") {
            const auto v = numbers(fields, 5, key, name, line);
            t.hand = {v[0] != 0, {v[1], v[2]}, v[3], v[4]};
        } else if (key == "vertex") {
            const auto v = numbers(fields, 5, key, name, line);
            if (v[0] != static_cast<double>(t.vertices.size()))
                fail(name, line,
                     "vertex " + std::to_string(static_cast<long>(v[0])) +
                         " out of order (expected " + std::to_string(t.vertices.size()) + ")");
            t.vertices.push_back({static_cast<int>(v[1]), {v[2], v[3]}, v[4] != 0});
        } else {
            fail(name, line, "unknown key '" + key + "'");
        }
    }
    if (!pose || !animation || !box || t.vertices.empty())
        throw std::runtime_error(name + ": incomplete (needs pose, animation, box and vertices)");
    return t;
}

HeadTruth loadHeadTruth(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(path + ": cannot open");
    return readHeadTruth(in, path);
}

}  // namespace headgen
