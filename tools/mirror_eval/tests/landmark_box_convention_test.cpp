// Measures again, on dlib's example faces (68 landmarks each, iBUG 300-W scheme), the factors of
// face_match.hpp that turn a Viola-Jones square into its face's landmark box: mirror-eval track
// matches FGNet's landmark truth with them, so they must come from these other faces and stay
// true to them.

#include "detect_eval.hpp"
#include "face_match.hpp"
#include "face_truth.hpp"
#include "test_paths.hpp"
#include "vision/face_detector.hpp"
#include "vision/haar_cascade.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

namespace {

using namespace mirror_eval;

struct DlibFace {
    std::string image;
    std::vector<vision::Point2f> points;
};

/// The faces of an imglab XML file with landmarks: <image file='..'>, <box ..>, <part .. x y>.
std::vector<DlibFace> loadDlibFaces(const std::string& path)
{
    std::vector<DlibFace> faces;
    std::ifstream in(path);
    std::string line, image;
    while (std::getline(in, line)) {
        char name[256];
        int part = 0, x = 0, y = 0;
        const std::size_t at = line.find_first_not_of(' ');
        if (at == std::string::npos)
            continue;
        if (std::sscanf(line.c_str() + at, "<image file='%255[^']'", name) == 1)
            image = name;
        else if (line.compare(at, 5, "<box ") == 0)
            faces.push_back({image, {}});
        else if (!faces.empty() && std::sscanf(line.c_str() + at, "<part name='%d' x='%d' y='%d'",
                                               &part, &x, &y) == 3)
            faces.back().points.push_back({static_cast<float>(x), static_cast<float>(y)});
    }
    return faces;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

TEST(LandmarkBoxConvention, FactorsHoldOnDlibsExampleFaces)
{
    const std::string dir = testing_support::sharedData("dlib_example_faces");
    std::vector<DlibFace> faces = loadDlibFaces(dir + "/training_with_face_landmarks.xml");
    const std::vector<DlibFace> more = loadDlibFaces(dir + "/testing_with_face_landmarks.xml");
    faces.insert(faces.end(), more.begin(), more.end());
    ASSERT_EQ(faces.size(), 43u);

    const vision::HaarCascade cascade = vision::loadHaarCascade(kDefaultCascade);
    std::vector<double> side, drop, across;
    for (const DlibFace& f : faces) {
        ASSERT_EQ(f.points.size(), 68u) << f.image;
        const cv::Mat gray = cv::imread(dir + "/" + f.image, cv::IMREAD_GRAYSCALE);
        ASSERT_FALSE(gray.empty()) << f.image;
        vision::FaceDetectorOptions o;
        o.maxFrameSize = {gray.cols, gray.rows};
        vision::FaceDetector detector(cascade, o);
        ASSERT_GE(detector.detect({gray.data, gray.cols, gray.rows, static_cast<int>(gray.step),
                                   vision::PixelFormat::Gray8}),
                  0);
        // The detection holding both eyes (points 36-41, 42-47) and the mouth (48-59).
        const vision::Point2f inside[] = {meanOf(f.points, 36, 41), meanOf(f.points, 42, 47),
                                          meanOf(f.points, 48, 59)};
        const BoxF landmarks = boundingBox(f.points);
        for (const vision::Rect& r : detector.faces()) {
            const BoxF b = toBoxF(r);
            if (!std::all_of(std::begin(inside), std::end(inside),
                             [&](vision::Point2f p) { return contains(b, p); }))
                continue;
            const double s = b.width;
            side.push_back(0.5 * (landmarks.width + landmarks.height) / s);
            drop.push_back((landmarks.y + 0.5 * landmarks.height - (b.y + 0.5 * b.height)) / s);
            across.push_back((landmarks.x + 0.5 * landmarks.width - (b.x + 0.5 * b.width)) / s);
            break;
        }
    }
    EXPECT_GE(side.size(), 38u);
    EXPECT_NEAR(median(side), kLandmarkBoxPerSide, 0.02);
    EXPECT_NEAR(median(drop), kLandmarkBoxDrop, 0.02);
    EXPECT_NEAR(median(across), 0.0, 0.04);
}

}  // namespace
