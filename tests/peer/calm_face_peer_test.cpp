// A person standing calmly in front of the mirror and a photograph on the wall, on real frames:
// the FGNet talking face from a cold start at frames where the head hardly moves (the static-face
// rule alone kept it hidden for up to 15 frames), and FGNet frames held still under camera
// noise, a changing light and JPEG, as a print seen by a camera is. The person is shown within
// the first frames, the print never (METHOD.md §3, "Detection"; LivenessCue). Both at the
// recording's 720x576 and at 360x288 with strong JPEG, as its 360x288 video has them.
#include "face_match.hpp"
#include "face_truth.hpp"
#include "test_paths.hpp"
#include "vision/face_stage.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/motion_stage.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

using namespace vision;
using testing_support::sharedData;

namespace {

const char* kCascade = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";

std::string fgnet(const char* folder, int i, const char* ext)
{
    char name[64];
    std::snprintf(name, sizeof name, "%s/franck_%05d.%s", folder, i, ext);
    return sharedData("fgnet_talking_face/") + name;
}

/// The frame as a camera of `size` gives it: shrunk (when smaller) and JPEG-coded at `quality`
/// (100: as recorded).
cv::Mat asCamera(const cv::Mat& bgr, cv::Size size, int quality)
{
    cv::Mat out = bgr;
    if (size != bgr.size())
        cv::resize(bgr, out, size, 0, 0, cv::INTER_AREA);
    if (quality >= 100)
        return out;
    std::vector<std::uint8_t> jpeg;
    cv::imencode(".jpg", out, jpeg, {cv::IMWRITE_JPEG_QUALITY, quality});
    return cv::imdecode(jpeg, cv::IMREAD_COLOR);
}

struct Camera {
    cv::Size size;
    int quality;
};

const Camera kRecording{{720, 576}, 100};
const Camera kSmallVideo{{360, 288}, 60};

FaceTrackerOptions shipped(bool sway)
{
    FaceTrackerOptions o;
    o.detectionWindowBudget = 5000;  // faces.detection_window_budget
    o.livenessBySway = sway;
    return o;
}

/// The first frame (from 0) of the run in which a face is shown on the person, -1: never in
/// `frames`; `phantoms` counts shown faces off the person.
int firstShown(int start, int frames, const Camera& camera, bool sway, int& phantoms)
{
    const HaarCascade cascade = loadHaarCascade(kCascade);
    MotionStage motion({camera.size.width, camera.size.height}, MotionStageOptions{});
    FaceStage faces(motion, cascade, shipped(sway));
    const float scale = static_cast<float>(camera.size.width) / 720.f;
    phantoms = 0;
    for (int k = 0; k < frames; ++k) {
        const cv::Mat bgr =
            asCamera(cv::imread(fgnet("images", start + k, "jpg")), camera.size, camera.quality);
        EXPECT_FALSE(bgr.empty()) << start + k;
        if (bgr.empty())
            return -1;
        FrameState state;
        state.frame.image = ConstImageView{bgr.data, bgr.cols, bgr.rows, static_cast<int>(bgr.step),
                                           PixelFormat::BGR24};
        motion.process(state);
        faces.process(state);
        const mirror_eval::BoxF box =
            mirror_eval::boundingBox(mirror_eval::loadPts(fgnet("points", start + k, "pts")));
        bool onPerson = false;
        for (const TrackedFace& f : state.faces) {
            if (!f.shown())
                continue;
            const float x = f.centre.x / scale, y = f.centre.y / scale;
            const bool inside =
                x >= box.x && y >= box.y && x <= box.x + box.width && y <= box.y + box.height;
            onPerson = onPerson || inside;
            phantoms += !inside;
        }
        if (onPerson)
            return k;
    }
    return -1;
}

/// Frames (of `frames`) in which any face was shown on FGNet frame `still` held still as a
/// print: per frame Gaussian camera noise, the light's gain and a left-right gradient drifting,
/// then the camera's coding. `tracked`: frames in which the tracker followed a face at all.
int printShown(int still, int frames, const Camera& camera, std::uint64_t seed, int& tracked)
{
    const HaarCascade cascade = loadHaarCascade(kCascade);
    MotionStage motion({camera.size.width, camera.size.height}, MotionStageOptions{});
    FaceStage faces(motion, cascade, shipped(true));
    cv::Mat print;
    cv::imread(fgnet("images", still, "jpg")).convertTo(print, CV_32FC3);
    EXPECT_FALSE(print.empty());
    cv::RNG rng(seed);
    cv::Mat ramp(print.size(), CV_32FC3), noise(print.size(), CV_32FC3), lit;
    for (int x = 0; x < print.cols; ++x)
        ramp.col(x).setTo(cv::Scalar::all(2.0 * x / (print.cols - 1) - 1.0));
    int shown = 0;
    tracked = 0;
    for (int k = 0; k < frames; ++k) {
        const double u = static_cast<double>(k) / frames;
        const double gain = 1.0 + 0.04 * std::sin(6.283 * 0.7 * u);
        const double gradient = 0.03 * std::sin(6.283 * 0.5 * u + 1.0);
        rng.fill(noise, cv::RNG::NORMAL, 0.0, 4.0);
        lit = print.mul(gain + gradient * ramp) + noise;
        cv::Mat bgr8;
        lit.convertTo(bgr8, CV_8UC3);
        const cv::Mat bgr = asCamera(bgr8, camera.size, std::min(camera.quality, 80));
        FrameState state;
        state.frame.image = ConstImageView{bgr.data, bgr.cols, bgr.rows, static_cast<int>(bgr.step),
                                           PixelFormat::BGR24};
        motion.process(state);
        faces.process(state);
        for (const TrackedFace& f : state.faces)
            shown += f.shown();
        tracked += !state.faces.empty();
    }
    return shown;
}

}  // namespace

TEST(CalmFacePeer, ACalmPersonIsShownWithinTheFirstFramesOfAColdStart)
{
    // Cold starts where the head hardly moves: the static-face rule alone waited for it to move
    // by 1.5% of its size (measured: 7-15 frames from these starts, with the shipped budget).
    int slowest = 0;
    for (const int start : {150, 333, 500, 777}) {
        int phantoms = 0;
        const int before = firstShown(start, 30, kRecording, false, phantoms);
        slowest = std::max(slowest, before < 0 ? 30 : before);
        for (const Camera& camera : {kRecording, kSmallVideo}) {
            const int after = firstShown(start, 30, camera, true, phantoms);
            std::printf("calm face from frame %d at %dx%d: shown at frame %d (%d without sway)\n",
                        start, camera.size.width, camera.size.height, after, before);
            EXPECT_GE(after, 1) << start;  // confirmFrames: two frames in a row
            EXPECT_LE(after, 12) << start << " at " << camera.size.width;  // half a second
            EXPECT_EQ(phantoms, 0) << start;
        }
    }
    EXPECT_GT(slowest, 12) << "these starts no longer show what the sway is needed for";
}

TEST(CalmFacePeer, APhotographHeldStillIsNeverShown)
{
    // 150 frames: the cold start's whole-image scan finds the print, the tracker follows it,
    // not shown, until it is dropped for never moving (after 2 x confirmMotionFrames), and the
    // still region is not scanned again.
    for (const Camera& camera : {kRecording, kSmallVideo}) {
        for (const int still : {0, 640}) {
            int tracked = 0;
            const int shown =
                printShown(still, 150, camera, 7 + static_cast<std::uint64_t>(still), tracked);
            std::printf("print of frame %d at %dx%d: tracked in %d frames, shown in %d\n", still,
                        camera.size.width, camera.size.height, tracked, shown);
            EXPECT_EQ(shown, 0) << "frame " << still << " at " << camera.size.width;
            EXPECT_GE(tracked, 60) << "the print must be found for the rule to be tested";
        }
    }
}
