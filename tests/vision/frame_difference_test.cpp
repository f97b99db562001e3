#include "vision/frame_difference.hpp"

#include <gtest/gtest.h>

#include <cstring>

using namespace vision;

namespace {

struct Fixture {
    ImageBuffer rgb{16, 8, PixelFormat::RGB24};
    ImageBuffer r{16, 8, PixelFormat::Gray8}, g{16, 8, PixelFormat::Gray8},
        b{16, 8, PixelFormat::Gray8};
    ImageBuffer mask{16, 8, PixelFormat::Gray8};
    ChromaticityPlanes planes() { return {r.view(), g.view(), b.view()}; }
    void setChroma(int x, int y, std::uint8_t v)
    {
        r.view().row(y)[x] = v;
        g.view().row(y)[x] = v;
        b.view().row(y)[x] = v;
    }
};

}  // namespace

TEST(FrameDifference, UpdatesTheMaskOnlyWhereTheFrameChanged)
{
    Fixture f;
    ColorBounds match;  // matches chroma 50 on every channel
    for (int c = 0; c < 3; ++c) {
        match.lo[c] = 45;
        match.hi[c] = 55;
    }
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            f.setChroma(x, y, 50);
    FrameDifference d({16, 8});
    // First frame: everything counts as changed and matches.
    EXPECT_EQ(d.updateMask(f.rgb.view(), f.planes(), match, 24, f.mask.view()), 16 * 8);
    EXPECT_EQ(f.mask.view().row(3)[3], 255);
    // Chromaticity now says "no match" everywhere, but only pixel (5, 2) changed enough.
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            f.setChroma(x, y, 0);
    std::uint8_t* p = f.rgb.view().row(2) + 5 * 3;
    p[0] = 10;
    p[1] = 10;
    p[2] = 10;  // sum of differences 30 > 24
    std::uint8_t* q = f.rgb.view().row(4) + 7 * 3;
    q[0] = 20;  // 20 <= 24: not a change
    EXPECT_EQ(d.updateMask(f.rgb.view(), f.planes(), match, 24, f.mask.view()), 1);
    EXPECT_EQ(f.mask.view().row(2)[5], 0);
    EXPECT_EQ(f.mask.view().row(4)[7], 255);
    EXPECT_EQ(f.mask.view().row(0)[0], 255);
    // Same frame again: nothing changed.
    EXPECT_EQ(d.updateMask(f.rgb.view(), f.planes(), match, 24, f.mask.view()), 0);
    d.forget();
    EXPECT_EQ(d.updateMask(f.rgb.view(), f.planes(), match, 24, f.mask.view()), 16 * 8);
}

TEST(FrameDifference, RejectsMismatchedInput)
{
    Fixture f;
    FrameDifference d({16, 8});
    ImageBuffer gray(16, 8, PixelFormat::Gray8);
    EXPECT_EQ(d.updateMask(gray.view(), f.planes(), ColorBounds{}, 24, f.mask.view()), -1);
    ImageBuffer small(8, 8, PixelFormat::RGB24);
    EXPECT_EQ(d.updateMask(small.view(), f.planes(), ColorBounds{}, 24, f.mask.view()), -1);
    ImageBuffer x(16, 8, PixelFormat::XRGB8888);
    EXPECT_EQ(d.updateMask(x.view(), f.planes(), ColorBounds{}, 24, f.mask.view()), 16 * 8);
}
