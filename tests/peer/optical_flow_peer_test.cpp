// Corner tracking beside its peer on real frames of the FGNet talking face: our Shi-Tomasi corners
// against cv::goodFeaturesToTrack, our pyramidal Lucas-Kanade against cv::calcOpticalFlowPyrLK
// with the same window, levels and stopping rule on the same points, and the time of a 50-point,
// 3-level track including the pyramid of the new frame (printed, never asserted).
#include "test_paths.hpp"
#include "vision/corner_detector.hpp"
#include "vision/image_pyramid.hpp"
#include "vision/optical_flow.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <string>
#include <vector>

using vision::Point2f;

namespace {

constexpr int kFrames = 6;
constexpr int kWindow = 15;
constexpr int kLevels = 3;  // level 0 and two halvings: OpenCV's maxLevel 2

std::string frameName(int i, const char* ext)
{
    char name[64];
    std::snprintf(name, sizeof name, "franck_%05d.%s", i, ext);
    return name;
}

cv::Mat loadGray(int i)
{
    const std::string path =
        testing_support::sharedData("fgnet_talking_face/images/" + frameName(i, "jpg"));
    cv::Mat img = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (img.empty())
        ADD_FAILURE() << "cannot read " << path;
    return img;
}

// The face box: the bounding box of the frame's 68 annotated landmarks.
cv::Rect faceBox(int i)
{
    std::ifstream in(
        testing_support::sharedData("fgnet_talking_face/points/" + frameName(i, "pts")));
    std::string line;
    float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
    while (std::getline(in, line)) {
        float x, y;
        if (std::sscanf(line.c_str(), "%f %f", &x, &y) == 2) {
            x0 = std::min(x0, x);
            y0 = std::min(y0, y);
            x1 = std::max(x1, x);
            y1 = std::max(y1, y);
        }
    }
    return {int(x0), int(y0), int(x1 - x0), int(y1 - y0)};
}

vision::ConstImageView view(const cv::Mat& m)
{
    return {m.data, m.cols, m.rows, int(m.step), vision::PixelFormat::Gray8};
}

double percentile(std::vector<double> v, double q)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

}  // namespace

TEST(OpticalFlowPeer, CornersAreLikeGoodFeaturesToTrack)
{
    int ours = 0, near = 0;
    for (int f = 0; f < kFrames; ++f) {
        const cv::Mat img = loadGray(f);
        ASSERT_FALSE(img.empty());
        const cv::Rect box = faceBox(f);
        const float minDistance = float(box.width) / 12.f;  // proportional to the face size
        cv::Mat mask = cv::Mat::zeros(img.size(), CV_8U);
        mask(box).setTo(255);
        std::vector<cv::Point2f> theirs;
        cv::goodFeaturesToTrack(img, theirs, 30, 0.01, minDistance, mask, 3, false);

        vision::CornerDetector det(
            {img.cols, img.rows},
            {.maxCorners = 30, .qualityLevel = 0.01f, .minDistance = minDistance});
        vision::Corner c[30];
        const int n = det.detect(view(img), {box.x, box.y, box.width, box.height}, c, 30);
        for (int i = 0; i < n; ++i) {
            double best = 1e9;
            for (const auto& t : theirs)
                best = std::min<double>(best,
                                        std::hypot(t.x - c[i].position.x, t.y - c[i].position.y));
            near += best <= 2.0;
        }
        ours += n;
        std::printf("frame %d: box %dx%d, ours %d corners, OpenCV %zu\n", f, box.width, box.height,
                    n, theirs.size());
    }
    const double fraction = double(near) / std::max(ours, 1);
    std::printf("corners: %d of ours, %.1f%% within 2 px of one of OpenCV's\n", ours,
                100.0 * fraction);
    EXPECT_GE(ours, kFrames * 20);
    EXPECT_GE(fraction, 0.75);
}

TEST(OpticalFlowPeer, FlowMatchesCalcOpticalFlowPyrLK)
{
    std::vector<cv::Mat> frames;
    for (int f = 0; f < kFrames; ++f) {
        frames.push_back(loadGray(f));
        ASSERT_FALSE(frames.back().empty());
    }
    const cv::Size size = frames[0].size();
    vision::ImagePyramid prev({size.width, size.height}, kLevels);
    vision::ImagePyramid next({size.width, size.height}, kLevels);
    vision::OpticalFlowOptions opt;
    opt.window = kWindow;
    opt.maxLevel = kLevels - 1;
    opt.maxIterations = 30;
    opt.epsilon = 0.01f;
    opt.fbThreshold = 0.f;  // the peer has no forward-backward check: compare raw tracks
    vision::PyramidalLucasKanade lk(opt);
    const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);

    std::vector<double> diffs;
    int bothTracked = 0, oursOnly = 0, theirsOnly = 0;
    for (int f = 0; f + 1 < kFrames; ++f) {
        const cv::Rect box = faceBox(f);
        cv::Mat mask = cv::Mat::zeros(size, CV_8U);
        mask(box).setTo(255);
        std::vector<cv::Point2f> pts;
        cv::goodFeaturesToTrack(frames[f], pts, 50, 0.01, 5.0, mask, 3, false);
        std::vector<cv::Point2f> cvOut;
        std::vector<std::uint8_t> cvStatus;
        std::vector<float> cvErr;
        cv::calcOpticalFlowPyrLK(frames[f], frames[f + 1], pts, cvOut, cvStatus, cvErr,
                                 cv::Size(kWindow, kWindow), kLevels - 1, criteria);

        ASSERT_TRUE(prev.build(view(frames[f])));
        ASSERT_TRUE(next.build(view(frames[f + 1])));
        const int n = int(pts.size());
        std::vector<Point2f> from(n), to(n);
        std::vector<vision::FlowStatus> st(n);
        for (int i = 0; i < n; ++i)
            from[i] = {pts[i].x, pts[i].y};
        lk.track(prev, next, from.data(), to.data(), st.data(), n);
        for (int i = 0; i < n; ++i) {
            const bool oursOk = st[i] == vision::FlowStatus::Tracked;
            if (oursOk && cvStatus[i]) {
                ++bothTracked;
                diffs.push_back(std::hypot(to[i].x - cvOut[i].x, to[i].y - cvOut[i].y));
            } else {
                oursOnly += oursOk;
                theirsOnly += cvStatus[i] != 0;
            }
        }
    }
    const double median = percentile(diffs, 0.5);
    const double within =
        double(std::count_if(diffs.begin(), diffs.end(), [](double d) { return d <= 0.5; })) /
        double(std::max<std::size_t>(diffs.size(), 1));
    std::printf(
        "flow: %d points tracked by both (%d only ours, %d only OpenCV); difference "
        "median %.4f px, p90 %.4f px, max %.4f px, %.1f%% within 0.5 px\n",
        bothTracked, oursOnly, theirsOnly, median, percentile(diffs, 0.9), percentile(diffs, 1.0),
        100.0 * within);
    EXPECT_GE(bothTracked, 100);
    EXPECT_LE(oursOnly + theirsOnly, bothTracked / 10);
    EXPECT_LT(median, 0.2);
    EXPECT_GE(within, 0.9);
}

// 50 points, 3 levels, the new frame's pyramid built each time (the previous one is kept from the
// frame before, as a tracker does): ours against buildOpticalFlowPyramid + calcOpticalFlowPyrLK,
// one thread. Printed only; meaningful in a Release build.
TEST(OpticalFlowPeer, TimeOfFiftyPointsThreeLevels)
{
    const cv::Mat a = loadGray(0);
    const cv::Mat b = loadGray(1);
    ASSERT_FALSE(a.empty());
    ASSERT_FALSE(b.empty());
    cv::setNumThreads(1);
    const cv::Rect box = faceBox(0);
    cv::Mat mask = cv::Mat::zeros(a.size(), CV_8U);
    mask(box).setTo(255);
    std::vector<cv::Point2f> pts;
    cv::goodFeaturesToTrack(a, pts, 50, 0.01, 3.0, mask, 3, false);
    ASSERT_EQ(pts.size(), 50u);
    const cv::Size win(kWindow, kWindow);
    const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
    constexpr int kRuns = 30;
    using Clock = std::chrono::steady_clock;
    auto perRunUs = [](Clock::time_point t0) {
        return std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / kRuns;
    };

    std::vector<cv::Mat> cvPrev, cvNext;
    cv::buildOpticalFlowPyramid(a, cvPrev, win, kLevels - 1);
    std::vector<cv::Point2f> cvOut;
    std::vector<std::uint8_t> cvStatus;
    std::vector<float> cvErr;

    vision::ImagePyramid prev({a.cols, a.rows}, kLevels), next({a.cols, a.rows}, kLevels);
    ASSERT_TRUE(prev.build(view(a)));
    Point2f from[50], to[50];
    vision::FlowStatus st[50];
    for (int i = 0; i < 50; ++i)
        from[i] = {pts[i].x, pts[i].y};
    vision::OpticalFlowOptions opt;
    opt.maxLevel = kLevels - 1;
    opt.fbThreshold = 0.f;
    vision::PyramidalLucasKanade lk(opt);
    opt.fbThreshold = 1.f;
    vision::PyramidalLucasKanade lkFb(opt);
    int tracked = 0;

    // Best of three interleaved trials each: the machine may be shared.
    double cvUs = 1e30, oursUs = 1e30, oursFbUs = 1e30, pyrUs = 1e30;
    for (int trial = 0; trial < 3; ++trial) {
        auto t0 = Clock::now();
        for (int r = 0; r < kRuns; ++r) {
            cv::buildOpticalFlowPyramid(b, cvNext, win, kLevels - 1);
            cv::calcOpticalFlowPyrLK(cvPrev, cvNext, pts, cvOut, cvStatus, cvErr, win, kLevels - 1,
                                     criteria);
        }
        cvUs = std::min(cvUs, perRunUs(t0));

        t0 = Clock::now();
        for (int r = 0; r < kRuns; ++r) {
            next.build(view(b));
            tracked = lk.track(prev, next, from, to, st, 50);
        }
        oursUs = std::min(oursUs, perRunUs(t0));

        t0 = Clock::now();
        for (int r = 0; r < kRuns; ++r) {
            next.build(view(b));
            lkFb.track(prev, next, from, to, st, 50);
        }
        oursFbUs = std::min(oursFbUs, perRunUs(t0));

        t0 = Clock::now();
        for (int r = 0; r < kRuns; ++r)
            next.build(view(b));
        pyrUs = std::min(pyrUs, perRunUs(t0));
    }

    std::printf(
        "LK 50 points, %d levels, %dx%d, one thread: OpenCV %.0f us, ours %.0f us "
        "(pyramid %.0f us), speed-up %.2fx; ours with forward-backward check %.0f us\n",
        kLevels, a.cols, a.rows, cvUs, oursUs, pyrUs, cvUs / oursUs, oursFbUs);
    EXPECT_GT(tracked, 40);
}
