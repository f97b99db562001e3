#include "face_truth.hpp"

#include "vision/roll_estimator.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mirror_eval {

namespace {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void fail(const std::string& name, int line, const std::string& what)
{
    throw std::runtime_error(name + ":" + std::to_string(line) + ": " + what);
}

std::string trimmed(const std::string& s)
{
    const auto first = s.find_first_not_of(" \t\r\n");
    if (first == std::string::npos)
        return {};
    const auto last = s.find_last_not_of(" \t\r\n");
    return s.substr(first, last - first + 1);
}

std::vector<std::string> fieldsOf(const std::string& line)
{
    std::istringstream in(line);
    std::vector<std::string> fields;
    std::string f;
    while (in >> f)
        fields.push_back(f);
    return fields;
}

double number(const std::string& text, const std::string& name, int line, const char* what)
{
    const char* begin = text.c_str();
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin || *end != '\0' || !std::isfinite(v))
        fail(name, line, std::string(what) + " '" + text + "' is not a number");
    return v;
}

int integer(const std::string& text, const std::string& name, int line, const char* what)
{
    const char* begin = text.c_str();
    char* end = nullptr;
    const long v = std::strtol(begin, &end, 10);
    if (end == begin || *end != '\0' || v < -1000000 || v > 1000000)
        fail(name, line, std::string(what) + " '" + text + "' is not an integer");
    return static_cast<int>(v);
}

std::ifstream openOrThrow(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error("truth " + path + ": cannot open (missing or unreadable)");
    return in;
}

vision::Point2f mid(vision::Point2f a, vision::Point2f b)
{
    return {0.5f * (a.x + b.x), 0.5f * (a.y + b.y)};
}

}  // namespace

vision::Point2f LandmarkFace::eyeMidpoint() const noexcept
{
    return mid(leftEye, rightEye);
}

vision::Point2f LandmarkFace::centre() const noexcept
{
    return mid(eyeMidpoint(), mouthCentre);
}

float LandmarkFace::eyeMouthDistance() const noexcept
{
    const vision::Point2f e = eyeMidpoint();
    return std::hypot(mouthCentre.x - e.x, mouthCentre.y - e.y);
}

std::vector<LandmarkFace> parseLandmarkFaces(std::istream& in, const std::string& name)
{
    static const char* const kFields[] = {"left eye x",     "left eye y",    "right eye x",
                                          "right eye y",    "nose x",        "nose y",
                                          "mouth left x",   "mouth left y",  "mouth centre x",
                                          "mouth centre y", "mouth right x", "mouth right y"};
    std::vector<LandmarkFace> faces;
    std::string raw;
    int lineNo = 0;
    while (std::getline(in, raw)) {
        ++lineNo;
        const std::string line = trimmed(raw);
        if (line.empty() || line[0] == '#')
            continue;
        const auto f = fieldsOf(line);
        if (f.size() != 13)
            fail(name, lineNo,
                 "expected 13 fields (file and 6 points x y), got " + std::to_string(f.size()));
        LandmarkFace face;
        face.image = f[0];
        face.line = lineNo;
        vision::Point2f* points[] = {&face.leftEye,   &face.rightEye,    &face.nose,
                                     &face.mouthLeft, &face.mouthCentre, &face.mouthRight};
        for (int k = 0; k < 6; ++k) {
            points[k]->x = static_cast<float>(number(f[1 + 2 * k], name, lineNo, kFields[2 * k]));
            points[k]->y =
                static_cast<float>(number(f[2 + 2 * k], name, lineNo, kFields[2 * k + 1]));
        }
        faces.push_back(face);
    }
    return faces;
}

std::vector<LandmarkFace> loadLandmarkFaces(const std::string& path)
{
    std::ifstream in = openOrThrow(path);
    auto faces = parseLandmarkFaces(in, path);
    if (faces.empty())
        throw std::runtime_error(path + ": no faces");
    return faces;
}

std::vector<vision::Point2f> parsePts(std::istream& in, const std::string& name)
{
    std::string raw;
    int lineNo = 0;
    int expected = -1;
    bool open = false;
    bool closed = false;
    std::vector<vision::Point2f> points;
    while (std::getline(in, raw)) {
        ++lineNo;
        const std::string line = trimmed(raw);
        if (line.empty() || closed)
            continue;
        if (!open) {
            if (line.rfind("version:", 0) == 0)
                continue;
            if (line.rfind("n_points:", 0) == 0) {
                expected = integer(trimmed(line.substr(9)), name, lineNo, "n_points");
                continue;
            }
            if (line == "{") {
                open = true;
                continue;
            }
            fail(name, lineNo, "expected 'version:', 'n_points:' or '{', got '" + line + "'");
        }
        if (line == "}") {
            closed = true;
            continue;
        }
        const auto f = fieldsOf(line);
        if (f.size() != 2)
            fail(name, lineNo, "expected 'x y', got '" + line + "'");
        points.push_back({static_cast<float>(number(f[0], name, lineNo, "x")),
                          static_cast<float>(number(f[1], name, lineNo, "y"))});
    }
    if (!closed)
        fail(name, lineNo, "missing '}' (truncated file?)");
    if (expected < 0)
        fail(name, lineNo, "missing 'n_points:'");
    if (static_cast<int>(points.size()) != expected)
        fail(name, lineNo,
             "n_points is " + std::to_string(expected) + ", read " + std::to_string(points.size()));
    return points;
}

std::vector<vision::Point2f> loadPts(const std::string& path)
{
    std::ifstream in = openOrThrow(path);
    return parsePts(in, path);
}

std::vector<ComposedFace> parseComposedTruth(std::istream& in, const std::string& name)
{
    std::vector<ComposedFace> faces;
    std::string raw;
    int lineNo = 0;
    while (std::getline(in, raw)) {
        ++lineNo;
        const std::string line = trimmed(raw);
        if (line.empty() || line[0] == '#')
            continue;
        const auto f = fieldsOf(line);
        if (f.size() != 6)
            fail(name, lineNo,
                 "expected 6 fields 'id cx cy size roll_deg moving', got " +
                     std::to_string(f.size()));
        ComposedFace face;
        face.id = integer(f[0], name, lineNo, "id");
        face.centre = {static_cast<float>(number(f[1], name, lineNo, "cx")),
                       static_cast<float>(number(f[2], name, lineNo, "cy"))};
        face.size = static_cast<float>(number(f[3], name, lineNo, "size"));
        face.rollDegrees = static_cast<float>(number(f[4], name, lineNo, "roll_deg"));
        const int moving = integer(f[5], name, lineNo, "moving");
        if (moving != 0 && moving != 1)
            fail(name, lineNo, "moving '" + f[5] + "' must be 0 or 1");
        if (!(face.size > 0.f))
            fail(name, lineNo, "size '" + f[3] + "' must be positive");
        face.moving = moving == 1;
        faces.push_back(face);
    }
    return faces;
}

std::vector<ComposedFace> loadComposedTruth(const std::string& path)
{
    std::ifstream in = openOrThrow(path);
    return parseComposedTruth(in, path);
}

double axisRollDegrees(vision::Point2f eyeMidpoint, vision::Point2f nose,
                       vision::Point2f mouthCentre) noexcept
{
    const vision::Point2f points[] = {eyeMidpoint, nose, mouthCentre};
    // The principal direction of three nearly collinear points: the line fit folds it into +-45
    // degrees of horizontal, and a face's vertical axis is within +-45 of vertical, so they agree.
    double roll = vision::estimateRollByLineFit(points).rollDegrees;
    // For a face rolled clockwise by r the direction eyes -> mouth is (-sin r, cos r).
    const double fromVertical =
        std::atan2(-(mouthCentre.x - eyeMidpoint.x), mouthCentre.y - eyeMidpoint.y) * 180.0 / kPi;
    if (std::fabs(fromVertical - roll) > 45.0)
        roll = fromVertical;
    return roll;
}

vision::Point2f meanOf(const std::vector<vision::Point2f>& p, int first, int last)
{
    double x = 0, y = 0;
    for (int i = first; i <= last; ++i) {
        x += p[static_cast<std::size_t>(i)].x;
        y += p[static_cast<std::size_t>(i)].y;
    }
    const double n = last - first + 1;
    return {static_cast<float>(x / n), static_cast<float>(y / n)};
}

std::array<vision::Point2f, 3> axisPoints68(const std::vector<vision::Point2f>& p)
{
    if (p.size() != 68)
        throw std::runtime_error("axisPoints68: expected 68 points, got " +
                                 std::to_string(p.size()));
    return {mid(p[31], p[36]), p[67], meanOf(p, 48, 59)};
}

}  // namespace mirror_eval
