// Roll by point symmetry on real annotated faces: the IMM face database's frontal photographs
// (types 1 and 2 of 40 people, 58 landmarks each). Protocol of issue 4's `mirror-eval roll`: a
// square crop of 3x the eye-to-mouth distance around the face, padded by border replication, is
// rotated about the face centre by a seeded random angle in [-30, 30] degrees, landmarks with it.
// Ground-truth roll: the angle between vertical and the best line through the nose tip, the mouth
// centre and the eye midpoint. Corners: cv::goodFeaturesToTrack in the face box (a stand-in for
// our own Shi-Tomasi until the face pipeline exists): at most 60 (and, second, 40) corners, none
// closer than 1/20 of the box side. Also scored: the dissertation's own variant (whole degrees,
// plain mean, axis through the box centre), its least-squares line-fit baseline, and "upright".
// The face box comes (a) from cv::CascadeClassifier (haarcascade_frontalface_default) on the
// rotated crop, faces it misses left out as in the dissertation, and (b) from the landmarks with a
// seeded detector-like error for every face. The CMU/MIT sets are GIFs, which this OpenCV cannot
// read, so they wait for mirror-eval.

#include "test_paths.hpp"
#include "vision/roll_estimator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using vision::Point2f;

constexpr double kPi = 3.14159265358979323846;

struct Face {
    std::string image;
    std::vector<cv::Point2f> landmarks;  // 58, pixels
};

/// The 58 landmarks of an IMM .asf file (relative coordinates) in pixels of a w x h image.
std::vector<cv::Point2f> readAsf(const std::string& path, int width, int height)
{
    std::ifstream in(path);
    std::vector<cv::Point2f> points;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#')
            continue;
        std::istringstream fields(line);
        int pathIndex = 0, type = 0;
        double x = 0, y = 0;
        if (fields >> pathIndex >> type >> x >> y)
            points.emplace_back(static_cast<float>(x * width), static_cast<float>(y * height));
    }
    return points;
}

std::vector<Face> frontalImmFaces()
{
    std::vector<Face> faces;
    const std::filesystem::path dir = testing_support::sharedData("imm_face_db");
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        // NN-1m.jpg / NN-2f.jpg: frontal, neutral (1) and "happy" (2); 3-6 turn or light the face.
        if (entry.path().extension() == ".jpg" && name.size() == 9 &&
            (name[3] == '1' || name[3] == '2'))
            names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    for (const auto& stem : names) {
        Face face;
        face.image = (dir / (stem + ".jpg")).string();
        face.landmarks = readAsf((dir / (stem + ".asf")).string(), 640, 480);
        if (face.landmarks.size() == 58)
            faces.push_back(std::move(face));
    }
    return faces;
}

cv::Point2f mean(const std::vector<cv::Point2f>& p, int first, int last)
{
    cv::Point2f sum(0.f, 0.f);
    for (int i = first; i <= last; ++i)
        sum += p[static_cast<std::size_t>(i)];
    return sum * (1.f / static_cast<float>(last - first + 1));
}

/// Eye midpoint, nose tip, mouth centre of the IMM markup (eyes 13-20 and 21-28, mouth 39-46,
/// nose 47-57 with its lowest centre point 52).
std::array<cv::Point2f, 3> axisPoints(const std::vector<cv::Point2f>& p)
{
    const cv::Point2f eyes = 0.5f * (mean(p, 13, 20) + mean(p, 21, 28));
    return {eyes, p[52], mean(p, 39, 46)};
}

/// Roll (our sign: clockwise on screen positive) of the best line through the axis points.
double truthRoll(const std::array<cv::Point2f, 3>& a)
{
    std::vector<Point2f> points;
    for (const auto& p : a)
        points.push_back({p.x, p.y});
    // The principal direction of three nearly collinear points; the line fit folds it into
    // +-45 degrees of horizontal, and a face's vertical axis is +-45 of vertical, so both agree.
    double roll = vision::estimateRollByLineFit(points).rollDegrees;
    // Sign check against the eye-to-mouth direction: for a face rolled clockwise by r the
    // direction (eyes -> mouth) is (-sin r, cos r).
    const cv::Point2f down = a[2] - a[0];
    const double fromVertical = std::atan2(-down.x, down.y) * 180.0 / kPi;
    if (std::fabs(fromVertical - roll) > 45.0)
        roll = fromVertical;  // degenerate fit; use the two-point axis
    return roll;
}

/// Absolute roll errors (degrees) of one estimator configuration.
struct Errors {
    const char* name;
    std::vector<double> values;

    double mean() const
    {
        double sum = 0;
        for (double x : values)
            sum += x;
        return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
    }
    double within(double limit) const
    {
        const auto n =
            std::count_if(values.begin(), values.end(), [&](double x) { return x <= limit; });
        return values.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(values.size());
    }
    void report(const char* boxes) const
    {
        std::printf("roll %s %s: faces=%zu mean_err_deg=%.2f within1=%.0f%% within5=%.0f%%\n",
                    boxes, name, values.size(), mean(), 100.0 * within(1.0), 100.0 * within(5.0));
    }
};

/// Every configuration on one set of face boxes.
struct Results {
    Errors symmetry60{"symmetry (60 corners)", {}};
    Errors symmetry40{"symmetry (40 corners)", {}};
    Errors dissertation60{"dissertation's symmetry (60 corners)", {}};
    Errors lineFit60{"line-fit baseline (60 corners)", {}};
    Errors upright{"assume vertical", {}};
    void report(const char* boxes) const
    {
        for (const Errors* e : {&symmetry60, &symmetry40, &dissertation60, &lineFit60, &upright})
            e->report(boxes);
    }
};

/// Corners as the face pipeline will find them: Shi-Tomasi in the box, at most `count`, no two
/// closer than 1/20 of the box side.
std::vector<Point2f> corners(const cv::Mat& gray, cv::Rect box, int count)
{
    std::vector<cv::Point2f> found;
    cv::goodFeaturesToTrack(gray(box), found, count, 0.01, box.width / 20.0);
    std::vector<Point2f> points;
    for (const auto& c : found)
        points.push_back({c.x + static_cast<float>(box.x), c.y + static_cast<float>(box.y)});
    return points;
}

void estimate(const cv::Mat& gray, cv::Rect box, double truth, Results& results)
{
    box &= cv::Rect(0, 0, gray.cols, gray.rows);
    const Point2f centre{static_cast<float>(box.x) + 0.5f * static_cast<float>(box.width - 1),
                         static_cast<float>(box.y) + 0.5f * static_cast<float>(box.height - 1)};
    const auto size = static_cast<float>(box.width);
    // The dissertation's method: whole degrees, plain mean, axis through the box centre.
    vision::RollEstimatorOptions plain;
    plain.refineToleranceDegrees = 0.f;
    plain.trimFraction = 0.f;
    plain.capFraction = 0.f;
    plain.maxAxisOffsetFraction = 0.f;

    const auto points60 = corners(gray, box, 60);
    const auto points40 = corners(gray, box, 40);
    auto error = [&](const vision::RollEstimate& e) { return std::fabs(e.rollDegrees - truth); };
    results.symmetry60.values.push_back(
        error(vision::estimateRollBySymmetry(points60, centre, size)));
    results.symmetry40.values.push_back(
        error(vision::estimateRollBySymmetry(points40, centre, size)));
    results.dissertation60.values.push_back(
        error(vision::estimateRollBySymmetry(points60, centre, size, plain)));
    results.lineFit60.values.push_back(error(vision::estimateRollByLineFit(points60)));
    results.upright.values.push_back(std::fabs(truth));
}

TEST(RollLandmarksPeer, ImmFrontalFacesRotatedUpTo30Degrees)
{
    const auto faces = frontalImmFaces();
    ASSERT_EQ(faces.size(), 80u) << "IMM frontal faces (types 1 and 2) not found";
    cv::CascadeClassifier cascade(
        "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml");
    ASSERT_FALSE(cascade.empty());

    std::mt19937 rng(2006);
    std::uniform_real_distribution<double> angle(-30.0, 30.0);
    std::uniform_real_distribution<double> jitter(-0.05, 0.05);
    Results detected, fromLandmarks;
    int missed = 0;
    for (const auto& face : faces) {
        const cv::Mat gray = cv::imread(face.image, cv::IMREAD_GRAYSCALE);
        ASSERT_FALSE(gray.empty()) << face.image;
        const auto axis = axisPoints(face.landmarks);
        const cv::Point2f centre = 0.5f * (axis[0] + axis[2]);
        const double eyeMouth = cv::norm(axis[2] - axis[0]);
        const int side = static_cast<int>(std::lround(3.0 * eyeMouth));
        const double rotation = angle(rng);

        // Our positive roll is clockwise on screen; OpenCV's positive angle is anticlockwise.
        cv::Mat m = cv::getRotationMatrix2D(centre, -rotation, 1.0);
        m.at<double>(0, 2) += 0.5 * (side - 1) - centre.x;
        m.at<double>(1, 2) += 0.5 * (side - 1) - centre.y;
        cv::Mat crop;
        cv::warpAffine(gray, crop, m, cv::Size(side, side), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
        std::vector<cv::Point2f> moved;
        cv::transform(std::vector<cv::Point2f>(axis.begin(), axis.end()), moved, m);
        const std::array<cv::Point2f, 3> rotated = {moved[0], moved[1], moved[2]};
        const double truth = truthRoll(rotated);
        EXPECT_NEAR(truth, truthRoll(axis) + rotation, 1e-3);

        // (a) the cascade's box holding the eye midpoint and mouth centre, if it finds one.
        std::vector<cv::Rect> boxes;
        cascade.detectMultiScale(crop, boxes, 1.1, 3, 0, cv::Size(side / 4, side / 4));
        const auto hit = std::find_if(boxes.begin(), boxes.end(), [&](const cv::Rect& b) {
            return b.contains(rotated[0]) && b.contains(rotated[2]);
        });
        if (hit != boxes.end())
            estimate(crop, *hit, truth, detected);
        else
            ++missed;

        // (b) every face: a square of 2.2x the eye-mouth distance about the face centre, off by up
        // to 5% of its size each way as a detector's box would be.
        const double size = 2.2 * eyeMouth;
        const double cx = 0.5 * (side - 1) + jitter(rng) * size;
        const double cy = 0.5 * (side - 1) + jitter(rng) * size;
        const cv::Rect box(static_cast<int>(std::lround(cx - 0.5 * size)),
                           static_cast<int>(std::lround(cy - 0.5 * size)),
                           static_cast<int>(std::lround(size)),
                           static_cast<int>(std::lround(size)));
        estimate(crop, box, truth, fromLandmarks);
    }
    std::printf("roll: cascade missed %d of %zu rotated faces\n", missed, faces.size());
    detected.report("cascade-box");
    fromLandmarks.report("landmark-box");

    // Issue 4's targets (mean <= 4.0 degrees, >= 85% within 5; the dissertation had 6.0 and 73%),
    // on the faces the cascade finds and on every face with a jittered box.
    ASSERT_GE(detected.symmetry60.values.size(), 55u);
    for (const Results* r : {&detected, &fromLandmarks}) {
        EXPECT_LE(r->symmetry60.mean(), 3.5);
        EXPECT_GE(r->symmetry60.within(5.0), 0.88);
        EXPECT_LE(r->symmetry40.mean(), 5.0);
        EXPECT_GE(r->symmetry40.within(5.0), 0.85);
        // Better than the dissertation's own scoring on the same corners, and far better than the
        // line fit it compared with.
        EXPECT_LT(r->symmetry60.mean(), r->dissertation60.mean());
        EXPECT_LT(r->symmetry60.mean() * 3.0, r->lineFit60.mean());
    }
}

}  // namespace
