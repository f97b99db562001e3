// Our Viola-Jones evaluator beside cv::CascadeClassifier (the peer) with the same cascade and
// parameters, on the CMU/MIT frontal-face test images (PNG, read as grey by OpenCV): every
// window decision (raw hits, minNeighbors 0) and the grouped boxes (minNeighbors 3) must agree.
// Also prints the time per 360x240 frame of both, single-threaded (printed, never asserted).
#include "test_paths.hpp"
#include "vision/face_detector.hpp"
#include "vision/haar_cascade.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <string>
#include <vector>

using namespace vision;

namespace {

const char* const kCascades[] = {
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml",
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_alt2.xml",
};

constexpr double kScaleFactor = 1.1;
constexpr int kMinNeighbors = 3;
constexpr int kMinSize = 24;

std::vector<std::string> testImages()
{
    std::vector<std::string> files;
    const std::string dir = testing_support::sharedData("cmu_mit_frontal/images");
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        if (e.path().extension() == ".png")
            files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// CPU time of this thread: the build machine is shared, wall time would measure the others.
double threadCpuMs()
{
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

ConstImageView viewOf(const cv::Mat& m)
{
    return {m.data, m.cols, m.rows, static_cast<int>(m.step), PixelFormat::Gray8};
}

bool sameRect(const cv::Rect& a, const Rect& b)
{
    return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
}

struct Agreement {
    long opencv = 0;
    long ours = 0;
    long opencvFound = 0;  // OpenCV boxes we reproduce identically
    long oursFound = 0;    // our boxes OpenCV reproduces identically

    void add(const std::vector<cv::Rect>& theirs, std::span<const Rect> mine)
    {
        opencv += static_cast<long>(theirs.size());
        ours += static_cast<long>(mine.size());
        for (const cv::Rect& t : theirs) {
            opencvFound += std::any_of(mine.begin(), mine.end(),
                                       [&](const Rect& m) { return sameRect(t, m); });
        }
        for (const Rect& m : mine) {
            oursFound += std::any_of(theirs.begin(), theirs.end(),
                                     [&](const cv::Rect& t) { return sameRect(t, m); });
        }
    }
    double recall() const { return opencv == 0 ? 1.0 : double(opencvFound) / double(opencv); }
    double precision() const { return ours == 0 ? 1.0 : double(oursFound) / double(ours); }
};

class FaceDetectorPeer : public ::testing::TestWithParam<const char*> {};

TEST_P(FaceDetectorPeer, SameWindowsAndBoxesAsOpenCvOnCmuMitImages)
{
    cv::setNumThreads(1);
    const std::vector<std::string> files = testImages();
    ASSERT_GE(files.size(), 40u);
    // A pixel budget keeps the test quick; MIRROR_PEER_FULL=1 runs all 76 images.
    const bool full = std::getenv("MIRROR_PEER_FULL") != nullptr;
    constexpr long kPixelBudget = 1'000'000;
    long pixels = 0;
    std::vector<cv::Mat> images;
    Size maxSize;
    for (const std::string& f : files) {
        cv::Mat m = cv::imread(f, cv::IMREAD_GRAYSCALE);
        ASSERT_FALSE(m.empty()) << f;
        if (!full && pixels + long(m.total()) > kPixelBudget)
            continue;
        pixels += long(m.total());
        maxSize.width = std::max(maxSize.width, m.cols);
        maxSize.height = std::max(maxSize.height, m.rows);
        images.push_back(m);
    }

    cv::CascadeClassifier theirs(GetParam());
    ASSERT_FALSE(theirs.empty());
    FaceDetectorOptions options;
    options.maxFrameSize = maxSize;
    options.scaleFactor = kScaleFactor;
    options.minNeighbors = 0;  // raw hits: every window decision (clipped like OpenCV's)
    options.minSize = {kMinSize, kMinSize};
    options.maxRawHits = 20000;
    options.maxFaces = 20000;
    const HaarCascade cascade = loadHaarCascade(GetParam());
    FaceDetector oursRaw(cascade, options);
    options.minNeighbors = kMinNeighbors;
    FaceDetector ours(cascade, options);

    Agreement raw;
    Agreement grouped;
    long imagesWithIdenticalRaw = 0;
    for (std::size_t i = 0; i < images.size(); ++i) {
        std::vector<cv::Rect> theirRaw;
        theirs.detectMultiScale(images[i], theirRaw, kScaleFactor, 0, 0,
                                cv::Size(kMinSize, kMinSize));
        ASSERT_GE(oursRaw.detect(viewOf(images[i])), 0) << oursRaw.lastError();
        ASSERT_FALSE(oursRaw.rawHitsOverflowed());
        const std::span<const Rect> ourRaw = oursRaw.faces();
        raw.add(theirRaw, ourRaw);
        // Same windows in the same order: the order decides how groups are numbered.
        bool identical = theirRaw.size() == ourRaw.size();
        for (std::size_t k = 0; identical && k < theirRaw.size(); ++k) {
            identical = sameRect(theirRaw[k], ourRaw[k]);
        }
        imagesWithIdenticalRaw += identical;

        std::vector<cv::Rect> theirFaces;
        theirs.detectMultiScale(images[i], theirFaces, kScaleFactor, kMinNeighbors, 0,
                                cv::Size(kMinSize, kMinSize));
        ASSERT_GE(ours.detect(viewOf(images[i])), 0);
        grouped.add(theirFaces, ours.faces());
        EXPECT_EQ(theirFaces.size(), ours.faces().size()) << files[i];
    }
    std::printf("[ peer ] %s on %zu CMU/MIT images (scale %.2f, minSize %d):\n", GetParam(),
                images.size(), kScaleFactor, kMinSize);
    std::printf(
        "[ peer ]   raw windows: opencv %ld, ours %ld, identical %.4f / %.4f, images "
        "with the identical raw list %ld\n",
        raw.opencv, raw.ours, raw.recall(), raw.precision(), imagesWithIdenticalRaw);
    std::printf(
        "[ peer ]   grouped (minNeighbors %d): opencv %ld, ours %ld, identical boxes "
        "%.4f of opencv's, %.4f of ours\n",
        kMinNeighbors, grouped.opencv, grouped.ours, grouped.recall(), grouped.precision());
    EXPECT_GE(raw.recall(), 0.99);
    EXPECT_GE(raw.precision(), 0.99);
    EXPECT_GE(grouped.recall(), 0.99);
    EXPECT_GE(grouped.precision(), 0.99);
}

INSTANTIATE_TEST_SUITE_P(Cascades, FaceDetectorPeer, ::testing::ValuesIn(kCascades));

TEST(FaceDetectorPeerSpeed, PrintsTimePer360x240Frame)
{
    cv::setNumThreads(1);
    const cv::Mat astronaut = cv::imread(
        testing_support::sharedData("debian_skimage_faces/astronaut.png"), cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(astronaut.empty());
    cv::Mat frame;
    cv::resize(astronaut(cv::Rect(0, 64, 512, 341)), frame, cv::Size(360, 240), 0, 0,
               cv::INTER_AREA);
    for (const char* path : kCascades) {
        cv::CascadeClassifier theirs(path);
        FaceDetectorOptions options;
        options.maxFrameSize = {360, 240};
        options.scaleFactor = kScaleFactor;
        options.minNeighbors = kMinNeighbors;
        options.minSize = {kMinSize, kMinSize};
        FaceDetector ours(loadHaarCascade(path), options);
        constexpr int kRuns = 8;
        std::vector<cv::Rect> theirFaces;
        int ourCount = 0;
        theirs.detectMultiScale(frame, theirFaces, kScaleFactor, kMinNeighbors, 0,
                                cv::Size(kMinSize, kMinSize));
        ourCount = ours.detect(viewOf(frame));
        const double t0 = threadCpuMs();
        for (int i = 0; i < kRuns; ++i) {
            theirs.detectMultiScale(frame, theirFaces, kScaleFactor, kMinNeighbors, 0,
                                    cv::Size(kMinSize, kMinSize));
        }
        const double t1 = threadCpuMs();
        for (int i = 0; i < kRuns; ++i)
            ourCount = ours.detect(viewOf(frame));
        const double t2 = threadCpuMs();
        const double theirMs = (t1 - t0) / kRuns;
        const double ourMs = (t2 - t1) / kRuns;
        std::printf(
            "[ peer ] 360x240 %s (thread CPU time): opencv %.2f ms (%zu faces), ours %.2f ms (%d "
            "faces), "
            "speed-up %.2fx, %ld windows evaluated\n",
            std::filesystem::path(path).filename().c_str(), theirMs, theirFaces.size(), ourMs,
            ourCount, theirMs / ourMs, ours.windowsEvaluated());
        EXPECT_EQ(theirFaces.size(), static_cast<std::size_t>(ourCount));
    }
}

}  // namespace
