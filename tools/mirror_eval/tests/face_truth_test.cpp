// Face truth parsers (CMU/MIT 6-point lines, FGNet .pts, facegen per-frame lines) and the truth
// roll: good input, one clear NAME:LINE error per kind of bad input.

#include "face_truth.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

using namespace mirror_eval;

template <typename Parse>
std::string errorOf(Parse parse, const std::string& text)
{
    std::istringstream in(text);
    try {
        parse(in, "t.txt");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(no error)";
}

const auto landmarks = [](std::istream& in, const std::string& n) {
    return parseLandmarkFaces(in, n);
};
const auto pts = [](std::istream& in, const std::string& n) { return parsePts(in, n); };
const auto composed = [](std::istream& in, const std::string& n) {
    return parseComposedTruth(in, n);
};

TEST(FaceTruth, ParsesLandmarkLines)
{
    std::istringstream in(
        "# comment\n"
        "voyager.png 122.0 43.0 137.0 47.0 129.0 54.0 123.0 59.0 128.0 60.0 "
        "133.0 62.0\r\n"
        "\n"
        "a.png 10 20 30 20 20 30 12 40 20 40 28 40\n");
    const auto faces = parseLandmarkFaces(in, "t.txt");
    ASSERT_EQ(faces.size(), 2u);
    EXPECT_EQ(faces[0].image, "voyager.png");
    EXPECT_EQ(faces[0].line, 2);
    EXPECT_FLOAT_EQ(faces[0].rightEye.x, 137.f);
    EXPECT_FLOAT_EQ(faces[0].mouthRight.y, 62.f);
    EXPECT_EQ(faces[1].image, "a.png");
    EXPECT_FLOAT_EQ(faces[1].eyeMidpoint().x, 20.f);
    EXPECT_FLOAT_EQ(faces[1].eyeMidpoint().y, 20.f);
    EXPECT_FLOAT_EQ(faces[1].eyeMouthDistance(), 20.f);
    EXPECT_FLOAT_EQ(faces[1].centre().y, 30.f);
}

TEST(FaceTruth, MalformedLandmarkLinesNameFileAndLine)
{
    EXPECT_EQ(errorOf(landmarks, "a.png 1 2 3\n"),
              "t.txt:1: expected 13 fields (file and 6 points x y), got 4");
    EXPECT_EQ(errorOf(landmarks, "\na.png 1 2 3 4 5 6 7 8 9 x 11 12\n"),
              "t.txt:2: mouth centre y 'x' is not a number");
}

TEST(FaceTruth, MissingLandmarkFileIsOneClearError)
{
    try {
        loadLandmarkFaces("/nonexistent/set.txt");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "truth /nonexistent/set.txt: cannot open (missing or unreadable)");
    }
}

TEST(FaceTruth, ParsesPts)
{
    std::istringstream in("version: 1\nn_points: 3\n{\n1.5 2\n3 4\n 5 6 \n}\n");
    const auto p = parsePts(in, "t.pts");
    ASSERT_EQ(p.size(), 3u);
    EXPECT_FLOAT_EQ(p[0].x, 1.5f);
    EXPECT_FLOAT_EQ(p[2].y, 6.f);
}

TEST(FaceTruth, MalformedPts)
{
    EXPECT_EQ(errorOf(pts, "version: 1\nn_points: 2\n{\n1 2\n"),
              "t.txt:4: missing '}' (truncated file?)");
    EXPECT_EQ(errorOf(pts, "version: 1\nn_points: 3\n{\n1 2\n3 4\n}\n"),
              "t.txt:6: n_points is 3, read 2");
    EXPECT_EQ(errorOf(pts, "hello\n"),
              "t.txt:1: expected 'version:', 'n_points:' or '{', got 'hello'");
    EXPECT_EQ(errorOf(pts, "n_points: 1\n{\n1 y\n}\n"), "t.txt:3: y 'y' is not a number");
}

TEST(FaceTruth, RealFgnetPtsHas68Points)
{
    const auto p =
        loadPts(testing_support::sharedData("fgnet_talking_face/points/franck_00000.pts"));
    ASSERT_EQ(p.size(), 68u);
    // The FGNet markup: eye centres 31 and 36 either side of the nose tip 67, mouth below.
    const auto axis = axisPoints68(p);
    EXPECT_LT(p[31].x, p[67].x);
    EXPECT_GT(p[36].x, p[67].x);
    EXPECT_LT(axis[0].y, axis[1].y);
    EXPECT_LT(axis[1].y, axis[2].y);
    EXPECT_LT(std::fabs(axisRollDegrees(axis[0], axis[1], axis[2])), 15.0);
}

TEST(FaceTruth, ParsesComposedTruth)
{
    std::istringstream in("1 129.05 301.83 112.78 -24.25 1\n101 182.50 246.50 118.00 0.00 0\n");
    const auto f = parseComposedTruth(in, "t.txt");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f[0].id, 1);
    EXPECT_FLOAT_EQ(f[0].centre.x, 129.05f);
    EXPECT_FLOAT_EQ(f[0].size, 112.78f);
    EXPECT_FLOAT_EQ(f[0].rollDegrees, -24.25f);
    EXPECT_TRUE(f[0].moving);
    EXPECT_FALSE(f[1].moving);
    std::istringstream empty("");
    EXPECT_TRUE(parseComposedTruth(empty, "t.txt").empty());  // a frame without faces
}

TEST(FaceTruth, MalformedComposedTruth)
{
    EXPECT_EQ(errorOf(composed, "1 2 3 4 5\n"),
              "t.txt:1: expected 6 fields 'id cx cy size roll_deg moving', got 5");
    EXPECT_EQ(errorOf(composed, "1 2 3 4 5 2\n"), "t.txt:1: moving '2' must be 0 or 1");
    EXPECT_EQ(errorOf(composed, "1 2 3 -4 5 1\n"), "t.txt:1: size '-4' must be positive");
    EXPECT_EQ(errorOf(composed, "a 2 3 4 5 1\n"), "t.txt:1: id 'a' is not an integer");
}

TEST(FaceTruth, AxisRollSignIsClockwiseOnScreen)
{
    EXPECT_NEAR(axisRollDegrees({0, 0}, {0, 10}, {0, 20}), 0.0, 1e-4);
    // Rotated clockwise on screen (y down) by 20 degrees: eyes -> mouth is (-sin r, cos r).
    const double r = 20.0 * 3.14159265358979323846 / 180.0;
    const vision::Point2f e{100, 100};
    const auto at = [&](double t) {
        return vision::Point2f{static_cast<float>(100 - t * std::sin(r)),
                               static_cast<float>(100 + t * std::cos(r))};
    };
    EXPECT_NEAR(axisRollDegrees(e, at(10), at(20)), 20.0, 1e-3);
    EXPECT_NEAR(axisRollDegrees(e, at(10), at(20)) +
                    axisRollDegrees(e, {200 - at(10).x, at(10).y}, {200 - at(20).x, at(20).y}),
                0.0, 1e-3);
    // A nose off the eye-mouth line: the best line through the three points lies between.
    const double withNose = axisRollDegrees({0, 0}, {2, 10}, {0, 20});
    EXPECT_NEAR(withNose, 0.0, 1e-3);  // symmetric about the line x = 2/3: still vertical
}

TEST(FaceTruth, AxisPoints68NeedsSixtyEightPoints)
{
    EXPECT_THROW(axisPoints68(std::vector<vision::Point2f>(10)), std::runtime_error);
}

}  // namespace
