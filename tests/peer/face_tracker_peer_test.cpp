// The face pipeline of fig. 89 (MotionStage + FaceStage) on the FGNet talking face, the real
// video with 68 landmarks per frame: one person, talking, moving the head. The face must be found
// within the first frames and then shown in every frame, on the landmarks, with no phantom face.
#include "test_paths.hpp"
#include "vision/face_stage.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/motion_stage.hpp"

#include <gtest/gtest.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

using namespace vision;
using testing_support::sharedData;

namespace {

const char* kCascade = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";

double cpuMs()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

std::string framePath(int i)
{
    char name[64];
    std::snprintf(name, sizeof name, "franck_%05d", i);
    return sharedData("fgnet_talking_face/images/") + name + ".jpg";
}

/// Bounding box of the 68 landmarks of frame i, and the roll of the line between the eye centres
/// (points 31 and 36 of FGNet's markup) in degrees, clockwise on screen positive.
bool landmarkBox(int i, float& x0, float& y0, float& x1, float& y1, float& roll)
{
    char name[64];
    std::snprintf(name, sizeof name, "franck_%05d.pts", i);
    std::ifstream in(sharedData("fgnet_talking_face/points/") + name);
    std::string line;
    while (std::getline(in, line) && line != "{") {
    }
    x0 = y0 = 1e9f;
    x1 = y1 = -1e9f;
    float x = 0, y = 0;
    float ex[2] = {}, ey[2] = {};
    int n = 0;
    while (in >> x >> y) {
        if (n == 31 || n == 36) {
            ex[n == 36] = x;
            ey[n == 36] = y;
        }
        x0 = std::min(x0, x);
        y0 = std::min(y0, y);
        x1 = std::max(x1, x);
        y1 = std::max(y1, y);
        ++n;
    }
    roll = std::atan2(ey[1] - ey[0], ex[1] - ex[0]) * 57.29578f;
    return n == 68;
}

struct RunStats {
    int counted = 0, shownFrames = 0, phantomFrames = 0, offFace = 0, idChanges = 0;
    long maxWindows = 0;         ///< most windows of a frame after the first
    long firstFrameWindows = 0;  ///< the cold start's whole-image scans
};

RunStats runOnFgnet(const FaceTrackerOptions& options)
{
    RunStats r;
    const HaarCascade cascade = loadHaarCascade(kCascade);
    MotionStage motion({720, 576}, MotionStageOptions{});
    FaceStage faces(motion, cascade, options);

    // 250 frames keep the test quick; MIRROR_FGNET_FRAMES=1000 runs the whole sequence.
    const char* env = std::getenv("MIRROR_FGNET_FRAMES");
    const int frames = env ? std::clamp(std::atoi(env), 20, 1000) : 250;
    const int warmup = 15;
    int firstId = 0;
    std::vector<double> times;
    double rollError = 0;
    int rollCount = 0;
    for (int i = 0; i < frames; ++i) {
        cv::Mat bgr = cv::imread(framePath(i), cv::IMREAD_COLOR);
        if (bgr.empty()) {
            ADD_FAILURE() << "cannot read " << framePath(i);
            return r;
        }
        FrameState state;
        state.frame.image = ConstImageView{bgr.data, bgr.cols, bgr.rows, static_cast<int>(bgr.step),
                                           PixelFormat::BGR24};
        const double t0 = cpuMs();
        motion.process(state);
        faces.process(state);
        times.push_back(cpuMs() - t0);
        if (i == 0)
            r.firstFrameWindows = faces.tracker().windowsEvaluated();
        else
            r.maxWindows = std::max(r.maxWindows, faces.tracker().windowsEvaluated());
        if (i < warmup)
            continue;
        ++r.counted;
        float x0, y0, x1, y1, roll;
        if (!landmarkBox(i, x0, y0, x1, y1, roll)) {
            ADD_FAILURE() << "no landmarks for frame " << i;
            return r;
        }
        int shown = 0;
        for (const TrackedFace& f : state.faces) {
            if (!f.shown())
                continue;
            ++shown;
            if (firstId == 0)
                firstId = f.id;
            else if (f.id != firstId) {
                ++r.idChanges;
                firstId = f.id;
            }
            rollError += std::fabs(f.rollDegrees - roll);
            ++rollCount;
            if (f.centre.x < x0 || f.centre.x > x1 || f.centre.y < y0 || f.centre.y > y1)
                ++r.offFace;
        }
        r.shownFrames += shown >= 1;
        r.phantomFrames += shown > 1;
    }
    std::sort(times.begin(), times.end());
    double mean = 0;
    for (double t : times)
        mean += t / static_cast<double>(times.size());
    // Information only (timing is the benchmark's job): CPU ms of motion + faces per frame.
    std::printf(
        "fgnet: frames=%d shown=%d phantom=%d off_face=%d id_changes=%d cpu_ms mean=%.2f "
        "p99=%.2f max=%.2f roll_err_deg=%.2f max_windows=%ld\n",
        r.counted, r.shownFrames, r.phantomFrames, r.offFace, r.idChanges, mean,
        times[times.size() * 99 / 100], times.back(), rollError / std::max(1, rollCount),
        r.maxWindows);
    return r;
}

void expectTracked(const RunStats& r)
{
    EXPECT_GE(r.shownFrames, r.counted * 99 / 100);
    EXPECT_EQ(r.phantomFrames, 0);
    EXPECT_EQ(r.offFace, 0);
    EXPECT_LE(r.idChanges, 1);
}

}  // namespace

TEST(FaceTrackerPeer, FollowsTheTalkingFaceWithoutPhantoms)
{
    expectTracked(runOnFgnet(FaceTrackerOptions{}));
}

TEST(FaceTrackerPeer, ADetectionBudgetSpreadsTheScanAndStillFollowsTheFace)
{
    // A budget far below a full masked scan of the first frames (about 20k windows at 360x288):
    // each frame evaluates at most that many scan windows (plus the small verification scans).
    FaceTrackerOptions options;
    options.detectionWindowBudget = 3000;
    const RunStats r = runOnFgnet(options);
    expectTracked(r);
    EXPECT_LE(r.maxWindows, 3000 + 4000) << "scan budget plus one verification scan";
    // The first frame scans the whole image, upright and turned both ways, whatever the budget:
    // the faces in view at start are all found at once (a one-frame stall at start).
    EXPECT_GT(r.firstFrameWindows, 20 * 3000);
}

namespace {

struct TiltRun {
    int firstShown = -1;   ///< frame the face was first shown, -1: never
    double rollError = 0;  ///< mean |roll - (eye roll + tilt)| over the shown frames
    int shown = 0, offFace = 0, phantom = 0;
};

/// The talking face at half size, sliding over a plain frame and turned by `tiltDegrees`
/// (clockwise on screen) about the frame centre from the first frame on: a face that enters
/// tilted beyond the upright cascade's reach. Negative tilts mirror the face first (its own
/// roll of about -6 degrees then adds to the tilt's magnitude the same way).
TiltRun runTilted(const FaceTrackerOptions& options, float tiltDegrees, int frames)
{
    TiltRun r;
    const HaarCascade cascade = loadHaarCascade(kCascade);
    MotionStage motion({720, 576}, MotionStageOptions{});
    FaceStage faces(motion, cascade, options);
    // cv's angle is counter-clockwise on screen.
    const cv::Mat turn = cv::getRotationMatrix2D(cv::Point2f(360.f, 288.f), -tiltDegrees, 1.0);
    for (int i = 0; i < frames; ++i) {
        const cv::Mat bgr = cv::imread(framePath(i), cv::IMREAD_COLOR);
        if (bgr.empty()) {
            ADD_FAILURE() << "cannot read " << framePath(i);
            return r;
        }
        cv::Mat small;
        cv::resize(bgr, small, cv::Size(360, 288), 0, 0, cv::INTER_AREA);
        cv::Mat scene(576, 720, CV_8UC3, cv::Scalar(120, 128, 136));
        const int ox = 120 + 2 * i, oy = 140 + i;
        small.copyTo(scene(cv::Rect(ox, oy, 360, 288)));
        const bool mirror = tiltDegrees < 0.f;
        if (mirror)
            cv::flip(scene, scene, 1);
        cv::Mat turned;
        cv::warpAffine(scene, turned, turn, scene.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
        FrameState state;
        state.frame.image = ConstImageView{turned.data, turned.cols, turned.rows,
                                           static_cast<int>(turned.step), PixelFormat::BGR24};
        motion.process(state);
        faces.process(state);
        float x0, y0, x1, y1, roll;
        if (!landmarkBox(i, x0, y0, x1, y1, roll)) {
            ADD_FAILURE() << "no landmarks for frame " << i;
            return r;
        }
        // The landmarks' centre, turned with the frame.
        double cx = 0.25 * (x0 + x1) + ox;
        const double cy = 0.25 * (y0 + y1) + oy;
        if (mirror) {
            cx = 719.0 - cx;
            roll = -roll;
        }
        const double tx =
            turn.at<double>(0, 0) * cx + turn.at<double>(0, 1) * cy + turn.at<double>(0, 2);
        const double ty =
            turn.at<double>(1, 0) * cx + turn.at<double>(1, 1) * cy + turn.at<double>(1, 2);
        int shown = 0;
        for (const TrackedFace& f : state.faces) {
            if (!f.shown())
                continue;
            ++shown;
            if (r.firstShown < 0)
                r.firstShown = i;
            r.rollError += std::fabs(f.rollDegrees - (roll + tiltDegrees));
            r.offFace += std::hypot(f.centre.x - tx, f.centre.y - ty) > 0.25 * f.size;
        }
        r.shown += shown >= 1;
        r.phantom += shown > 1;
    }
    r.rollError /= std::max(1, r.shown);
    std::printf(
        "tilted %.0f: first_shown=%d shown=%d/%d off_face=%d phantom=%d "
        "roll_err_deg=%.2f\n",
        static_cast<double>(tiltDegrees), r.firstShown, r.shown, frames, r.offFace, r.phantom,
        r.rollError);
    return r;
}

}  // namespace

TEST(FaceTrackerPeer, FindsAFaceThatEntersTiltedBeyondTheUprightCascade)
{
    // Upright scans alone find this face only once it happens to turn upright enough, if ever;
    // the tilted scans of the moving region find it within the first frames, with its roll.
    constexpr int kFrames = 30;
    FaceTrackerOptions upright;
    upright.tiltScanDegrees = 0.f;
    for (const float tilt : {35.f, -35.f}) {
        const TiltRun without = runTilted(upright, tilt, kFrames);
        const TiltRun with = runTilted(FaceTrackerOptions{}, tilt, kFrames);
        ASSERT_GE(with.firstShown, 0) << tilt;
        EXPECT_LE(with.firstShown, 10) << tilt;
        EXPECT_GE(with.shown, kFrames / 2) << tilt;
        EXPECT_GT(with.shown, without.shown + 10) << tilt;
        EXPECT_EQ(with.offFace, 0) << tilt;
        EXPECT_EQ(with.phantom, 0) << tilt;
        EXPECT_LT(with.rollError, 8.0) << tilt;
    }
}

namespace {

struct TwoFaceRun {
    int firstShown = -1;   ///< first frame the moving face was shown, -1: never
    int shownFrames = 0;   ///< frames it was shown in
    int photoShown = 0;    ///< frames a face was shown on the still photo
    int coveredShown = 0;  ///< of the covered frames, those it was shown in
};

/// Two faces in view from the first frame, at 0.45 scale on a plain frame: on the left a still
/// photo (FGNet frame 0, never changing), on the right the talking face sliding back and forth
/// by 10 px. Frames [coverFrom, coverTo) cover the moving face from the eyebrows down
/// with a grey card (the cascade no longer finds it, the corners above still move together).
TwoFaceRun runTwoFaces(const FaceTrackerOptions& options, int frames, int coverFrom, int coverTo)
{
    TwoFaceRun r;
    constexpr double kScale = 0.45;
    const HaarCascade cascade = loadHaarCascade(kCascade);
    MotionStage motion({720, 576}, MotionStageOptions{});
    FaceStage faces(motion, cascade, options);
    cv::Mat photo;
    cv::resize(cv::imread(framePath(0), cv::IMREAD_COLOR), photo, cv::Size(), kScale, kScale,
               cv::INTER_AREA);
    for (int i = 0; i < frames; ++i) {
        cv::Mat bgr = cv::imread(framePath(i), cv::IMREAD_COLOR);
        float x0, y0, x1, y1, roll;
        if (bgr.empty() || photo.empty() || !landmarkBox(i, x0, y0, x1, y1, roll)) {
            ADD_FAILURE() << "cannot read FGNet frame " << i;
            return r;
        }
        cv::Mat small;
        cv::resize(bgr, small, photo.size(), 0, 0, cv::INTER_AREA);
        cv::Mat scene(576, 720, CV_8UC3, cv::Scalar(120, 128, 136));
        photo.copyTo(scene(cv::Rect(10, 150, photo.cols, photo.rows)));
        const int phase = i % 20;
        const int ox = 375 + (phase < 10 ? phase : 20 - phase), oy = 150;
        small.copyTo(scene(cv::Rect(ox, oy, small.cols, small.rows)));
        const double cx = ox + kScale * 0.5 * (x0 + x1);
        const double cy = oy + kScale * 0.5 * (y0 + y1);
        const bool covered = i >= coverFrom && i < coverTo;
        if (covered)
            cv::rectangle(scene,
                          cv::Rect(static_cast<int>(ox + kScale * x0) - 5,
                                   static_cast<int>(oy + kScale * (y0 + 0.2f * (y1 - y0))),
                                   static_cast<int>(kScale * (x1 - x0)) + 10,
                                   static_cast<int>(kScale * (y1 - y0)) + 10),
                          cv::Scalar(90, 90, 90), cv::FILLED);
        FrameState state;
        state.frame.image = ConstImageView{scene.data, scene.cols, scene.rows,
                                           static_cast<int>(scene.step), PixelFormat::BGR24};
        motion.process(state);
        faces.process(state);
        bool onMoving = false;
        for (const TrackedFace& f : state.faces) {
            if (!f.shown())
                continue;
            if (f.centre.x < 360.f)
                ++r.photoShown;
            else if (std::hypot(f.centre.x - cx, f.centre.y - cy) < 0.5 * f.size)
                onMoving = true;
        }
        if (onMoving && r.firstShown < 0)
            r.firstShown = i;
        r.shownFrames += onMoving;
        r.coveredShown += onMoving && covered;
    }
    std::printf("two faces: first_shown=%d shown=%d/%d photo_shown=%d covered_shown=%d/%d\n",
                r.firstShown, r.shownFrames, frames, r.photoShown, r.coveredShown,
                coverTo - coverFrom);
    return r;
}

}  // namespace

TEST(FaceTrackerPeer, FacesInViewAtStartAreFoundAtOnceAndAStillPhotoIsNeverShown)
{
    // Nothing moves yet in the first frame: the whole image is scanned then, whatever the
    // window budget, and the static rule tells the person from the photo within a few frames.
    FaceTrackerOptions shipped;
    shipped.detectionWindowBudget = 5000;
    for (const FaceTrackerOptions& options : {FaceTrackerOptions{}, shipped}) {
        const TwoFaceRun r = runTwoFaces(options, 60, 0, 0);
        ASSERT_GE(r.firstShown, 0);
        EXPECT_LE(r.firstShown, 4);
        EXPECT_GE(r.shownFrames, 60 - 5);
        EXPECT_EQ(r.photoShown, 0);
    }
}

TEST(FaceTrackerPeer, ACoveredFaceKeepsItsPlaceWhileItsCornersMoveTogether)
{
    // Covered from the eyebrows down for 20 frames: the cascade misses it (with the grace of
    // fig. 89 alone it is dropped), the corners on the forehead and hair keep moving as one.
    FaceTrackerOptions figure89;
    figure89.occludedGraceFrames = figure89.graceFrames;
    const TwoFaceRun plain = runTwoFaces(figure89, 60, 20, 40);
    const TwoFaceRun held = runTwoFaces(FaceTrackerOptions{}, 60, 20, 40);
    EXPECT_LT(plain.coveredShown, 20) << "the card must defeat the cascade";
    EXPECT_EQ(held.coveredShown, 20);
    EXPECT_EQ(held.photoShown, 0);
}

TEST(FaceTrackerPeer, RejectsAWrongImageAndKeepsItsTracks)
{
    const HaarCascade cascade = loadHaarCascade(kCascade);
    FaceTrackerOptions options;
    options.imageSize = {360, 288};
    FaceTracker tracker(cascade, options);
    std::uint8_t pixels[16] = {};
    const ConstImageView tiny{pixels, 4, 4, 4, PixelFormat::Gray8};
    EXPECT_FALSE(tracker.process(tiny, ConstImageView{}));
    EXPECT_NE(std::string(tracker.lastError()), "");
    EXPECT_TRUE(tracker.faces().empty());
}
