#pragma once
// The IMM face database's frontal photographs (types 1 and 2 of 40 people, 58 landmarks each),
// rotated under `mirror-eval roll`'s protocol: a square crop of 3x the eye-to-mouth
// distance about the face centre, border replicated, rotated about that centre by a seeded angle
// in [-30, 30] degrees, landmarks with it. Truth: the best line through eye midpoint, nose tip and
// mouth centre. Face boxes (a) from cv::CascadeClassifier (haarcascade_frontalface_default) on the
// crop (missed faces left out, as in the dissertation) and (b) from the landmarks, off by up to 5%
// of their size each way as a detector's box is. Shared by the roll peer tests.

#include "error_stats.hpp"
#include "face_truth.hpp"
#include "test_paths.hpp"

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

namespace imm_rotated_faces {

using vision::Point2f;

struct Face {
    std::string image;
    std::vector<cv::Point2f> landmarks;  // 58, pixels
};

/// The 58 landmarks of an IMM .asf file (relative coordinates) in pixels of a w x h image.
inline std::vector<cv::Point2f> readAsf(const std::string& path, int width, int height)
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

inline std::vector<Face> frontalImmFaces()
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

inline cv::Point2f mean(const std::vector<cv::Point2f>& p, int first, int last)
{
    cv::Point2f sum(0.f, 0.f);
    for (int i = first; i <= last; ++i)
        sum += p[static_cast<std::size_t>(i)];
    return sum * (1.f / static_cast<float>(last - first + 1));
}

/// Eye midpoint, nose tip, mouth centre of the IMM markup (eyes 13-20 and 21-28, mouth 39-46,
/// nose 47-57 with its lowest centre point 52).
inline std::array<cv::Point2f, 3> axisPoints(const std::vector<cv::Point2f>& p)
{
    const cv::Point2f eyes = 0.5f * (mean(p, 13, 20) + mean(p, 21, 28));
    return {eyes, p[52], mean(p, 39, 46)};
}

/// Roll (our sign: clockwise on screen positive) of the best line through the axis points:
/// mirror-eval roll's truth (face_truth.hpp).
inline double truthRoll(const std::array<cv::Point2f, 3>& a)
{
    return mirror_eval::axisRollDegrees({a[0].x, a[0].y}, {a[1].x, a[1].y}, {a[2].x, a[2].y});
}

/// Absolute roll errors (degrees) of one estimator configuration.
using Errors = mirror_eval::ErrorStats;

/// One line: the configuration's errors on faces of the named kind of box.
inline void printErrors(const Errors& e, const char* boxes)
{
    std::printf("roll %s %s: faces=%zu mean_err_deg=%.2f within1=%.0f%% within5=%.0f%%\n", boxes,
                e.name, e.values.size(), e.mean(), 100.0 * e.within(1.0), 100.0 * e.within(5.0));
}

/// One rotated face: its crop, the truth roll and the two kinds of box.
struct Sample {
    cv::Mat crop;
    double truth = 0.0;
    double rotation = 0.0;      ///< the seeded angle the crop was turned by
    double uprightTruth = 0.0;  ///< the truth before turning
    bool detected = false;
    cv::Rect cascadeBox, landmarkBox;
};

/// `small`: the crop is shrunk so the eye-mouth distance is 12-25 px (the size of the scanned
/// CMU/MIT faces), noised, and blown up again to 150 px, as mirror-eval resamples small crops.
inline std::vector<Sample> rotatedSamples(unsigned seed, bool small)
{
    const auto faces = frontalImmFaces();
    EXPECT_EQ(faces.size(), 80u) << "IMM frontal faces (types 1 and 2) not found";
    cv::CascadeClassifier cascade(
        "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml");
    EXPECT_FALSE(cascade.empty());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> angle(-30.0, 30.0);
    std::uniform_real_distribution<double> jitter(-0.05, 0.05);
    std::vector<Sample> samples;
    for (const auto& face : faces) {
        const cv::Mat gray = cv::imread(face.image, cv::IMREAD_GRAYSCALE);
        if (gray.empty())
            continue;
        const auto axis = axisPoints(face.landmarks);
        const cv::Point2f centre = 0.5f * (axis[0] + axis[2]);
        const double eyeMouth = cv::norm(axis[2] - axis[0]);
        const int side = static_cast<int>(std::lround(3.0 * eyeMouth));
        const double rotation = angle(rng);
        cv::Mat m = cv::getRotationMatrix2D(centre, -rotation, 1.0);
        m.at<double>(0, 2) += 0.5 * (side - 1) - centre.x;
        m.at<double>(1, 2) += 0.5 * (side - 1) - centre.y;
        Sample s;
        cv::warpAffine(gray, s.crop, m, cv::Size(side, side), cv::INTER_LINEAR,
                       cv::BORDER_REPLICATE);
        std::vector<cv::Point2f> moved;
        cv::transform(std::vector<cv::Point2f>(axis.begin(), axis.end()), moved, m);
        double scale = 1.0;  // crop pixels per original pixel
        if (small) {
            std::uniform_real_distribution<double> target(12.0, 25.0);
            const int tiny = static_cast<int>(std::lround(3.0 * target(rng)));
            cv::Mat shrunk, noise(tiny, tiny, CV_16S);
            cv::resize(s.crop, shrunk, cv::Size(tiny, tiny), 0, 0, cv::INTER_AREA);
            cv::theRNG().state = seed;
            cv::randn(noise, 0, 4);
            cv::Mat noisy;
            shrunk.convertTo(noisy, CV_16S);
            noisy += noise;
            noisy.convertTo(shrunk, CV_8U);
            cv::resize(shrunk, s.crop, cv::Size(150, 150), 0, 0, cv::INTER_LINEAR);
            scale = 150.0 / side;
            for (auto& p : moved)
                p = cv::Point2f(static_cast<float>((p.x + 0.5) * scale - 0.5),
                                static_cast<float>((p.y + 0.5) * scale - 0.5));
        }
        const int cropSide = s.crop.cols;
        s.truth = truthRoll({moved[0], moved[1], moved[2]});
        s.rotation = rotation;
        s.uprightTruth = truthRoll(axis);
        std::vector<cv::Rect> boxes;
        cascade.detectMultiScale(s.crop, boxes, 1.1, 3, 0, cv::Size(cropSide / 4, cropSide / 4));
        const auto hit = std::find_if(boxes.begin(), boxes.end(), [&](const cv::Rect& b) {
            return b.contains(moved[0]) && b.contains(moved[2]);
        });
        if (hit != boxes.end()) {
            s.detected = true;
            s.cascadeBox = *hit;
        }
        const double size = 2.2 * eyeMouth * scale;
        const double cx = 0.5 * (cropSide - 1) + jitter(rng) * size;
        const double cy = 0.5 * (cropSide - 1) + jitter(rng) * size;
        s.landmarkBox =
            cv::Rect(static_cast<int>(std::lround(cx - 0.5 * size)),
                     static_cast<int>(std::lround(cy - 0.5 * size)),
                     static_cast<int>(std::lround(size)), static_cast<int>(std::lround(size)));
        samples.push_back(std::move(s));
    }
    return samples;
}

}  // namespace imm_rotated_faces
