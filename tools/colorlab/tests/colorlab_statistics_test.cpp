// colorlab's pieces: sample lists and grids, disc sampling, the DP of eq. 19, the ranking.
#include "ranking.hpp"
#include "samples.hpp"
#include "sampling.hpp"
#include "statistics.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>

namespace {

using colorlab::Sample;
using colorlab::SampleError;

std::string writeFile(const std::string& dir, const std::string& name, const std::string& text)
{
    const std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    return path;
}

std::string errorOf(const std::function<void()>& f)
{
    try {
        f();
    } catch (const SampleError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(SampleFile, ReadsNamesPositionsRadiiAndSkipsComments)
{
    const auto dir = testing_support::freshOutputDir("colorlab_samples_read");
    const auto path = writeFile(dir, "samples.txt",
                                "# the eight papers\n\norange 10 20\n  red 30 40 5  # big disc\n");
    const auto samples = colorlab::readSampleFile(path);
    ASSERT_EQ(samples.size(), 2u);
    EXPECT_EQ(samples[0].name, "orange");
    EXPECT_EQ(samples[0].x, 10);
    EXPECT_EQ(samples[0].y, 20);
    EXPECT_EQ(samples[0].radius, colorlab::kDefaultRadius);
    EXPECT_EQ(samples[0].origin, path + ":3");
    EXPECT_EQ(samples[1].name, "red");
    EXPECT_EQ(samples[1].radius, 5);
}

TEST(SampleFile, ProblemsNameTheFileAndLine)
{
    const auto dir = testing_support::freshOutputDir("colorlab_samples_bad");
    auto read = [&](const std::string& text) {
        const auto path = writeFile(dir, "s.txt", text);
        return errorOf([&] { colorlab::readSampleFile(path); });
    };
    EXPECT_EQ(read("a 1 2\nb 1\n"), dir + "/s.txt:2: expected `name x y [radius]`, got 2 fields");
    EXPECT_EQ(read("a 1 2\na 3 4\n"), dir + "/s.txt:2: sample name 'a' is used twice");
    EXPECT_EQ(read("a 1 two\n"), dir + "/s.txt:1: sample 'a': x and y must be integers");
    EXPECT_EQ(read("a 1 2 -1\n"), dir + "/s.txt:1: sample 'a': radius must be an integer 0..100");
    EXPECT_EQ(read("a/b 1 2\n"),
              dir + "/s.txt:1: sample name 'a/b' may only use letters, digits, '-', '_' and '.'");
    EXPECT_EQ(read("# nothing\n\n"), dir + "/s.txt: no samples (lines `name x y [radius]`)");
    EXPECT_EQ(errorOf([&] { colorlab::readSampleFile(dir + "/missing.txt"); }),
              dir + "/missing.txt: cannot read sample list: No such file or directory");
}

TEST(SampleCheck, OutsideTheFrameIsOneClearLine)
{
    std::vector<Sample> samples = {{"paper", 10, 10, 3, "samples.txt:2"},
                                   {"skin", 900, 20, 3, "samples.txt:3"}};
    EXPECT_EQ(errorOf([&] { colorlab::checkSamples(samples, 720, 576); }),
              "samples.txt:3: sample 'skin' at (900, 20) is outside the 720x576 frame");
    samples[1] = {"edge", 718, 20, 3, "samples.txt:4"};
    EXPECT_EQ(errorOf([&] { colorlab::checkSamples(samples, 720, 576); }),
              "samples.txt:4: sample 'edge' at (718, 20) with radius 3 does not fit in the "
              "720x576 frame");
    EXPECT_EQ(errorOf([&] { colorlab::checkSamples({}, 720, 576); }), "no samples to measure");
    samples.pop_back();
    EXPECT_NO_THROW(colorlab::checkSamples(samples, 720, 576));
}

TEST(SampleGrid, ParsesAndPlacesCellCentres)
{
    int cols = 0, rows = 0;
    colorlab::parseGrid("4x2", cols, rows);
    EXPECT_EQ(cols, 4);
    EXPECT_EQ(rows, 2);
    EXPECT_THROW(colorlab::parseGrid("4", cols, rows), SampleError);
    EXPECT_THROW(colorlab::parseGrid("0x3", cols, rows), SampleError);
    EXPECT_THROW(colorlab::parseGrid("3xq", cols, rows), SampleError);
    const auto grid = colorlab::gridSamples(400, 200, 4, 2, 3);
    ASSERT_EQ(grid.size(), 8u);
    EXPECT_EQ(grid[0].name, "r0c0");
    EXPECT_EQ(grid[0].x, 50);
    EXPECT_EQ(grid[0].y, 50);
    EXPECT_EQ(grid[7].name, "r1c3");
    EXPECT_EQ(grid[7].x, 350);
    EXPECT_EQ(grid[7].y, 150);
    EXPECT_NO_THROW(colorlab::checkSamples(grid, 400, 200));
}

TEST(Sampling, MeanOverTheDiscAndSaturation)
{
    // BGR24 6x6 with padding: every pixel B=10 G=20 R=x*10, one clipped pixel outside radius 1.
    constexpr int kW = 6, kH = 6, kStride = 20;
    std::uint8_t data[kStride * kH] = {};
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            data[y * kStride + 3 * x + 0] = 10;
            data[y * kStride + 3 * x + 1] = 20;
            data[y * kStride + 3 * x + 2] = static_cast<std::uint8_t>(x * 10);
        }
    data[0 * kStride + 3 * 0 + 1] = 255;  // (0, 0): outside the radius-1 disc around (2, 2)
    const vision::ConstImageView view{data, kW, kH, kStride, vision::PixelFormat::BGR24};
    // Radius 1: the centre and its 4 neighbours; R = (20 + 10 + 30 + 20 + 20) / 5 = 20.
    auto m = colorlab::measureDisc(view, {"s", 2, 2, 1, ""});
    EXPECT_DOUBLE_EQ(m.r, 20.0);
    EXPECT_DOUBLE_EQ(m.g, 20.0);
    EXPECT_DOUBLE_EQ(m.b, 10.0);
    EXPECT_FALSE(m.saturated);
    // Radius 2 around (2, 2) includes (0, 2) but not the corner (0, 0): dx^2 + dy^2 = 8 > 4.
    EXPECT_FALSE(colorlab::measureDisc(view, {"s", 2, 2, 2, ""}).saturated);
    EXPECT_TRUE(colorlab::measureDisc(view, {"s", 1, 1, 2, ""}).saturated);
    // Radius 0: the pixel itself.
    EXPECT_DOUBLE_EQ(colorlab::measureDisc(view, {"s", 4, 3, 0, ""}).r, 40.0);
}

TEST(DiscriminativePower, Equation19OverTheChromaticComponents)
{
    // YIQ: Y is not chromatic, so its huge difference must not count.
    const auto& yiq = vision::colorSpaceInfo(vision::ColorSpace::Yiq);
    colorlab::ComponentStats a{{100.0, 0.0, 0.0}, {50.0, 1.0, 0.0}};
    colorlab::ComponentStats b{{0.0, 3.0, 4.0}, {50.0, 0.0, 2.0}};
    // |(0,0) - (3,4)| = 5; |(1,0)| + |(0,2)| = 3.
    EXPECT_DOUBLE_EQ(colorlab::discriminativePower(yiq, a, b), 5.0 / 3.0);
    EXPECT_DOUBLE_EQ(colorlab::discriminativePower(yiq, b, a), 5.0 / 3.0);
    colorlab::ComponentStats still{{0.0, 3.0, 4.0}, {}};
    colorlab::ComponentStats other{{0.0, 0.0, 0.0}, {}};
    EXPECT_EQ(colorlab::discriminativePower(yiq, still, other), colorlab::kDpCap);
    EXPECT_EQ(colorlab::discriminativePower(yiq, still, still), 0.0);
}

TEST(DiscriminativePower, PairsInOrder)
{
    // n = 4: (0,1) (0,2) (0,3) (1,2) (1,3) (2,3).
    const std::array<int, 2> want[] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    for (int k = 0; k < 6; ++k)
        EXPECT_EQ(colorlab::pairOf(4, k), want[k]) << k;
}

TEST(Statistics, ConstantAndScaledSeries)
{
    // Two samples over three frames; the first grey-ish colour is scaled by the light.
    colorlab::Recording rec;
    rec.samples = {{"a", 0, 0, 0, ""}, {"b", 0, 0, 0, ""}};
    for (double k : {1.0, 0.5, 2.0}) {
        rec.frameNumbers.push_back(static_cast<long>(rec.frameNumbers.size()));
        rec.measurements.push_back({{60 * k, 30 * k, 10 * k, false}, {10, 60, 20, k == 2.0}});
    }
    const std::vector<bool> all(3, true);
    const auto chroma = colorlab::computeSpaceStats(rec, all, vision::ColorSpace::Chromaticity);
    EXPECT_NEAR(chroma.samples[0].stdev[0], 0.0, 1e-9);  // invariant
    EXPECT_NEAR(chroma.samples[0].mean[0], 255.0 * 60 / 100, 1e-9);
    EXPECT_NEAR(chroma.invariancePercent, 0.0, 1e-9);
    ASSERT_EQ(chroma.dp.size(), 1u);
    EXPECT_EQ(chroma.dp[0], colorlab::kDpCap);
    const auto rgb = colorlab::computeSpaceStats(rec, all, vision::ColorSpace::Rgb);
    // R of sample a: 60, 30, 120: mean 70, sample stdev sqrt(((10)^2+(40)^2+(50)^2)/2) =
    // sqrt(2100).
    EXPECT_NEAR(rgb.samples[0].mean[0], 70.0, 1e-9);
    EXPECT_NEAR(rgb.samples[0].stdev[0], std::sqrt(2100.0), 1e-9);
    EXPECT_GT(rgb.invariancePercent, 1.0);
    // Leaving out the last row changes the statistics.
    const auto two = colorlab::computeSpaceStats(rec, {true, true, false}, vision::ColorSpace::Rgb);
    EXPECT_NEAR(two.samples[0].mean[0], 45.0, 1e-9);
}

TEST(Ranking, RankSumWithMeanDpTieBreak)
{
    std::vector<colorlab::SpaceStats> stats(3);
    stats[0].space = vision::ColorSpace::Yiq;  // worst invariance, best mean DP
    stats[0].invariancePercent = 5.0;
    stats[0].dpMean = 9.0;
    stats[0].dpMin = 0.5;
    stats[1].space = vision::ColorSpace::Chromaticity;  // best everywhere but mean DP
    stats[1].invariancePercent = 0.1;
    stats[1].dpMean = 8.0;
    stats[1].dpMin = 3.0;
    stats[2].space = vision::ColorSpace::Hsv;
    stats[2].invariancePercent = 1.0;
    stats[2].dpMean = 2.0;
    stats[2].dpMin = 1.0;
    const auto ranking = colorlab::rankSpaces(stats);
    ASSERT_EQ(ranking.size(), 3u);
    EXPECT_EQ(ranking[0].space, vision::ColorSpace::Chromaticity);
    EXPECT_EQ(ranking[0].score, 1 + 2 + 1);
    // yiq: 3 + 1 + 3 = 7, hsv: 2 + 3 + 2 = 7: tie, yiq has the higher mean DP.
    EXPECT_EQ(ranking[1].space, vision::ColorSpace::Yiq);
    EXPECT_EQ(ranking[2].space, vision::ColorSpace::Hsv);
    EXPECT_EQ(colorlab::rankingLine(ranking), "ranking: chromaticity > yiq > hsv");
}

TEST(ComponentRanges, BoundEveryConvertedValue)
{
    for (const auto& info : vision::colorSpaces())
        for (int r = 0; r <= 255; r += 17)
            for (int g = 0; g <= 255; g += 17)
                for (int b = 0; b <= 255; b += 17) {
                    const auto v = vision::convertReference(info.space, r, g, b);
                    for (int c = 0; c < info.components; ++c) {
                        const double range = colorlab::componentRange(info.space, c);
                        if (range > 0.0) {
                            ASSERT_LE(std::abs(v[c]), range + 1e-9) << info.name << c;
                        }
                    }
                }
}

}  // namespace
