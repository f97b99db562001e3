// The AAM model file (docs/aam-model-format.md): a model read back equals the one written; a
// missing, short, foreign, newer, truncated or bit-flipped file is refused with one line saying
// which; a model whose parts disagree is not written.
#include "crc32.hpp"  // private to vision/src
#include "test_paths.hpp"
#include "vision/aam_model.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <random>

namespace {

vision::AamModel tinyModel()
{
    vision::AamModel m;
    m.mesh.vertices = {{0, 0, 0}, {1, 0, 0.5f}, {0, 1, 0}};
    m.mesh.candideNumber = {5, 7, 9};
    m.mesh.triangles = {{0, 1, 2}};
    m.mesh.animationUnits = {{"Jaw drop (AU26/27)", "AUV11", {2}, {{0, -0.25f, 0}}}};
    m.mesh.shapeUnits = {{"Eyes, width", "", {0, 1}, {{-0.1f, 0, 0}, {0.1f, 0, 0}}}};
    m.meanShape = {0.5f, 0.5f, 3.5f, 0.5f, 0.5f, 3.5f};
    m.shapeModes = {1, 0, 0, 0, 0, 0};
    m.shapeVariances = {2.5f};
    m.frameWidth = 4;
    m.frameHeight = 4;
    m.pixels = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.meanAppearance = {1.2f, -0.6f, -0.6f};
    m.appearanceModes = {0.f, 0.7071f, -0.7071f};
    m.appearanceVariances = {0.3f};
    return m;
}

vision::AamModelFile decoded(const std::string& bytes)
{
    return vision::decodeAamModel(std::as_bytes(std::span(bytes.data(), bytes.size())));
}

TEST(AamModelFile, ReadsBackWhatWasWritten)
{
    const vision::AamModel m = tinyModel();
    const vision::AamModelFile back = decoded(vision::encodeAamModel(m));
    ASSERT_TRUE(back.ok) << back.problem;
    EXPECT_EQ(back.model.mesh.vertices, m.mesh.vertices);
    EXPECT_EQ(back.model.mesh.candideNumber, m.mesh.candideNumber);
    EXPECT_EQ(back.model.mesh.triangles, m.mesh.triangles);
    EXPECT_EQ(back.model.mesh.animationUnits[0].name, "Jaw drop (AU26/27)");
    EXPECT_EQ(back.model.mesh.animationUnits[0].label, "AUV11");
    EXPECT_EQ(back.model.mesh.shapeUnits[0].vertices, m.mesh.shapeUnits[0].vertices);
    EXPECT_EQ(back.model.mesh.shapeUnits[0].displacements, m.mesh.shapeUnits[0].displacements);
    EXPECT_EQ(back.model.meanShape, m.meanShape);
    EXPECT_EQ(back.model.shapeModes, m.shapeModes);
    EXPECT_EQ(back.model.shapeVariances, m.shapeVariances);
    EXPECT_EQ(back.model.frameWidth, 4);
    EXPECT_EQ(back.model.frameHeight, 4);
    ASSERT_EQ(back.model.pixels.size(), 3u);
    EXPECT_EQ(back.model.pixels[2].y, 1);
    EXPECT_EQ(back.model.meanAppearance, m.meanAppearance);
    EXPECT_EQ(back.model.appearanceModes, m.appearanceModes);
    EXPECT_EQ(back.model.appearanceVariances, m.appearanceVariances);
}

TEST(AamModelFile, ChecksumIsTheStandardCrc32)
{
    const std::string check = "123456789";
    EXPECT_EQ(vision::crc32(std::as_bytes(std::span(check.data(), check.size()))), 0xCBF43926u);
}

TEST(AamModelFile, EveryTruncationIsNamed)
{
    const std::string bytes = vision::encodeAamModel(tinyModel());
    for (std::size_t n = 0; n < bytes.size(); ++n) {
        const vision::AamModelFile f = decoded(bytes.substr(0, n));
        ASSERT_FALSE(f.ok) << n;
        // The first 8 bytes are the magic: a shorter prefix is still "shorter than the header".
        EXPECT_EQ(f.problem.rfind("truncated: ", 0), 0u) << n << ": " << f.problem;
    }
    EXPECT_EQ(decoded(bytes + "x").problem,
              "trailing bytes: the header announces " + std::to_string(bytes.size() - 20) +
                  " payload bytes, the file has " + std::to_string(bytes.size() - 19));
}

TEST(AamModelFile, EveryFlippedPayloadBitIsCorrupt)
{
    const std::string bytes = vision::encodeAamModel(tinyModel());
    for (std::size_t i = 20; i < bytes.size(); ++i) {
        for (int bit = 0; bit < 8; bit += 3) {
            std::string flipped = bytes;
            flipped[i] = static_cast<char>(flipped[i] ^ (1 << bit));
            const vision::AamModelFile f = decoded(flipped);
            ASSERT_FALSE(f.ok);
            EXPECT_EQ(f.problem.rfind("corrupt: the payload's CRC-32 is 0x", 0), 0u)
                << i << ": " << f.problem;
        }
    }
}

TEST(AamModelFile, ForeignAndNewerFilesAreNamed)
{
    std::string bytes = vision::encodeAamModel(tinyModel());
    std::string foreign = bytes;
    foreign[0] = 'X';
    EXPECT_EQ(decoded(foreign).problem, "not an AAM model file (it does not start with MIRRAAM)");
    bytes[8] = 2;
    EXPECT_EQ(decoded(bytes).problem, "model format version 2; this build reads version 1");
}

TEST(AamModelFile, AChecksummedButInconsistentPayloadIsMalformed)
{
    // A faulty writer: a triangle naming vertex 3 of 3, checksum recomputed.
    std::string bytes = vision::encodeAamModel(tinyModel());
    const std::size_t triangles = 20 + 9 * 4 + 3 * 16;
    bytes[triangles + 4] = 3;
    const std::uint32_t sum =
        vision::crc32(std::as_bytes(std::span(bytes.data() + 20, bytes.size() - 20)));
    std::memcpy(bytes.data() + 16, &sum, 4);
    EXPECT_EQ(decoded(bytes).problem, "malformed: triangle 0 uses vertex 3 of 3");
}

TEST(AamModelFile, RandomPayloadsWithAGoodChecksumNeverReadOutOfBounds)
{
    // A faulty writer's payloads: random bytes changed, the checksum made to match. Each is read
    // or refused as malformed; none crashes (the sanitizer build runs this too).
    const std::string good = vision::encodeAamModel(tinyModel());
    std::mt19937 random(7);
    for (int trial = 0; trial < 3000; ++trial) {
        std::string bytes = good;
        const int changes = 1 + trial % 4;
        for (int c = 0; c < changes; ++c) {
            const std::size_t at = 20 + random() % (bytes.size() - 20);
            bytes[at] = static_cast<char>(random() & 0xFF);
        }
        const std::uint32_t sum =
            vision::crc32(std::as_bytes(std::span(bytes.data() + 20, bytes.size() - 20)));
        std::memcpy(bytes.data() + 16, &sum, 4);
        const vision::AamModelFile f = decoded(bytes);
        if (!f.ok) {
            EXPECT_EQ(f.problem.rfind("malformed: ", 0), 0u) << f.problem;
        }
    }
}

TEST(AamModelFile, AModelWhosePartsDisagreeIsNotWritten)
{
    vision::AamModel m = tinyModel();
    m.appearanceModes.pop_back();
    EXPECT_THROW(vision::encodeAamModel(m), std::invalid_argument);
}

TEST(AamModelFile, AMissingFileIsOneLineWithItsPath)
{
    const vision::AamModelFile f = vision::loadAamModel("/nonexistent/face.aam");
    EXPECT_FALSE(f.ok);
    EXPECT_EQ(f.problem, "/nonexistent/face.aam: cannot read file: No such file or directory");
}

TEST(AamModelFile, LoadsAWrittenFile)
{
    const std::string path = testing_support::freshOutputDir("aam_model_file") + "/tiny.aam";
    std::ofstream(path, std::ios::binary) << vision::encodeAamModel(tinyModel());
    const vision::AamModelFile f = vision::loadAamModel(path);
    ASSERT_TRUE(f.ok) << f.problem;
    EXPECT_EQ(f.model.pixels.size(), 3u);
}

}  // namespace
