#include "platform/png_writer.hpp"

#include "alloc_counter.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using platform::PngInputLayout;
using platform::PngRowOrder;
using platform::PngWriter;

// RGB pixel (x, y) of the test pattern: every channel varies, so swaps and flips show.
std::uint8_t patternValue(int x, int y, int c)
{
    return static_cast<std::uint8_t>(x * 7 + y * 13 + c * 85);
}

std::vector<std::uint8_t> makeRgb(int w, int h)
{
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                rgb[(static_cast<std::size_t>(y) * w + x) * 3 + c] = patternValue(x, y, c);
    return rgb;
}

std::vector<std::uint8_t> makeNoise(int w, int h)
{
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
    std::mt19937 random(12345);
    for (auto& v : rgb)
        v = static_cast<std::uint8_t>(random() >> 24);
    return rgb;
}

// Pixel-exact comparison of a PNG file with top-down tightly packed RGB.
void expectPngEquals(const std::string& path, const std::vector<std::uint8_t>& rgb, int w, int h)
{
    const cv::Mat bgr = cv::imread(path, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(bgr.empty()) << path;
    ASSERT_EQ(bgr.type(), CV_8UC3) << "expected an RGB PNG";
    ASSERT_EQ(bgr.cols, w);
    ASSERT_EQ(bgr.rows, h);
    long mismatches = 0;
    for (int y = 0; y < h; ++y) {
        const auto* row = bgr.ptr<std::uint8_t>(y);
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                if (row[x * 3 + (2 - c)] != rgb[(static_cast<std::size_t>(y) * w + x) * 3 + c])
                    ++mismatches;
    }
    EXPECT_EQ(mismatches, 0) << path;
}

bool exists(const std::string& path)
{
    return std::filesystem::exists(path);
}

TEST(PngWriter, WritesKnownRgbPatternPixelExact)
{
    const std::string dir = testing_support::freshOutputDir("png_writer/pattern");
    const int w = 37;  // odd width: rows are not 4-byte aligned
    const int h = 23;
    const auto rgb = makeRgb(w, h);
    PngWriter writer;
    const std::string path = dir + "/pattern.png";
    ASSERT_TRUE(writer.write(path.c_str(), rgb.data(), w, h, w * 3)) << writer.lastError();
    EXPECT_STREQ(writer.lastError(), "");
    expectPngEquals(path, rgb, w, h);
    EXPECT_FALSE(exists(path + ".tmp"));
}

TEST(PngWriter, DropsFourthByteAndFlipsBottomUpRows)
{
    const std::string dir = testing_support::freshOutputDir("png_writer/rgbx");
    const int w = 19;
    const int h = 11;
    const std::size_t stride = w * 4 + 8;  // padded rows
    const auto rgb = makeRgb(w, h);
    std::vector<std::uint8_t> rgbx(stride * h, 0xEE);
    for (int y = 0; y < h; ++y)  // memory row 0 = bottom image row, as glReadPixels gives it
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c)
                rgbx[(h - 1 - y) * stride + x * 4 + c] =
                    rgb[(static_cast<std::size_t>(y) * w + x) * 3 + c];
            rgbx[(h - 1 - y) * stride + x * 4 + 3] = 0x40;  // alpha must not leak into the PNG
        }
    PngWriter writer;
    const std::string path = dir + "/rgbx.png";
    ASSERT_TRUE(writer.write(path.c_str(), rgbx.data(), w, h, stride, PngInputLayout::Rgbx,
                             PngRowOrder::BottomUp))
        << writer.lastError();
    expectPngEquals(path, rgb, w, h);
}

TEST(PngWriter, DefaultArenaSufficesForIncompressibleHdImages)
{
    const std::string dir = testing_support::freshOutputDir("png_writer/noise");
    PngWriter writer;
    for (const auto& [w, h] : {std::pair{1280, 720}, std::pair{1920, 1080}}) {
        const auto noise = makeNoise(w, h);
        const std::string path = dir + "/noise-" + std::to_string(w) + ".png";
        ASSERT_TRUE(writer.write(path.c_str(), noise.data(), w, h, w * 3)) << writer.lastError();
        expectPngEquals(path, noise, w, h);
    }
    EXPECT_LT(writer.arenaHighWater(), writer.arenaBytes() / 2) << "arena margin is thin";
}

TEST(PngWriter, WritesWithoutAnyHeapAllocation)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting is not available in this build";
    const std::string dir = testing_support::freshOutputDir("png_writer/allocations");
    const int w = 640;
    const int h = 480;
    const auto noise = makeNoise(w, h);
    const std::string first = dir + "/first.png";
    const std::string second = dir + "/second.png";
    PngWriter writer;
    ASSERT_TRUE(writer.write(first.c_str(), noise.data(), w, h, w * 3)) << writer.lastError();

    testing_support::AllocationCounts counts;
    bool ok = false;
    {
        testing_support::AllocationScope scope;
        ok = writer.write(second.c_str(), noise.data(), w, h, w * 3);
        counts = scope.counts();
    }
    ASSERT_TRUE(ok) << writer.lastError();
    // libpng and zlib are shared libraries: their mallocs would show as foreign.
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
    EXPECT_EQ(counts.foreignMalloc, 0);
}

TEST(PngWriter, ExhaustedArenaFailsCleanly)
{
    const std::string dir = testing_support::freshOutputDir("png_writer/tiny");
    const auto rgb = makeRgb(64, 64);
    // 512 bytes: not even libpng's own struct fits. 64 KiB: libpng fits, zlib's window does not.
    for (const std::size_t arena : {std::size_t{512}, std::size_t{64} << 10}) {
        PngWriter writer(arena);
        const std::string path = dir + "/tiny-" + std::to_string(arena) + ".png";
        for (int attempt = 0; attempt < 2; ++attempt) {
            EXPECT_FALSE(writer.write(path.c_str(), rgb.data(), 64, 64, 64 * 3));
            EXPECT_NE(std::string(writer.lastError()).find("arena"), std::string::npos)
                << writer.lastError();
            EXPECT_FALSE(exists(path));
            EXPECT_FALSE(exists(path + ".tmp"));
        }
    }
}

TEST(PngWriter, UnwritablePathFailsWithReason)
{
    const auto rgb = makeRgb(8, 8);
    PngWriter writer;
    EXPECT_FALSE(writer.write("/nonexistent-mirror-dir/x.png", rgb.data(), 8, 8, 8 * 3));
    EXPECT_NE(std::string(writer.lastError()).find("No such file or directory"), std::string::npos)
        << writer.lastError();
    EXPECT_FALSE(writer.write("/proc/mirror-test.png", rgb.data(), 8, 8, 8 * 3));
    EXPECT_NE(std::string(writer.lastError()).find("/proc/mirror-test.png"), std::string::npos)
        << writer.lastError();
}

TEST(PngWriter, RejectsInvalidImages)
{
    const std::string dir = testing_support::freshOutputDir("png_writer/invalid");
    const auto rgb = makeRgb(8, 8);
    const std::string path = dir + "/x.png";
    PngWriter writer;
    EXPECT_FALSE(writer.write(path.c_str(), nullptr, 8, 8, 24));
    EXPECT_FALSE(writer.write(path.c_str(), rgb.data(), 0, 8, 24));
    EXPECT_FALSE(writer.write(path.c_str(), rgb.data(), 8, 8, 23));  // stride shorter than a row
    EXPECT_FALSE(writer.write("", rgb.data(), 8, 8, 24));
    EXPECT_STRNE(writer.lastError(), "");
    EXPECT_FALSE(exists(path));
}

TEST(PngWriter, ReplacesAnExistingFile)
{
    const std::string dir = testing_support::freshOutputDir("png_writer/replace");
    const std::string path = dir + "/same.png";
    PngWriter writer;
    const auto small = makeRgb(4, 4);
    const auto large = makeRgb(16, 9);
    ASSERT_TRUE(writer.write(path.c_str(), small.data(), 4, 4, 12)) << writer.lastError();
    ASSERT_TRUE(writer.write(path.c_str(), large.data(), 16, 9, 48)) << writer.lastError();
    expectPngEquals(path, large, 16, 9);
}

}  // namespace
