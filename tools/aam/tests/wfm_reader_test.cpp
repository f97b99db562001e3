// The .wfm reader: CANDIDE-3 read whole (counts, a vertex, a triangle, named units); a malformed
// or truncated file is rejected with one line naming the line.
#include "wfm_reader.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

const std::string kCandide = testing_support::sharedData("candide3/candide3.wfm");

std::string readAll(const std::string& path)
{
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), {}};
}

/// The error line reading `text` gives ("" when it reads).
std::string errorOf(const std::string& text)
{
    std::istringstream in(text);
    try {
        aam::readWfm(in, "bad.wfm");
    } catch (const aam::WfmError& e) {
        return e.what();
    }
    return "";
}

// A small valid file: a triangle, one animation unit, one shape unit.
const std::string kTiny =
    "# VERTEX LIST:\n3\n0 0 0\n1 0 0\n0 1 0\n"
    "# FACE LIST:\n1\n0 1 2\n"
    "# ANIMATION UNITS LIST:\n1\n# AUV11 Jaw drop (AU26/27)\n1\n2 0 -0.26 -0.05\n"
    "# SHAPE UNITS LIST:\n1\n# Mouth width\n1\n1 0.1 0 0\n"
    "0\n0\n0\n0 0 0\n1 1 1\n0 0 0\n# END OF FILE\n";

TEST(WfmReader, ReadsCandide3Whole)
{
    if (!std::filesystem::exists(kCandide))
        GTEST_SKIP() << kCandide << " not present";
    const vision::CandideMesh mesh = aam::loadWfm(kCandide);
    ASSERT_EQ(mesh.vertices.size(), 113u);
    EXPECT_EQ(mesh.triangles.size(), 184u);
    EXPECT_EQ(mesh.animationUnits.size(), 65u);  // 11 action unit vectors, 54 MPEG-4 FAPs
    ASSERT_EQ(mesh.shapeUnits.size(), 14u);
    EXPECT_FLOAT_EQ(mesh.vertices[0].y(), 1.061f);
    EXPECT_FLOAT_EQ(mesh.vertices[112].x(), -0.12f);
    EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{0, 11, 1}));
    EXPECT_EQ(mesh.candideNumber[57], 57);
    const vision::CandideUnit& jaw = mesh.animationUnits[1];
    EXPECT_EQ(jaw.label, "AUV11");
    EXPECT_EQ(jaw.name, "Jaw drop (AU26/27)");
    ASSERT_EQ(jaw.vertices.size(), 12u);
    EXPECT_EQ(jaw.vertices[2], 9);
    EXPECT_FLOAT_EQ(jaw.displacements[2].z(), -0.1f);
    EXPECT_EQ(mesh.animationUnits[11].label, "FAP 3");
    EXPECT_EQ(mesh.animationUnits[11].name, "open_jaw");
    EXPECT_EQ(mesh.shapeUnits[0].name, "Head height");
    EXPECT_EQ(mesh.shapeUnits[13].name, "Chin width");
    EXPECT_NE(vision::findUnit(mesh.animationUnits, "Lip corner depressor"), nullptr);
}

TEST(WfmReader, ReadsAMinimalFile)
{
    std::istringstream in(kTiny);
    const vision::CandideMesh mesh = aam::readWfm(in, "tiny.wfm");
    EXPECT_EQ(mesh.vertices.size(), 3u);
    EXPECT_EQ(mesh.shapeUnits.at(0).name, "Mouth width");
    EXPECT_EQ(mesh.shapeUnits.at(0).label, "");
}

TEST(WfmReader, RejectsATruncatedFileNamingTheLine)
{
    if (!std::filesystem::exists(kCandide))
        GTEST_SKIP() << kCandide << " not present";
    const std::string whole = readAll(kCandide);
    // Cut inside the face list: lines 156-169 are its first 14 triangles.
    std::string cut;
    std::istringstream lines(whole);
    std::string line;
    for (int n = 1; n < 170 && std::getline(lines, line); ++n)
        cut += line + "\n";
    EXPECT_EQ(errorOf(cut), "bad.wfm:169: file ends where triangle 14 of 184 was expected");
}

TEST(WfmReader, RejectsGarbledLinesNamingTheLine)
{
    auto replaced = [](std::string text, const std::string& from, const std::string& to) {
        return text.replace(text.find(from), from.size(), to);
    };
    EXPECT_EQ(errorOf(kTiny), "");
    EXPECT_EQ(errorOf(replaced(kTiny, "1 0 0\n", "1 zero 0\n")),
              "bad.wfm:4: vertex 1 of 3: \"zero\" is not a number");
    EXPECT_EQ(errorOf(replaced(kTiny, "0 1 0\n", "0 1\n")),
              "bad.wfm:5: vertex 2 of 3: expected 3 fields \"x y z\", got \"0 1\"");
    EXPECT_EQ(errorOf(replaced(kTiny, "0 1 2\n", "0 1 7\n")),
              "bad.wfm:8: triangle 0 of 1: vertex 7 does not exist (3 vertices)");
    EXPECT_EQ(errorOf(replaced(kTiny, "0 1 2\n", "0 1 1\n")),
              "bad.wfm:8: triangle 0 of 1: repeats a vertex");
    EXPECT_EQ(errorOf(replaced(kTiny, "# VERTEX LIST:\n3\n", "# VERTEX LIST:\n-3\n")),
              "bad.wfm:2: the vertex count -3 is out of range");
    EXPECT_EQ(
        errorOf(replaced(kTiny, "2 0 -0.26 -0.05\n", "2 0 -0.26\n")),
        "bad.wfm:13: animation unit 0 of 1 (Jaw drop (AU26/27)), entry 0 of 1: expected 4 fields "
        "\"vertex dx dy dz\", got \"2 0 -0.26\"");
    EXPECT_EQ(errorOf(replaced(kTiny, "# END OF FILE\n", "5\n")),
              "bad.wfm:25: unexpected data after the global motion: \"5\"");
    EXPECT_EQ(errorOf(replaced(kTiny, "0\n0\n0\n0 0 0\n", "0\n0\n2\n0 0 0\n")),
              "bad.wfm:21: texture coordinates are not supported (expected a count of 0)");
}

TEST(WfmReader, AMissingFileIsOneLine)
{
    try {
        aam::loadWfm("/nonexistent/candide3.wfm");
        FAIL() << "no error";
    } catch (const aam::WfmError& e) {
        EXPECT_STREQ(e.what(),
                     "/nonexistent/candide3.wfm: cannot read the CANDIDE model file: cannot read "
                     "file: No such file or directory");
    }
}

TEST(WfmReader, ADeviceInTheFilesPlaceIsOneLine)
{
    // Read through readBoundedFile: /dev/zero is refused at once instead of read for ever.
    try {
        aam::loadWfm("/dev/zero");
        FAIL() << "no error";
    } catch (const aam::WfmError& e) {
        EXPECT_STREQ(e.what(),
                     "/dev/zero: cannot read the CANDIDE model file: not a regular file (a FIFO, a "
                     "device or a socket)");
    }
}

}  // namespace
