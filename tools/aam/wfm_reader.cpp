// The .wfm reader: one function per section of the file, in the file's order, over FieldLines
// (whose remembered comment names the next unit).
#include "wfm_reader.hpp"

#include "field_lines.hpp"
#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <charconv>
#include <optional>
#include <sstream>
#include <vector>

namespace aam {

namespace {

// Bounds a garbled count could otherwise turn into a huge allocation; CANDIDE-3 has 113 vertices.
constexpr long kMaxCount = 100000;

using WfmLines = FieldLines<WfmError>;

long toInt(WfmLines& lines, const std::string& text, const std::string& what)
{
    long value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
        lines.fail(what + ": \"" + text + "\" is not an integer");
    return value;
}

float toFloat(WfmLines& lines, const std::string& text, const std::string& what)
{
    float value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
        lines.fail(what + ": \"" + text + "\" is not a number");
    return value;
}

/// A line of exactly `n` fields.
std::vector<std::string> fieldsOf(WfmLines& lines, std::size_t n, const std::string& what,
                                  const std::string& form)
{
    auto fields = lines.expect(what);
    if (fields.size() != n) {
        lines.fail(what + ": expected " + std::to_string(n) + " fields \"" + form + "\", got \"" +
                   joinedFields(fields) + "\"");
    }
    return fields;
}

long countOf(WfmLines& lines, const std::string& what)
{
    const auto fields = fieldsOf(lines, 1, "the " + what + " count", "count");
    const long n = toInt(lines, fields[0], "the " + what + " count");
    if (n < 0 || n > kMaxCount)
        lines.fail("the " + what + " count " + fields[0] + " is out of range");
    return n;
}

int vertexIndex(WfmLines& lines, const std::string& text, const std::string& what,
                std::size_t vertexCount)
{
    const long v = toInt(lines, text, what);
    if (v < 0 || v >= static_cast<long>(vertexCount)) {
        lines.fail(what + ": vertex " + text + " does not exist (" + std::to_string(vertexCount) +
                   " vertices)");
    }
    return static_cast<int>(v);
}

Eigen::Vector3f vector3(WfmLines& lines, const std::vector<std::string>& f, std::size_t first,
                        const std::string& what)
{
    return {toFloat(lines, f[first], what), toFloat(lines, f[first + 1], what),
            toFloat(lines, f[first + 2], what)};
}

void readVertices(WfmLines& lines, vision::CandideMesh& mesh)
{
    const long n = countOf(lines, "vertex");
    for (long i = 0; i < n; ++i) {
        const std::string what = "vertex " + std::to_string(i) + " of " + std::to_string(n);
        mesh.vertices.push_back(vector3(lines, fieldsOf(lines, 3, what, "x y z"), 0, what));
        mesh.candideNumber.push_back(static_cast<int>(i));
    }
}

void readTriangles(WfmLines& lines, vision::CandideMesh& mesh)
{
    const long n = countOf(lines, "triangle");
    for (long i = 0; i < n; ++i) {
        const std::string what = "triangle " + std::to_string(i) + " of " + std::to_string(n);
        const auto f = fieldsOf(lines, 3, what, "i j k");
        std::array<int, 3> t{};
        for (std::size_t k = 0; k < 3; ++k)
            t[k] = vertexIndex(lines, f[k], what, mesh.vertices.size());
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            lines.fail(what + ": repeats a vertex");
        mesh.triangles.push_back(t);
    }
}

/// "AUV11 Jaw drop (AU26/27)" -> label "AUV11", name "Jaw drop (AU26/27)"; "FAP 3 open_jaw" ->
/// "FAP 3", "open_jaw"; a shape unit's comment is all name.
void nameUnit(const std::string& comment, vision::CandideUnit& unit)
{
    std::istringstream words(comment);
    std::string first;
    words >> first;
    std::string label;
    if (first.starts_with("AUV")) {
        label = first;
    } else if (first.starts_with("FAP")) {
        std::string number = first.substr(3);
        if (number.empty())
            words >> number;
        label = "FAP " + number;
    }
    if (label.empty()) {
        unit.name = comment;
        return;
    }
    std::string rest;
    std::getline(words >> std::ws, rest);
    unit.label = label;
    unit.name = rest;
}

void readUnits(WfmLines& lines, std::size_t vertexCount, const std::string& kind,
               std::vector<vision::CandideUnit>& units)
{
    const long n = countOf(lines, kind + " unit");
    for (long u = 0; u < n; ++u) {
        const std::string unitWhat =
            kind + " unit " + std::to_string(u) + " of " + std::to_string(n);
        const long entries = countOf(lines, unitWhat + "'s vertex");
        vision::CandideUnit unit;
        nameUnit(lines.comment(), unit);
        for (long e = 0; e < entries; ++e) {
            const std::string what = unitWhat + " (" +
                                     (unit.name.empty() ? unit.label : unit.name) + "), entry " +
                                     std::to_string(e) + " of " + std::to_string(entries);
            const auto f = fieldsOf(lines, 4, what, "vertex dx dy dz");
            unit.vertices.push_back(vertexIndex(lines, f[0], what, vertexCount));
            unit.displacements.push_back(vector3(lines, f, 1, what));
        }
        units.push_back(std::move(unit));
    }
}

/// Parameters stored with the model pose it, they are not part of it: checked, not kept.
void readParameters(WfmLines& lines, std::size_t unitCount, const std::string& kind)
{
    const long n = countOf(lines, kind + " parameter");
    for (long i = 0; i < n; ++i) {
        const std::string what =
            kind + " parameter " + std::to_string(i) + " of " + std::to_string(n);
        const auto f = fieldsOf(lines, 2, what, "unit value");
        const long unit = toInt(lines, f[0], what);
        if (unit < 0 || unit >= static_cast<long>(unitCount))
            lines.fail(what + ": unit " + f[0] + " does not exist");
        toFloat(lines, f[1], what);
    }
}

void readTextureAndGlobalMotion(WfmLines& lines)
{
    if (countOf(lines, "texture") != 0)
        lines.fail("texture coordinates are not supported (expected a count of 0)");
    for (const char* row : {"global rotation", "global scale", "global translation"}) {
        vector3(lines, fieldsOf(lines, 3, std::string("the ") + row, "x y z"), 0,
                std::string("the ") + row);
    }
    if (const auto extra = lines.next())
        lines.fail("unexpected data after the global motion: \"" + joinedFields(*extra) + "\"");
}

}  // namespace

vision::CandideMesh readWfm(std::istream& in, const std::string& name)
{
    WfmLines lines(in, name);
    vision::CandideMesh mesh;
    readVertices(lines, mesh);
    readTriangles(lines, mesh);
    readUnits(lines, mesh.vertices.size(), "animation", mesh.animationUnits);
    readUnits(lines, mesh.vertices.size(), "shape", mesh.shapeUnits);
    readParameters(lines, mesh.animationUnits.size(), "animation");
    readParameters(lines, mesh.shapeUnits.size(), "shape");
    readTextureAndGlobalMotion(lines);
    return mesh;
}

vision::CandideMesh loadWfm(const std::string& path)
{
    const vision::BoundedFile file =
        vision::readBoundedFile(path, vision::limits::kCandideWfmBytes);
    if (file.status != vision::BoundedFile::Status::Ok) {
        throw WfmError(path + ": cannot read the CANDIDE model file: " + file.problem);
    }
    std::istringstream in(file.text);
    return readWfm(in, path);
}

}  // namespace aam
