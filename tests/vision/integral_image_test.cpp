#include "vision/integral_image.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>

using vision::ImageBuffer;
using vision::IntegralImage;
using vision::PixelFormat;
using vision::Rect;

namespace {

std::uint64_t bruteSum(const vision::ConstImageView& im, int x0, int y0, int x1, int y1)
{
    std::uint64_t s = 0;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            s += im.row(y)[x];
        }
    }
    return s;
}

}  // namespace

TEST(IntegralImage, RectangleSumsEqualBruteForce)
{
    ImageBuffer image(37, 23, PixelFormat::Gray8);
    std::mt19937 rng(7);
    for (int y = 0; y < 23; ++y) {
        for (int x = 0; x < 37; ++x) {
            image.view().row(y)[x] = static_cast<std::uint8_t>(rng() & 0xff);
        }
    }
    IntegralImage integral({37, 23});
    ASSERT_TRUE(integral.compute(image.view()));
    for (int y0 = 0; y0 <= 23; ++y0) {
        for (int y1 = y0; y1 <= 23; y1 += 3) {
            for (int x0 = 0; x0 <= 37; x0 += 2) {
                for (int x1 = x0; x1 <= 37; ++x1) {
                    ASSERT_EQ(integral.sum(x0, y0, x1, y1), bruteSum(image.view(), x0, y0, x1, y1))
                        << x0 << "," << y0 << " - " << x1 << "," << y1;
                }
            }
        }
    }
    EXPECT_EQ(integral.rectSum({0, 0, 37, 23}), bruteSum(image.view(), 0, 0, 37, 23));
}

TEST(IntegralImage, ClipsRectanglesAndGivesMaskFraction)
{
    ImageBuffer mask(20, 10, PixelFormat::Gray8);
    for (int y = 0; y < 10; ++y) {
        for (int x = 0; x < 20; ++x) {
            mask.view().row(y)[x] = x < 5 ? 255 : 0;  // left quarter set
        }
    }
    IntegralImage integral({20, 10});
    ASSERT_TRUE(integral.compute(mask.view()));
    EXPECT_FLOAT_EQ(integral.maskFraction({0, 0, 20, 10}), 0.25f);
    EXPECT_FLOAT_EQ(integral.maskFraction({0, 0, 5, 10}), 1.0f);
    EXPECT_FLOAT_EQ(integral.maskFraction({-10, -10, 20, 30}), 0.5f);  // clipped to 0..10 x 0..10
    EXPECT_EQ(integral.rectSum({-10, -10, 20, 30}), 5u * 10u * 255u);
    EXPECT_EQ(integral.rectSum({25, 0, 5, 5}), 0u);  // outside
    EXPECT_FLOAT_EQ(integral.maskFraction({25, 0, 5, 5}), 0.0f);
    EXPECT_EQ(integral.rectSum({3, 3, 0, 4}), 0u);  // empty
}

TEST(IntegralImage, LargestFrameSumIsExact)
{
    ImageBuffer white(720, 576, PixelFormat::Gray8);
    for (int y = 0; y < 576; ++y) {
        std::fill_n(white.view().row(y), 720, std::uint8_t{255});
    }
    IntegralImage integral({720, 576});
    ASSERT_TRUE(integral.compute(white.view()));
    EXPECT_EQ(integral.rectSum({0, 0, 720, 576}), 720u * 576u * 255u);
}

TEST(IntegralImage, RejectsWrongSizeOrFormat)
{
    IntegralImage integral({8, 8});
    ImageBuffer wrongSize(9, 8, PixelFormat::Gray8);
    ImageBuffer wrongFormat(8, 8, PixelFormat::RGB24);
    EXPECT_FALSE(integral.compute(wrongSize.view()));
    EXPECT_FALSE(integral.compute(wrongFormat.view()));
}
