// The grey pyramid: sizes, the 5-tap binomial filter against a direct reference, no allocation.
#include "vision/image_pyramid.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>

using vision::ImageBuffer;
using vision::ImagePyramid;
using vision::PixelFormat;

namespace {

ImageBuffer noiseImage(int w, int h, std::uint32_t seed)
{
    ImageBuffer img(w, h, PixelFormat::Gray8);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            seed = seed * 1664525u + 1013904223u;
            img.view().row(y)[x] = static_cast<std::uint8_t>(seed >> 24);
        }
    return img;
}

int reflect101(int i, int n)
{
    if (i < 0)
        i = -i;
    if (i >= n)
        i = 2 * n - 2 - i;
    return i;
}

// cv::pyrDown's definition written out: [1 4 6 4 1]^2 / 256, reflect-101 borders, rounded.
int referenceDown(vision::ConstImageView src, int x, int y)
{
    static const int k[5] = {1, 4, 6, 4, 1};
    int sum = 0;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i)
            sum += k[j] * k[i] *
                   src.row(
                       reflect101(2 * y + j - 2, src.height))[reflect101(2 * x + i - 2, src.width)];
    return (sum + 128) >> 8;
}

}  // namespace

TEST(ImagePyramid, LevelSizesHalveRoundingUp)
{
    ImagePyramid pyr({101, 77}, 4);
    ASSERT_EQ(pyr.levels(), 4);
    ImageBuffer img = noiseImage(101, 77, 1);
    ASSERT_TRUE(pyr.build(img.view()));
    EXPECT_EQ(pyr.level(0).data, img.view().data);  // level 0 is the frame itself
    EXPECT_EQ(pyr.level(1).size(), (vision::Size{51, 39}));
    EXPECT_EQ(pyr.level(2).size(), (vision::Size{26, 20}));
    EXPECT_EQ(pyr.level(3).size(), (vision::Size{13, 10}));
}

TEST(ImagePyramid, MatchesTheBinomialReferenceExactly)
{
    for (vision::Size size : {vision::Size{64, 48}, vision::Size{33, 17}, vision::Size{720, 576}}) {
        ImagePyramid pyr(size, 3);
        ImageBuffer img = noiseImage(size.width, size.height, 7u + size.width);
        ASSERT_TRUE(pyr.build(img.view()));
        for (int l = 1; l < pyr.levels(); ++l) {
            const auto src = pyr.level(l - 1);
            const auto dst = pyr.level(l);
            int mismatches = 0;
            for (int y = 0; y < dst.height; ++y)
                for (int x = 0; x < dst.width; ++x)
                    mismatches += dst.row(y)[x] != referenceDown(src, x, y);
            EXPECT_EQ(mismatches, 0) << size.width << "x" << size.height << " level " << l;
        }
    }
}

TEST(ImagePyramid, ConstantImageStaysConstant)
{
    ImageBuffer img(40, 30, PixelFormat::Gray8);
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x)
            img.view().row(y)[x] = 173;
    ImagePyramid pyr({40, 30});
    ASSERT_TRUE(pyr.build(img.view()));
    for (int l = 1; l < pyr.levels(); ++l)
        for (int y = 0; y < pyr.level(l).height; ++y)
            for (int x = 0; x < pyr.level(l).width; ++x)
                ASSERT_EQ(pyr.level(l).row(y)[x], 173);
}

TEST(ImagePyramid, SmallFramesGetFewerLevelsAndBadInputIsRefused)
{
    ImagePyramid small({20, 20}, 6);
    EXPECT_EQ(small.levels(), 2);  // 20 -> 10; 5 would be under 8 pixels
    EXPECT_THROW(ImagePyramid({0, 10}), std::runtime_error);
    EXPECT_THROW(ImagePyramid({10, 10}, 0), std::runtime_error);
    EXPECT_THROW(ImagePyramid({10, 10}, 9), std::runtime_error);
    ImageBuffer wrong(21, 20, PixelFormat::Gray8);
    EXPECT_FALSE(small.build(wrong.view()));
    ImageBuffer rgb(20, 20, PixelFormat::RGB24);
    EXPECT_FALSE(small.build(rgb.view()));
}

TEST(ImagePyramid, BuildDoesNotAllocate)
{
    ImagePyramid pyr({320, 240}, 4);
    ImageBuffer img = noiseImage(320, 240, 3);
    testing_support::AllocationScope scope;
    for (int i = 0; i < 3; ++i)
        ASSERT_TRUE(pyr.build(img.view()));
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}
