#include "face_photo.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace facegen {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

cv::Point2d meanOf(const FacePhoto& f, int first, int last)
{
    cv::Point2d sum(0, 0);
    for (int i = first; i <= last; ++i)
        sum += f.points[i];
    return sum * (1.0 / (last - first + 1));
}

}  // namespace

FacePhoto loadImmFace(const std::string& asfPath)
{
    std::ifstream in(asfPath);
    if (!in)
        throw std::runtime_error("face " + asfPath + ": cannot read");
    FacePhoto face;
    face.name = fs::path(asfPath).stem().string();
    std::string line, host;
    int count = -1, read = 0;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos)
            continue;
        std::istringstream s(line);
        if (count < 0) {
            s >> count;
            continue;
        }
        if (read < count) {
            int path = 0, type = 0, index = 0;
            double x = 0, y = 0;
            if (!(s >> path >> type >> x >> y >> index) || index != read || read >= kImmPoints)
                throw std::runtime_error("face " + asfPath + ": bad point line '" + line + "'");
            // The host images are 640x480; coordinates are relative to that.
            face.points[read++] = {x * 640.0, y * 480.0};
            continue;
        }
        s >> host;
    }
    if (count != kImmPoints || read != kImmPoints || host.empty())
        throw std::runtime_error("face " + asfPath + ": expected 58 points and a host image");
    face.imagePath = (fs::path(asfPath).parent_path() / host).string();
    std::error_code ec;
    if (!fs::is_regular_file(face.imagePath, ec))
        throw std::runtime_error("face " + asfPath + ": host image " + face.imagePath + " missing");
    return face;
}

FaceFrame faceFrameOf(const FacePhoto& f)
{
    // IMM paths: 0-12 jaw, 13-20 and 21-28 eyes, 29-38 brows, 39-46 mouth, 47-57 nose.
    const cv::Point2d eyes = (meanOf(f, 13, 20) + meanOf(f, 21, 28)) * 0.5;
    const cv::Point2d mouth = meanOf(f, 39, 46);
    const cv::Point2d nose = meanOf(f, 47, 57);
    // Total least-squares line through the three midline points (the dissertation's roll truth).
    const cv::Point2d c = (eyes + mouth + nose) * (1.0 / 3.0);
    double sxx = 0, sxy = 0, syy = 0;
    for (const cv::Point2d& p : {eyes, mouth, nose}) {
        sxx += (p.x - c.x) * (p.x - c.x);
        sxy += (p.x - c.x) * (p.y - c.y);
        syy += (p.y - c.y) * (p.y - c.y);
    }
    const double theta = 0.5 * std::atan2(2.0 * sxy, sxx - syy);  // principal direction
    cv::Point2d up(std::cos(theta), std::sin(theta));
    if (up.dot(eyes - mouth) < 0)
        up = -up;
    FaceFrame frame;
    frame.anchor = (eyes + mouth) * 0.5;
    frame.width = cv::norm(f.points[12] - f.points[0]);
    // Upright is (0,-1); turning it clockwise on screen by r gives (sin r, -cos r).
    frame.rollDeg = std::atan2(up.x, -up.y) * kDeg;
    return frame;
}

cv::Point2d rotateOnScreen(cv::Point2d v, double deg) noexcept
{
    const double r = deg / kDeg, c = std::cos(r), s = std::sin(r);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

FaceBox faceBoxOf(const FaceFrame& frame) noexcept
{
    FaceBox box;
    box.centre = frame.anchor +
                 rotateOnScreen(cv::Point2d(kBoxOffsetX, kBoxOffsetY) * frame.width, frame.rollDeg);
    box.size = kBoxPerWidth * frame.width;
    box.rollDeg = frame.rollDeg;
    return box;
}

cv::Mat headMask(const cv::Mat& photo, const FacePhoto& face)
{
    const FaceFrame fr = faceFrameOf(face);
    const double w = fr.width;
    // Ellipse from above the hair (1.3 w over the anchor) to just under the chin (0.85 w below),
    // 0.72 w to either side: the ears and the hair at the temples, as on the IMM photographs.
    const cv::Point2d centre = fr.anchor + rotateOnScreen({0.0, -0.225 * w}, fr.rollDeg);
    const double a = 0.72 * w, b = 1.075 * w;
    const double c = std::cos(fr.rollDeg / kDeg), s = std::sin(fr.rollDeg / kDeg);

    // The IMM backdrop is a plain cloth: its colour from the top corners, keyed out in Lab.
    cv::Mat lab;
    cv::cvtColor(photo, lab, cv::COLOR_BGR2Lab);
    const int cw = std::min(60, photo.cols / 4), ch = std::min(40, photo.rows / 4);
    const cv::Scalar left = cv::mean(lab(cv::Rect(0, 0, cw, ch)));
    const cv::Scalar right = cv::mean(lab(cv::Rect(photo.cols - cw, 0, cw, ch)));
    const cv::Scalar backdrop = (left + right) * 0.5;

    // Inside the landmarks' hull (raised to the forehead) the face is always kept.
    std::vector<cv::Point> hull;
    {
        std::vector<cv::Point2f> pts;
        for (const cv::Point2d& p : face.points) {
            pts.emplace_back(p);
            const cv::Point2d raised = p + rotateOnScreen({0.0, -0.3 * w}, fr.rollDeg);
            if (&p - face.points.data() >= 29 && &p - face.points.data() <= 38)
                pts.emplace_back(raised);
        }
        std::vector<cv::Point2f> h;
        cv::convexHull(pts, h);
        for (const cv::Point2f& p : h)
            hull.emplace_back(cvRound(p.x), cvRound(p.y));
    }
    cv::Mat keep = cv::Mat::zeros(photo.size(), CV_8U);
    cv::fillConvexPoly(keep, hull, cv::Scalar(255), cv::LINE_8);

    cv::Mat alpha(photo.size(), CV_32F);
    for (int y = 0; y < photo.rows; ++y) {
        const cv::Vec3b* l = lab.ptr<cv::Vec3b>(y);
        const std::uint8_t* k = keep.ptr<std::uint8_t>(y);
        float* out = alpha.ptr<float>(y);
        for (int x = 0; x < photo.cols; ++x) {
            const double dx = x - centre.x, dy = y - centre.y;
            const double u = (c * dx + s * dy) / a, v = (-s * dx + c * dy) / b;
            const double r = std::sqrt(u * u + v * v);
            const double ellipse = std::clamp((1.0 - r) / 0.1, 0.0, 1.0);
            double key = 1.0;
            if (k[x] == 0) {
                const double d = std::sqrt((l[x][0] - backdrop[0]) * (l[x][0] - backdrop[0]) +
                                           (l[x][1] - backdrop[1]) * (l[x][1] - backdrop[1]) +
                                           (l[x][2] - backdrop[2]) * (l[x][2] - backdrop[2]));
                key = std::clamp((d - 14.0) / 16.0, 0.0, 1.0);
            }
            out[x] = static_cast<float>(ellipse * key);
        }
    }
    // A slightly soft edge, as a lens gives it.
    cv::GaussianBlur(alpha, alpha, cv::Size(0, 0), std::max(0.8, 0.012 * w));
    return alpha;
}

std::vector<std::string> frontalImmFaces(const std::string& immDir)
{
    std::vector<std::string> paths;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(immDir, ec)) {
        const std::string name = entry.path().filename().string();
        // <person>-<type><gender>.asf; types 3 and 4 are turned ~30 degrees sideways.
        if (entry.path().extension() != ".asf" || name.size() < 6)
            continue;
        const char type = name[3];
        if (type == '1' || type == '2' || type == '5' || type == '6')
            paths.push_back(entry.path().string());
    }
    if (ec || paths.empty())
        throw std::runtime_error("faces " + immDir + ": no IMM .asf files of frontal faces (" +
                                 (ec ? ec.message() : std::string("none found")) + ")");
    std::sort(paths.begin(), paths.end());
    return paths;
}

SizeMeasurement measureBoxAgainstLandmarks(const std::vector<std::string>& asfPaths,
                                           const std::string& cascadePath)
{
    cv::CascadeClassifier cascade;
    if (!cascade.load(cascadePath))
        throw std::runtime_error("cascade " + cascadePath + ": cannot load");
    SizeMeasurement m;
    double sum = 0, sum2 = 0, ox = 0, oy = 0;
    for (const std::string& path : asfPaths) {
        const FacePhoto face = loadImmFace(path);
        const cv::Mat photo = cv::imread(face.imagePath, cv::IMREAD_GRAYSCALE);
        if (photo.empty())
            throw std::runtime_error("face " + face.imagePath + ": cannot read");
        ++m.photos;
        const FaceFrame fr = faceFrameOf(face);
        std::vector<cv::Rect> hits;
        cascade.detectMultiScale(photo, hits, 1.1, 3, 0, cv::Size(40, 40));
        const cv::Rect* best = nullptr;
        for (const cv::Rect& r : hits)
            if (r.contains(cv::Point(cvRound(fr.anchor.x), cvRound(fr.anchor.y))) &&
                (best == nullptr || r.area() > best->area()))
                best = &r;
        if (best == nullptr)
            continue;
        ++m.detected;
        // Pixel centres at integer coordinates: a box x..x+w-1 is centred at x + w/2 - 0.5.
        const cv::Point2d centre(best->x + best->width * 0.5 - 0.5,
                                 best->y + best->height * 0.5 - 0.5);
        const double ratio = best->width / fr.width;
        const cv::Point2d off = rotateOnScreen(centre - fr.anchor, -fr.rollDeg) * (1.0 / fr.width);
        sum += ratio;
        sum2 += ratio * ratio;
        ox += off.x;
        oy += off.y;
    }
    if (m.detected > 0) {
        m.boxPerWidth = sum / m.detected;
        m.boxPerWidthStd =
            std::sqrt(std::max(0.0, sum2 / m.detected - m.boxPerWidth * m.boxPerWidth));
        m.offsetX = ox / m.detected;
        m.offsetY = oy / m.detected;
    }
    return m;
}

}  // namespace facegen
