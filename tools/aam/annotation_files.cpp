// The .asf and .pts readers: one function per part of each file, over FieldLines.
#include "annotation_files.hpp"

#include "field_lines.hpp"
#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <charconv>
#include <iomanip>
#include <optional>
#include <sstream>

namespace aam {

namespace {

constexpr long kMaxPoints = 10000;  // a garbled count must not become a huge allocation

using AnnotationLines = FieldLines<AnnotationError>;

template <typename T>
T parsed(AnnotationLines& lines, const std::string& text, const std::string& what)
{
    T value{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) {
        lines.fail(what + ": \"" + text + "\" is not " +
                   (std::is_integral_v<T> ? "an integer" : "a number"));
    }
    return value;
}

long pointCount(AnnotationLines& lines, const std::vector<std::string>& fields, std::size_t at)
{
    const long n = parsed<long>(lines, fields[at], "the point count");
    if (n <= 0 || n > kMaxPoints)
        lines.fail("the point count " + fields[at] + " is out of range");
    return n;
}

Eigen::Vector2d asfPoint(AnnotationLines& lines, long i, long n, int width, int height)
{
    const std::string what = "point " + std::to_string(i) + " of " + std::to_string(n);
    const auto f = lines.expect(what);
    // 41 of IMM's files append three numbers (0.00) to each point, as later AAM-API versions write.
    if (f.size() != 7 && f.size() != 10) {
        lines.fail(what + ": expected 7 fields \"path type x y point from to\", got \"" +
                   joinedFields(f) + "\"");
    }
    const double x = parsed<double>(lines, f[2], what);
    const double y = parsed<double>(lines, f[3], what);
    if (parsed<long>(lines, f[4], what) != i)
        lines.fail(what + ": numbered " + f[4]);
    if (!(x >= 0 && x <= 1 && y >= 0 && y <= 1))
        lines.fail(what + ": relative coordinates outside [0, 1]");
    return {x * width, y * height};
}

}  // namespace

Annotation readAsf(std::istream& in, const std::string& name, int imageWidth, int imageHeight)
{
    AnnotationLines lines(in, name);
    const auto countLine = lines.expect("the point count");
    if (countLine.size() != 1)
        lines.fail("expected the point count, got \"" + joinedFields(countLine) + "\"");
    const long n = pointCount(lines, countLine, 0);
    Annotation a;
    for (long i = 0; i < n; ++i)
        a.points.push_back(asfPoint(lines, i, n, imageWidth, imageHeight));
    const auto host = lines.expect("the host image's file name");
    if (host.size() != 1)
        lines.fail("expected the host image's file name, got \"" + joinedFields(host) + "\"");
    a.hostImage = host[0];
    if (const auto extra = lines.next())
        lines.fail("unexpected data after the host image: \"" + joinedFields(*extra) + "\"");
    return a;
}

Annotation readPts(std::istream& in, const std::string& name)
{
    AnnotationLines lines(in, name);
    const auto version = lines.expect("\"version: 1\"");
    if (version.size() != 2 || version[0] != "version:" || version[1] != "1") {
        lines.fail("expected \"version: 1\", got \"" + joinedFields(version) + "\"");
    }
    const auto count = lines.expect("\"n_points: N\"");
    if (count.size() != 2 || count[0] != "n_points:")
        lines.fail("expected \"n_points: N\", got \"" + joinedFields(count) + "\"");
    const long n = pointCount(lines, count, 1);
    if (lines.expect("\"{\"") != std::vector<std::string>{"{"})
        lines.fail("expected \"{\" before the points");
    Annotation a;
    for (long i = 0; i < n; ++i) {
        const std::string what = "point " + std::to_string(i) + " of " + std::to_string(n);
        const auto f = lines.expect(what);
        if (f.size() != 2)
            lines.fail(what + ": expected \"x y\", got \"" + joinedFields(f) + "\"");
        a.points.emplace_back(parsed<double>(lines, f[0], what), parsed<double>(lines, f[1], what));
    }
    const auto close = lines.expect("\"}\" after " + std::to_string(n) + " points");
    if (close != std::vector<std::string>{"}"}) {
        lines.fail("expected \"}\" after " + std::to_string(n) + " points, got \"" +
                   joinedFields(close) + "\"");
    }
    if (const auto extra = lines.next())
        lines.fail("unexpected data after \"}\": \"" + joinedFields(*extra) + "\"");
    return a;
}

namespace {

/// The file's text, read through readBoundedFile (limits::kAnnotationBytes).
std::istringstream annotationText(const std::string& path)
{
    const vision::BoundedFile file =
        vision::readBoundedFile(path, vision::limits::kAnnotationBytes);
    if (file.status != vision::BoundedFile::Status::Ok) {
        throw AnnotationError(path + ": cannot read the annotation file: " + file.problem);
    }
    return std::istringstream(file.text);
}

}  // namespace

Annotation loadAsf(const std::string& path, int imageWidth, int imageHeight)
{
    std::istringstream in = annotationText(path);
    return readAsf(in, path, imageWidth, imageHeight);
}

Annotation loadPts(const std::string& path)
{
    std::istringstream in = annotationText(path);
    return readPts(in, path);
}

Annotation loadAnnotation(const std::string& path)
{
    return path.ends_with(".asf") ? loadAsf(path) : loadPts(path);
}

void writePts(std::ostream& out, const std::vector<Eigen::Vector2d>& points)
{
    out << "version: 1\nn_points: " << points.size() << "\n{\n" << std::setprecision(9);
    for (const auto& p : points)
        out << p.x() << ' ' << p.y() << '\n';
    out << "}\n";
}

}  // namespace aam
