// aam-annotate: the prompt drawing places every point of each scheme on the CANDIDE face, the
// scripted run writes the annotation aam-build reads, and bad input is one line and exit code 1.
#include "annotation_files.hpp"
#include "annotation_schemes.hpp"
#include "point_list.hpp"
#include "reference_face.hpp"
#include "test_paths.hpp"
#include "wfm_reader.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

namespace {

using testing_support::sharedData;

std::string candidePath()
{
    return sharedData("candide3/candide3.wfm");
}

// Runs aam-annotate with `arguments`; its exit code, and what it printed (both streams) in *out.
int annotate(const std::string& arguments, std::string* out = nullptr)
{
    // One log per test: ctest runs the tests of this file side by side.
    const std::string log = testing_support::freshOutputDir(
                                std::string("annotate_run_") +
                                ::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                            "/out.txt";
    // Never a window: a test must not wait for clicks on a desktop it happens to have.
    const int status = std::system((std::string("env -u DISPLAY -u WAYLAND_DISPLAY ") +
                                    AAM_ANNOTATE + " " + arguments + " >" + log + " 2>&1")
                                       .c_str());
    if (out != nullptr) {
        std::ifstream in(log);
        std::stringstream s;
        s << in.rdbuf();
        *out = s.str();
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(ReferenceFace, EveryPointOfEachSchemeLiesOnTheDrawnFace)
{
    if (!std::filesystem::exists(candidePath()))
        GTEST_SKIP() << "no " << candidePath();
    const vision::CandideMesh face = aam::loadWfm(candidePath());
    for (const aam::AnnotationScheme* scheme :
         {&aam::immScheme(), &aam::fgnetScheme(), &aam::ibugScheme()}) {
        const annotate::ReferenceFace reference(face, *scheme);
        ASSERT_EQ(reference.pointCount(), scheme->pointCount);
        int mapped = 0;
        for (int i = 0; i < reference.pointCount(); ++i) {
            const Eigen::Vector2d p = reference.point(i);
            EXPECT_GT(p.x(), 20.0) << scheme->name << " point " << i;
            EXPECT_LT(p.x(), 460.0) << scheme->name << " point " << i;
            EXPECT_GT(p.y(), 20.0) << scheme->name << " point " << i;
            EXPECT_LT(p.y(), 460.0) << scheme->name << " point " << i;
            mapped += reference.mapped(i);
        }
        EXPECT_GT(mapped, scheme->pointCount / 2) << scheme->name;
        const cv::Mat picture = reference.draw(3, 3);
        EXPECT_EQ(picture.rows, 480);
        // The next point is ringed in red.
        const cv::Vec3b ring =
            picture.at<cv::Vec3b>(static_cast<int>(reference.point(3).y() + 0.5),
                                  static_cast<int>(reference.point(3).x() + 9.5));
        EXPECT_GT(ring[2], 150) << scheme->name;
    }
}

TEST(PointList, ReadsPointsAndRefusesAnythingElseWithItsLine)
{
    const std::string dir = testing_support::freshOutputDir("annotate_points");
    std::ofstream(dir + "/good.txt") << "# x y\n10 20\n\n30.5 40.25\n";
    const auto points = annotate::readPointList(dir + "/good.txt");
    ASSERT_EQ(points.size(), 2u);
    EXPECT_DOUBLE_EQ(points[1].y(), 40.25);
    for (const char* bad : {"10\n", "10 20 30\n", "x y\n", "nan 3\n"}) {
        std::ofstream(dir + "/bad.txt") << "1 2\n" << bad;
        try {
            annotate::readPointList(dir + "/bad.txt");
            ADD_FAILURE() << bad;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("bad.txt:2: expected two numbers"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(AamAnnotate, AScriptedRunWritesTheAnnotationAamBuildReads)
{
    const std::string imm = sharedData("imm_face_db");
    if (!std::filesystem::exists(imm + "/01-1m.asf") || !std::filesystem::exists(candidePath()))
        GTEST_SKIP() << "no IMM or CANDIDE-3 data";
    // IMM's own annotation of 01-1m as the clicks, in pixels.
    const aam::Annotation truth = aam::loadAsf(imm + "/01-1m.asf");
    const std::string dir = testing_support::freshOutputDir("annotate_scripted");
    std::ofstream list(dir + "/clicks.txt");
    for (const Eigen::Vector2d& p : truth.points)
        list << p.x() << " " << p.y() << "\n";
    list.close();
    std::filesystem::copy_file(imm + "/01-1m.jpg", dir + "/me.jpg");
    std::string out;
    ASSERT_EQ(annotate("--image " + dir + "/me.jpg --scheme imm --points " + dir +
                           "/clicks.txt --reference " + dir + "/prompt.png --wfm " + candidePath(),
                       &out),
              0)
        << out;
    EXPECT_NE(out.find("point 1 of 58 (imm)"), std::string::npos) << out;
    EXPECT_NE(out.find("wrote " + dir + "/me.pts (58 points)"), std::string::npos) << out;
    const aam::Annotation written = aam::loadPts(dir + "/me.pts");
    ASSERT_EQ(written.points.size(), truth.points.size());
    for (std::size_t i = 0; i < truth.points.size(); ++i)
        EXPECT_LT((written.points[i] - truth.points[i]).norm(), 1e-3) << i;
    EXPECT_FALSE(cv::imread(dir + "/prompt.png").empty());
}

TEST(AamAnnotate, BadInputIsOneLineAndExitCodeOne)
{
    const std::string dir = testing_support::freshOutputDir("annotate_bad");
    std::ofstream(dir + "/three.txt") << "1 2\n3 4\n5 6\n";
    std::string out;
    EXPECT_EQ(annotate("--image " + dir + "/none.jpg --points " + dir + "/three.txt", &out), 1);
    EXPECT_NE(out.find("none.jpg: not a picture OpenCV can read"), std::string::npos) << out;
    const std::string imm = sharedData("imm_face_db");
    if (!std::filesystem::exists(imm + "/01-1m.jpg") || !std::filesystem::exists(candidePath()))
        return;
    EXPECT_EQ(annotate("--image " + imm + "/01-1m.jpg --out " + dir + "/x.pts --points " + dir +
                           "/three.txt --wfm " + candidePath(),
                       &out),
              1);
    EXPECT_NE(out.find("three.txt has 3 points; the ibug scheme has 68"), std::string::npos) << out;
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.pts"));
    // No desktop and no --points: a clear line, not a crash.
    EXPECT_EQ(annotate("--image " + imm + "/01-1m.jpg --out " + dir + "/y.pts --wfm " +
                           candidePath() + " </dev/null",
                       &out),
              1)
        << out;
    EXPECT_EQ(annotate("--image " + imm + "/01-1m.jpg --scheme klingon", &out), 1);
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
}

}  // namespace
