// Chromaticity (ch. 3, 4.3): the table path must equal round(255 c / (R+G+B)) exactly.
#include "vision/chromaticity.hpp"

#include "vision/chromaticity_stage.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using vision::ImageBuffer;
using vision::PixelFormat;

std::uint8_t reference(int c, int sum)
{
    if (sum == 0)
        return 0;
    return static_cast<std::uint8_t>(std::floor(255.0 * c / sum + 0.5));
}

TEST(ChromaticityTable, EveryEntryIsTheRoundedQuotient)
{
    vision::ChromaticityTable table;
    for (int sum = 0; sum <= 765; ++sum)
        for (int c = 0; c <= std::min(sum, 255); ++c)
            ASSERT_EQ(table.row(sum)[c], reference(c, sum)) << "c=" << c << " sum=" << sum;
}

TEST(ChromaticityTable, BlackIsZeroNotAnError)
{
    vision::ChromaticityTable table;
    EXPECT_EQ(table.row(0)[0], 0);
}

void fillRandom(ImageBuffer& img, std::mt19937& rng)
{
    auto v = img.view();
    std::uniform_int_distribution<int> d(0, 255);
    for (int y = 0; y < v.height; ++y)
        for (int x = 0; x < v.stride; ++x)
            v.row(y)[x] = static_cast<std::uint8_t>(d(rng));
}

class ChromaticityFormats : public ::testing::TestWithParam<PixelFormat> {};

TEST_P(ChromaticityFormats, RandomImageMatchesPerPixelReference)
{
    const PixelFormat fmt = GetParam();
    std::mt19937 rng(1234);
    for (int width : {1, 3, 4, 7, 64, 99}) {
        ImageBuffer in(width, 5, fmt);
        fillRandom(in, rng);
        ImageBuffer r(width, 5, PixelFormat::Gray8), g(width, 5, PixelFormat::Gray8),
            b(width, 5, PixelFormat::Gray8);
        vision::ChromaticityTable table;
        ASSERT_TRUE(vision::convertChromaticity(table, in.view(), {r.view(), g.view(), b.view()}));
        const int step = vision::bytesPerPixel(fmt);
        const int ri = fmt == PixelFormat::RGB24 ? 0 : 2, bi = fmt == PixelFormat::RGB24 ? 2 : 0;
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < width; ++x) {
                const std::uint8_t* p = in.view().row(y) + x * step;
                const int sum = p[0] + p[1] + p[2];
                ASSERT_EQ(r.view().row(y)[x], reference(p[ri], sum));
                ASSERT_EQ(g.view().row(y)[x], reference(p[1], sum));
                ASSERT_EQ(b.view().row(y)[x], reference(p[bi], sum));
            }
    }
}

INSTANTIATE_TEST_SUITE_P(Formats, ChromaticityFormats,
                         ::testing::Values(PixelFormat::RGB24, PixelFormat::BGR24,
                                           PixelFormat::XRGB8888));

TEST(Chromaticity, RejectsUnsupportedFormatAndSizeMismatch)
{
    vision::ChromaticityTable table;
    ImageBuffer gray(8, 8, PixelFormat::Gray8), rgb(8, 8, PixelFormat::RGB24);
    ImageBuffer p(8, 8, PixelFormat::Gray8), small(4, 8, PixelFormat::Gray8);
    EXPECT_FALSE(vision::convertChromaticity(table, gray.view(), {p.view(), p.view(), p.view()}));
    EXPECT_FALSE(
        vision::convertChromaticity(table, rgb.view(), {small.view(), p.view(), p.view()}));
}

TEST(ChromaticityStage, FillsPlanesOfFrameState)
{
    ImageBuffer in(16, 8, PixelFormat::RGB24);
    auto v = in.view();
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            v.row(y)[3 * x] = 200;
            v.row(y)[3 * x + 1] = 50;
            v.row(y)[3 * x + 2] = 5;
        }
    vision::ChromaticityStage stage({16, 8});
    vision::FrameState state;
    state.frame.image = in.view();
    stage.process(state);
    ASSERT_TRUE(state.valid);
    EXPECT_EQ(state.chroma.r.row(3)[7], reference(200, 255));
    EXPECT_EQ(state.chroma.g.row(3)[7], reference(50, 255));
    EXPECT_EQ(state.chroma.b.row(3)[7], reference(5, 255));
}

}  // namespace
