// The NEON frame difference against the scalar reference: the same mask bytes, changed-pixel
// counts and remembered frame, frame after frame, on random frames of both packings with widths
// that leave every tail length, random and edge-case colour bands and thresholds.
#include "vision/frame_difference.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

namespace {

using vision::ColorBounds;
using vision::DifferencePath;
using vision::FrameDifference;
using vision::ImageBuffer;
using vision::PixelFormat;

/// A frame, its chromaticity planes and two masks (one per path), random.
struct Frames {
    Frames(int w, int h, PixelFormat f)
        : rgb(w, h, f),
          r(w, h, PixelFormat::Gray8),
          g(w, h, PixelFormat::Gray8),
          b(w, h, PixelFormat::Gray8),
          scalarMask(w, h, PixelFormat::Gray8),
          neonMask(w, h, PixelFormat::Gray8)
    {
    }
    ImageBuffer rgb, r, g, b, scalarMask, neonMask;
    vision::ChromaticityPlanes planes() { return {r.view(), g.view(), b.view()}; }
};

void fill(const vision::ImageView& v, std::mt19937& rng, int bytesPerRow)
{
    std::uniform_int_distribution<int> byte(0, 255);
    for (int y = 0; y < v.height; ++y)
        for (int x = 0; x < bytesPerRow; ++x)
            v.row(y)[x] = static_cast<std::uint8_t>(byte(rng));
}

/// The next frame: most pixels as before, some changed a little, some a lot (the threshold's
/// both sides).
void nextFrame(Frames& f, std::mt19937& rng, int step)
{
    std::uniform_int_distribution<int> kind(0, 9), small(-12, 12), byte(0, 255);
    const vision::ImageView v = f.rgb.view();
    for (int y = 0; y < v.height; ++y)
        for (int x = 0; x < v.width; ++x) {
            const int k = kind(rng);
            for (int c = 0; c < step; ++c) {
                std::uint8_t& p = v.row(y)[step * x + c];
                if (k < 3)
                    p = static_cast<std::uint8_t>(std::clamp(p + small(rng), 0, 255));
                else if (k < 5)
                    p = static_cast<std::uint8_t>(byte(rng));
            }
        }
    for (const vision::ImageView plane : {f.r.view(), f.g.view(), f.b.view()})
        fill(plane, rng, plane.width);
}

ColorBounds randomBounds(std::mt19937& rng, int trial)
{
    std::uniform_int_distribution<int> byte(0, 255);
    ColorBounds b;
    for (int c = 0; c < 3; ++c) {
        const int a = byte(rng), d = byte(rng);
        b.lo[c] = static_cast<std::uint8_t>(std::min(a, d));
        b.hi[c] = static_cast<std::uint8_t>(std::max(a, d));
    }
    if (trial % 5 == 1)
        std::swap(b.lo[1], b.hi[1]);  // an empty band: nothing matches
    if (trial % 5 == 2) {
        b.lo[0] = 0;  // a full band
        b.hi[0] = 255;
    }
    return b;
}

TEST(FrameDifferenceSimd, NeonIsTheScalarPathBitForBit)
{
    if (!vision::differencePathAvailable(DifferencePath::Neon))
        GTEST_SKIP() << "no NEON path in this build (aarch64 only; the arm64 tests run it)";
    std::mt19937 rng(7);
    const int thresholds[] = {-3, 0, 1, 24, 100, 765, 1000};
    int trial = 0;
    for (const PixelFormat format : {PixelFormat::RGB24, PixelFormat::XRGB8888})
        for (const int w : {1, 15, 16, 17, 31, 47, 64, 79, 720}) {
            const int step = format == PixelFormat::XRGB8888 ? 4 : 3;
            const int h = w == 720 ? 6 : 5;
            Frames f(w, h, format);
            fill(f.rgb.view(), rng, w * step);
            fill(f.scalarMask.view(), rng, w);
            std::memcpy(f.neonMask.view().data, f.scalarMask.view().data, f.neonMask.bytes());
            FrameDifference scalar({w, h}), neon({w, h});
            for (int frame = 0; frame < 8; ++frame, ++trial) {
                if (frame > 0)
                    nextFrame(f, rng, step);
                const ColorBounds bounds = randomBounds(rng, trial);
                const int t = thresholds[trial % 7];
                const int ns = scalar.updateMask(f.rgb.view(), f.planes(), bounds, t,
                                                 f.scalarMask.view(), DifferencePath::Scalar);
                const int nn = neon.updateMask(f.rgb.view(), f.planes(), bounds, t,
                                               f.neonMask.view(), DifferencePath::Neon);
                ASSERT_EQ(ns, nn) << "width " << w << " frame " << frame << " threshold " << t;
                ASSERT_EQ(std::memcmp(f.scalarMask.view().data, f.neonMask.view().data,
                                      f.scalarMask.bytes()),
                          0)
                    << "width " << w << " frame " << frame << " threshold " << t;
            }
        }
}

TEST(FrameDifferenceSimd, PathsThisBuildHas)
{
    EXPECT_TRUE(vision::differencePathAvailable(DifferencePath::Scalar));
    EXPECT_TRUE(vision::differencePathAvailable(DifferencePath::Best));
#if defined(__aarch64__)
    EXPECT_TRUE(vision::differencePathAvailable(DifferencePath::Neon));
#else
    EXPECT_FALSE(vision::differencePathAvailable(DifferencePath::Neon));
#endif
}

}  // namespace
