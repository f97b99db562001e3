// facegen: a short sequence is written completely, its truth lines are well formed and within the
// scenario's limits, the same seed gives the same bytes, and the truth's box is the cascade's.

#include "compositor.hpp"
#include "face_photo.hpp"
#include "scenarios.hpp"
#include "sequence_writer.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using facegen::FaceState;
using testing_support::freshOutputDir;
using testing_support::sharedData;

constexpr int kFrames = 10;

facegen::GenerateOptions options(const std::string& scenario, const std::string& out,
                                 std::uint32_t seed)
{
    facegen::GenerateOptions o;
    o.scenario = scenario;
    o.outDir = out;
    o.frames = kFrames;
    o.seed = seed;
    o.dataDir = sharedData("");
    o.cascadePath = facegen::kDefaultCascade;
    return o;
}

std::string slurp(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<FaceState> readTruth(const fs::path& path)
{
    std::ifstream in(path);
    EXPECT_TRUE(in.good()) << path;
    std::vector<FaceState> faces;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        FaceState f;
        int moving = -1;
        std::string rest;
        EXPECT_TRUE(s >> f.id >> f.cx >> f.cy >> f.size >> f.rollDeg >> moving) << line;
        EXPECT_FALSE(s >> rest) << "more than 6 fields: " << line;
        EXPECT_TRUE(moving == 0 || moving == 1) << line;
        f.moving = moving == 1;
        faces.push_back(f);
    }
    return faces;
}

TEST(Facegen, ScenariosAreKnownAndBadArgumentsRejected)
{
    for (const char* name : {"one", "two", "three", "four", "enter-leave", "rotate"})
        EXPECT_NE(facegen::findScenario(name), nullptr) << name;
    EXPECT_EQ(facegen::findScenario("all"), nullptr);  // 'all' is the tool's, not a scenario
    const std::vector<std::string> sources(60, "x/01-1m.asf");
    EXPECT_THROW(facegen::Scenario("nope", {640, 480}, 10, 1, sources, {}), std::runtime_error);
    EXPECT_THROW(facegen::Scenario("one", {640, 480}, 1, 1, sources, {}), std::runtime_error);
    EXPECT_THROW(facegen::Scenario("one", {100, 80}, 10, 1, sources, {}), std::runtime_error);
    facegen::GenerateOptions o = options("one", freshOutputDir("facegen_bad"), 1);
    o.dataDir = "/nonexistent";
    EXPECT_THROW(facegen::generateSequence(o), std::runtime_error);
}

TEST(Facegen, TruthLineFormatAndRollConvention)
{
    FaceState f;
    f.id = 3, f.cx = 10.5, f.cy = -2.25, f.size = 80, f.rollDeg = -0.001, f.moving = true;
    EXPECT_EQ(facegen::truthLine(f), "3 10.50 -2.25 80.00 0.00 1");
    // Clockwise on screen (y down): "up" turned by +90 degrees points right.
    const cv::Point2d r = facegen::rotateOnScreen({0.0, -1.0}, 90.0);
    EXPECT_NEAR(r.x, 1.0, 1e-12);
    EXPECT_NEAR(r.y, 0.0, 1e-12);
}

TEST(Facegen, ImmLandmarksGiveAnUprightFaceFrame)
{
    const facegen::FacePhoto face = facegen::loadImmFace(sharedData("imm_face_db/01-1m.asf"));
    EXPECT_TRUE(fs::exists(face.imagePath));
    const facegen::FaceFrame fr = facegen::faceFrameOf(face);
    EXPECT_GT(fr.width, 120.0);
    EXPECT_LT(fr.width, 220.0);
    EXPECT_LT(std::abs(fr.rollDeg), 8.0);
    EXPECT_THROW(facegen::loadImmFace(sharedData("imm_face_db/missing.asf")), std::runtime_error);
    EXPECT_EQ(facegen::frontalImmFaces(sharedData("imm_face_db")).size(), 160u);
}

TEST(Facegen, ShortSequenceHasEveryFileAndSaneTruth)
{
    const std::string out = freshOutputDir("facegen_two");
    const facegen::GeneratedSequence seq = facegen::generateSequence(options("two", out, 7));
    EXPECT_EQ(seq.frames, kFrames);
    EXPECT_EQ(seq.movingFaces, 2);
    EXPECT_TRUE(fs::is_regular_file(fs::path(out) / "README.txt"));
    EXPECT_NE(slurp(fs::path(out) / "README.txt").find("seed: 7"), std::string::npos);
    for (int i = 0; i < kFrames; ++i) {
        char name[16];
        std::snprintf(name, sizeof name, "%06d", i);
        const cv::Mat frame =
            cv::imread((fs::path(out) / "frames" / (std::string(name) + ".png")).string());
        ASSERT_FALSE(frame.empty()) << name;
        EXPECT_EQ(frame.size(), cv::Size(640, 480));
        const std::vector<FaceState> faces =
            readTruth(fs::path(out) / "truth" / (std::string(name) + ".txt"));
        int moving = 0;
        for (const FaceState& f : faces) {
            if (f.moving) {
                ++moving;
                EXPECT_TRUE(f.id == 1 || f.id == 2);
                EXPECT_LE(std::abs(f.rollDeg), 35.0);
                EXPECT_GE(f.size, 60.0);  // a face the 360x240 detector can find
                // "two" keeps its faces wholly in view.
                EXPECT_GE(f.cx - f.size / 2, 0.0);
                EXPECT_LE(f.cx + f.size / 2, 639.0);
            } else {
                EXPECT_GE(f.id, 101);
                EXPECT_EQ(f.rollDeg, 0.0);
            }
        }
        EXPECT_EQ(moving, 2) << name;
        for (std::size_t a = 0; a < faces.size(); ++a)
            for (std::size_t b = a + 1; b < faces.size(); ++b)
                EXPECT_LE(facegen::overlapOfSmaller(faces[a], faces[b]), 0.3 + 1e-3);
    }
    EXPECT_FALSE(fs::exists(fs::path(out) / "frames" / "000010.png"));
}

TEST(Facegen, SameSeedSameBytesOtherSeedOtherSequence)
{
    const std::string a = freshOutputDir("facegen_seed_a");
    const std::string b = freshOutputDir("facegen_seed_b");
    const std::string c = freshOutputDir("facegen_seed_c");
    // Small frames keep it quick; the paths scale with the frame.
    for (const auto& [dir, seed] : {std::pair{a, 3u}, std::pair{b, 3u}, std::pair{c, 4u}}) {
        facegen::GenerateOptions o = options("enter-leave", dir, seed);
        o.size = cv::Size(320, 240);
        o.frames = 6;
        facegen::generateSequence(o);
    }
    int differentTruth = 0;
    for (const char* sub : {"frames", "truth"})
        for (const auto& entry : fs::directory_iterator(fs::path(a) / sub)) {
            const fs::path name = entry.path().filename();
            EXPECT_EQ(slurp(entry.path()), slurp(fs::path(b) / sub / name)) << sub << "/" << name;
            if (std::string(sub) == "truth")
                differentTruth += slurp(entry.path()) != slurp(fs::path(c) / sub / name);
        }
    EXPECT_EQ(slurp(fs::path(a) / "README.txt"), slurp(fs::path(b) / "README.txt"));
    EXPECT_GT(differentTruth, 0);
}

TEST(Facegen, TruthBoxOfAnUprightComposedFaceIsTheCascadesBox)
{
    cv::setNumThreads(1);
    cv::CascadeClassifier cascade;
    ASSERT_TRUE(cascade.load(facegen::kDefaultCascade));
    facegen::Background bg;
    bg.image = cv::Mat(480, 640, CV_32FC3, cv::Scalar(90, 110, 120));
    std::vector<facegen::FaceSprite> sprites;
    for (const char* name : {"02-1m", "12-2f", "33-1m"}) {
        sprites.clear();
        sprites.emplace_back(
            facegen::loadImmFace(sharedData(std::string("imm_face_db/") + name + ".asf")));
        FaceState f;
        f.id = 1, f.cx = 300, f.cy = 230, f.size = 110, f.rollDeg = 0, f.moving = true;
        const cv::Mat frame = facegen::renderFrame(bg, sprites, {f}, {}, 1);
        cv::Mat grey;
        cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
        std::vector<cv::Rect> hits;
        cascade.detectMultiScale(grey, hits, 1.1, 3, 0, cv::Size(24, 24));
        bool matched = false;
        for (const cv::Rect& r : hits) {
            const double dx = r.x + r.width * 0.5 - 0.5 - f.cx,
                         dy = r.y + r.height * 0.5 - 0.5 - f.cy;
            const double ratio = r.width / f.size;
            matched =
                matched || (std::hypot(dx, dy) < 0.12 * f.size && ratio > 0.85 && ratio < 1.18);
        }
        EXPECT_TRUE(matched) << name << ": " << hits.size() << " hits";
    }
}

TEST(Facegen, MeasuredSizeFactorHoldsOnASample)
{
    std::vector<std::string> sample;
    for (const char* name : {"03-1m", "08-2f", "14-1f", "21-5m", "27-6m", "40-1m"})
        sample.push_back(sharedData(std::string("imm_face_db/") + name + ".asf"));
    const facegen::SizeMeasurement m =
        facegen::measureBoxAgainstLandmarks(sample, facegen::kDefaultCascade);
    EXPECT_EQ(m.detected, 6);
    EXPECT_NEAR(m.boxPerWidth, facegen::kBoxPerWidth, 0.1 * facegen::kBoxPerWidth);
    EXPECT_NEAR(m.offsetY, facegen::kBoxOffsetY, 0.08);
}

}  // namespace
