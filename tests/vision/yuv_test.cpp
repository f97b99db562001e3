// YUV (BT.601 limited range) to RGB in fixed point: the tables equal the documented integer
// formula for every Y, U, V; the formula is within 1 of the real-valued BT.601 conversion; the
// YUYV and NV12 layouts and the packed RGB swizzles are right.
#include "vision/yuv.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace {

using vision::ImageBuffer;
using vision::PixelFormat;
using vision::Rgb8;

TEST(Yuv, BlackWhiteAndGreyOfStudioRange)
{
    EXPECT_EQ(vision::yuvToRgb(16, 128, 128), (Rgb8{0, 0, 0}));
    EXPECT_EQ(vision::yuvToRgb(235, 128, 128), (Rgb8{255, 255, 255}));
    EXPECT_EQ(vision::yuvToRgb(126, 128, 128), (Rgb8{128, 128, 128}));
    EXPECT_EQ(vision::yuvToRgb(0, 128, 128), (Rgb8{0, 0, 0}));          // below black: clamped
    EXPECT_EQ(vision::yuvToRgb(255, 128, 128), (Rgb8{255, 255, 255}));  // above white: clamped
}

TEST(Yuv, IntegerFormulaWithinOneOfRealBt601)
{
    int worst = 0;
    for (int y = 0; y < 256; y += 3)
        for (int u = 0; u < 256; u += 3)
            for (int v = 0; v < 256; v += 3) {
                const double c = 255.0 / 219.0 * (y - 16), d = 255.0 / 224.0 * (u - 128),
                             e = 255.0 / 224.0 * (v - 128);
                const double ref[3] = {c + 1.402 * e, c - 0.344136 * d - 0.714136 * e,
                                       c + 1.772 * d};
                const Rgb8 got = vision::yuvToRgb(y, u, v);
                const int g[3] = {got.r, got.g, got.b};
                for (int k = 0; k < 3; ++k) {
                    const int expected =
                        static_cast<int>(std::lround(std::clamp(ref[k], 0.0, 255.0)));
                    worst = std::max(worst, std::abs(g[k] - expected));
                }
            }
    EXPECT_LE(worst, 1);
}

// Every (Y, U, V) through the table path of YUYV rows: one row per (U, V) pair holding all 256
// luma values.
TEST(Yuv, TablesEqualTheFormulaEverywhere)
{
    std::vector<std::uint8_t> row(256 * 2), rgb(256 * 3);
    long mismatches = 0;
    for (int u = 0; u < 256; ++u)
        for (int v = 0; v < 256; ++v) {
            for (int k = 0; k < 128; ++k) {
                row[4 * k] = static_cast<std::uint8_t>(2 * k);
                row[4 * k + 1] = static_cast<std::uint8_t>(u);
                row[4 * k + 2] = static_cast<std::uint8_t>(2 * k + 1);
                row[4 * k + 3] = static_cast<std::uint8_t>(v);
            }
            vision::yuyvRowToRgb24(row.data(), 0, 256, rgb.data());
            for (int y = 0; y < 256; ++y) {
                const Rgb8 e = vision::yuvToRgb(y, u, v);
                const std::uint8_t* p = &rgb[static_cast<std::size_t>(3 * y)];
                if (p[0] != e.r || p[1] != e.g || p[2] != e.b) {
                    if (mismatches++ == 0)
                        ADD_FAILURE() << "Y=" << y << " U=" << u << " V=" << v;
                }
            }
        }
    EXPECT_EQ(mismatches, 0);
}

TEST(Yuv, YuyvAndNv12Layouts)
{
    std::mt19937 rng(9);
    const int w = 10, h = 6;
    ImageBuffer yuyv(w, h, PixelFormat::YUYV), nv12(w, h, PixelFormat::NV12);
    for (std::size_t i = 0; i < yuyv.bytes(); ++i)
        yuyv.view().data[i] = static_cast<std::uint8_t>(rng());
    for (std::size_t i = 0; i < nv12.bytes(); ++i)
        nv12.view().data[i] = static_cast<std::uint8_t>(rng());
    ImageBuffer a(w, h, PixelFormat::RGB24), b(w, h, PixelFormat::RGB24);
    ASSERT_TRUE(vision::convertToRgb24(yuyv.view(), a.view()));
    ASSERT_TRUE(vision::convertToRgb24(nv12.view(), b.view()));
    const auto yv = yuyv.view(), nv = nv12.view();
    const std::uint8_t* uv = nv.data + nv.stride * h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::uint8_t* p = yv.row(y) + 4 * (x / 2);
            const Rgb8 e = vision::yuvToRgb(p[x % 2 ? 2 : 0], p[1], p[3]);
            const std::uint8_t* o = a.view().row(y) + 3 * x;
            EXPECT_EQ((Rgb8{o[0], o[1], o[2]}), e) << x << "," << y;
            const std::uint8_t* c = uv + (y / 2) * nv.stride + 2 * (x / 2);
            const Rgb8 f = vision::yuvToRgb(nv.row(y)[x], c[0], c[1]);
            const std::uint8_t* q = b.view().row(y) + 3 * x;
            EXPECT_EQ((Rgb8{q[0], q[1], q[2]}), f) << x << "," << y;
        }
}

TEST(Yuv, PackedRgbFormatsSwizzleToRgb24)
{
    const int w = 5, h = 3;
    ImageBuffer bgr(w, h, PixelFormat::BGR24), xrgb(w, h, PixelFormat::XRGB8888),
        rgb(w, h, PixelFormat::RGB24);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::uint8_t r = static_cast<std::uint8_t>(10 * x + y), g = 100, b = 200;
            std::uint8_t* p = bgr.view().row(y) + 3 * x;
            p[0] = b, p[1] = g, p[2] = r;
            std::uint8_t* q = xrgb.view().row(y) + 4 * x;
            q[0] = b, q[1] = g, q[2] = r, q[3] = 7;
            std::uint8_t* s = rgb.view().row(y) + 3 * x;
            s[0] = r, s[1] = g, s[2] = b;
        }
    for (const ImageBuffer* in : {&bgr, &xrgb, &rgb}) {
        ImageBuffer out(w, h, PixelFormat::RGB24);
        ASSERT_TRUE(vision::convertToRgb24(in->view(), out.view()));
        for (int y = 0; y < h; ++y)
            EXPECT_EQ(std::memcmp(out.view().row(y), rgb.view().row(y), 3 * w), 0);
    }
}

TEST(Yuv, RejectsWhatItCannotConvert)
{
    ImageBuffer gray(4, 4, PixelFormat::Gray8), out(4, 4, PixelFormat::RGB24),
        small(2, 4, PixelFormat::RGB24), notRgb(4, 4, PixelFormat::BGR24);
    ImageBuffer yuyv(4, 4, PixelFormat::YUYV);
    EXPECT_FALSE(vision::convertToRgb24(gray.view(), out.view()));
    EXPECT_FALSE(vision::convertToRgb24(yuyv.view(), small.view()));
    EXPECT_FALSE(vision::convertToRgb24(yuyv.view(), notRgb.view()));
    vision::ConstImageView odd = yuyv.view();
    odd.width = 3;
    EXPECT_FALSE(vision::convertibleToRgb24(odd));
}

}  // namespace
