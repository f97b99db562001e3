// aam-annotate: annotates an integrator's own photograph for the AAM model builder (§5,
// dissertation 5.3.1: the tool "prompts the user for the next point"). A desktop window shows the
// photograph beside a drawing of the CANDIDE-3 face with the point to click next ringed in red;
// each click places it, `u` (or Backspace) takes the last one back, `q` (or Esc) quits without
// saving; once every point of the scheme is placed the .pts file is written beside the photograph
// (or to --out), where `aam-build model --scheme ... --points` finds it with its image.
// Scripted (tests, batch use): --points FILE places the file's points in order instead, printing
// each prompt, with no window.
#include "annotation_files.hpp"
#include "annotation_schemes.hpp"
#include "point_list.hpp"
#include "reference_face.hpp"
#include "shared_data.hpp"
#include "tool_cli.hpp"
#include "wfm_reader.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <opencv2/highgui.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

namespace {

struct Request {
    std::string image, scheme = "ibug", out, points, wfm, reference;
};

std::string prompt(const aam::AnnotationScheme& scheme, const annotate::ReferenceFace& face,
                   int next)
{
    char line[200];
    std::snprintf(line, sizeof line, "point %d of %d (%.*s)%s", next + 1, scheme.pointCount,
                  static_cast<int>(scheme.name.size()), scheme.name.data(),
                  face.mapped(next) ? "" : ", between its neighbours on the drawing");
    return line;
}

void writeAnnotation(const std::string& path, const std::vector<Eigen::Vector2d>& points)
{
    const std::string temp = path + ".tmp";
    {
        std::ofstream out(temp);
        aam::writePts(out, points);
        if (!out.flush())
            throw std::runtime_error(path + ": cannot be written");
    }
    std::filesystem::rename(temp, path);
}

// The window: the photograph (fitted to 800 pixels high) and the drawing side by side.
int annotateInWindow(const Request& r, const cv::Mat& photo, const aam::AnnotationScheme& scheme,
                     const annotate::ReferenceFace& face)
{
    if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr) {
        std::fprintf(stderr,
                     "aam-annotate: no desktop to open a window on (DISPLAY is not set): give "
                     "the points with --points FILE\n");
        return 1;
    }
    const double scale = 800.0 / photo.rows;
    cv::Mat shown;
    cv::resize(photo, shown, cv::Size(), scale, scale, cv::INTER_AREA);
    struct Clicks {
        std::vector<Eigen::Vector2d> points;
        double scale;
        int width;
        int count;
    } clicks{{}, scale, shown.cols, scheme.pointCount};
    const char* title = "aam-annotate";
    cv::namedWindow(title, cv::WINDOW_AUTOSIZE);
    cv::setMouseCallback(
        title,
        [](int event, int x, int y, int, void* user) {
            auto& c = *static_cast<Clicks*>(user);
            if (event == cv::EVENT_LBUTTONDOWN && x < c.width &&
                static_cast<int>(c.points.size()) < c.count)
                c.points.emplace_back(x / c.scale, y / c.scale);
        },
        &clicks);
    for (;;) {
        const int next = static_cast<int>(clicks.points.size());
        if (next == scheme.pointCount)
            break;
        cv::Mat left = shown.clone();
        for (const Eigen::Vector2d& p : clicks.points)
            cv::circle(left,
                       cv::Point(static_cast<int>(p.x() * scale), static_cast<int>(p.y() * scale)),
                       3, cv::Scalar(60, 200, 60), cv::FILLED, cv::LINE_AA);
        cv::Mat right;
        cv::resize(face.draw(next, next), right, cv::Size(shown.rows, shown.rows));
        cv::Mat both;
        cv::hconcat(left, right, both);
        cv::putText(both, prompt(scheme, face, next) + "  (click; u: undo; q: quit)",
                    cv::Point(10, 28), cv::FONT_HERSHEY_SIMPLEX, 0.7, cv::Scalar(0, 220, 255), 2);
        cv::imshow(title, both);
        const int key = cv::waitKey(30);
        if (key == 'q' || key == 27) {
            std::fprintf(stderr, "aam-annotate: quit after %d of %d points; nothing written\n",
                         next, scheme.pointCount);
            return 1;
        }
        if ((key == 'u' || key == 8) && !clicks.points.empty())
            clicks.points.pop_back();
    }
    cv::destroyWindow(title);
    writeAnnotation(r.out, clicks.points);
    std::printf("aam-annotate: wrote %s (%d points)\n", r.out.c_str(), scheme.pointCount);
    return 0;
}

int annotateFromFile(const Request& r, const aam::AnnotationScheme& scheme,
                     const annotate::ReferenceFace& face)
{
    const std::vector<Eigen::Vector2d> points = annotate::readPointList(r.points);
    if (static_cast<int>(points.size()) != scheme.pointCount) {
        std::fprintf(stderr, "aam-annotate: %s has %zu points; the %.*s scheme has %d\n",
                     r.points.c_str(), points.size(), static_cast<int>(scheme.name.size()),
                     scheme.name.data(), scheme.pointCount);
        return 1;
    }
    for (int i = 0; i < scheme.pointCount; ++i)
        std::printf("%s: %.1f %.1f\n", prompt(scheme, face, i).c_str(),
                    points[static_cast<std::size_t>(i)].x(),
                    points[static_cast<std::size_t>(i)].y());
    writeAnnotation(r.out, points);
    std::printf("aam-annotate: wrote %s (%d points)\n", r.out.c_str(), scheme.pointCount);
    return 0;
}

int run(Request r)
{
    const aam::AnnotationScheme& scheme = aam::schemeNamed(r.scheme);
    const cv::Mat photo = cv::imread(r.image, cv::IMREAD_COLOR);
    if (photo.empty())
        throw std::runtime_error(r.image + ": not a picture OpenCV can read");
    if (r.out.empty())
        r.out = std::filesystem::path(r.image).replace_extension(".pts").string();
    const vision::CandideMesh candide = aam::loadWfm(r.wfm);
    const annotate::ReferenceFace face(candide, scheme);
    if (!r.reference.empty() && !cv::imwrite(r.reference, face.draw(0, 0)))
        throw std::runtime_error(r.reference + ": cannot be written");
    return r.points.empty() ? annotateInWindow(r, photo, scheme, face)
                            : annotateFromFile(r, scheme, face);
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{
        "aam-annotate: mark an annotation scheme's points on your own photograph for aam-build, "
        "prompted point by point on a drawing of the CANDIDE-3 face"};
    tool_cli::addVersion(app, "aam-annotate");
    Request r;
    r.wfm = tool_data::defaultDir() + "/candide3/candide3.wfm";
    app.add_option("--image", r.image, "the photograph to annotate")->required();
    app.add_option("--scheme", r.scheme, "the points to mark: ibug (68), imm (58) or fgnet (68)")
        ->capture_default_str();
    app.add_option("--out", r.out, "the .pts file to write (default: beside the image)");
    app.add_option("--points", r.points,
                   "place these points (\"x y\" per line, in order) instead of clicks: no window");
    app.add_option("--wfm", r.wfm, "the CANDIDE-3 .wfm file")->capture_default_str();
    app.add_option("--reference", r.reference, "also write the prompt drawing (first point) here");
    if (const int code = tool_cli::parse(app, argc, argv); code >= 0)
        return code;
    try {
        return run(r);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "aam-annotate: %s\n", e.what());
        return 1;
    }
}
