// warpUpright: an exact copy at roll 0, a pattern rotated on screen comes back upright with its
// roll (and not with the opposite one), border replication, bad arguments; warpRotated (regions
// of any shape, units per axis) and its agreement with warpUpright.
#include "vision/upright_patch.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

using namespace vision;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A smooth pattern without rotational symmetry, about (0, 0) in upright face coordinates.
double pattern(double u, double v)
{
    return 128.0 + 50.0 * std::sin(u / 4.0) + 40.0 * std::cos(v / 6.0) + 0.8 * u - 0.3 * v;
}

// The pattern turned clockwise on screen (y down) by `degrees` about `centre`: the pixel at
// offset d from the centre shows the upright pattern at R(-degrees) d.
/// A w x h grey image of uniform noise from `seed`.
ImageBuffer noiseImage(int w, int h, unsigned seed)
{
    ImageBuffer img(w, h, PixelFormat::Gray8);
    std::mt19937 rng(seed);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x)
            img.view().row(y)[x] = static_cast<std::uint8_t>(rng() & 255);
    }
    return img;
}

ImageBuffer rotatedScene(int w, int h, Point2f centre, double degrees)
{
    ImageBuffer img(w, h, PixelFormat::Gray8);
    const double c = std::cos(degrees * kPi / 180.0);
    const double s = std::sin(degrees * kPi / 180.0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double dx = x + 0.5 - centre.x;
            const double dy = y + 0.5 - centre.y;
            const double u = c * dx + s * dy;
            const double v = -s * dx + c * dy;
            img.view().row(y)[x] = static_cast<std::uint8_t>(std::lrint(pattern(u, v)));
        }
    }
    return img;
}

// Mean |patch - upright pattern| over the patch (patch pixel = one source pixel).
double meanErrorToUpright(const ImageBuffer& patch)
{
    const ConstImageView p = patch.view();
    double sum = 0.0;
    for (int v = 0; v < p.height; ++v) {
        for (int u = 0; u < p.width; ++u) {
            const double pu = u + 0.5 - p.width * 0.5;
            const double pv = v + 0.5 - p.height * 0.5;
            sum += std::fabs(p.row(v)[u] - std::lrint(pattern(pu, pv)));
        }
    }
    return sum / (p.width * p.height);
}

TEST(UprightPatch, RollZeroIsAnExactCopy)
{
    const ImageBuffer img = noiseImage(64, 48, 3);
    ImageBuffer patch(32, 32, PixelFormat::Gray8);
    ASSERT_TRUE(warpUpright(img.view(), {32.f, 24.f}, 0.f, 32.f, patch.view()));
    for (int v = 0; v < 32; ++v) {
        for (int u = 0; u < 32; ++u)
            ASSERT_EQ(patch.view().row(v)[u], img.view().row(8 + v)[16 + u]) << u << "," << v;
    }
}

TEST(UprightPatch, HalfSizePatchAveragesNeighbours)
{
    // Side 32 into 16: each patch pixel samples midway between two columns and two rows.
    ImageBuffer img(64, 48, PixelFormat::Gray8);
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 64; ++x)
            img.view().row(y)[x] = static_cast<std::uint8_t>(x * 2 + y);
    }
    ImageBuffer patch(16, 16, PixelFormat::Gray8);
    ASSERT_TRUE(warpUpright(img.view(), {32.f, 24.f}, 0.f, 32.f, patch.view()));
    // Patch pixel (u, v) is at source (16.5 + 2u, 8.5 + 2v) in pixel-centre coordinates.
    for (int v = 0; v < 16; ++v) {
        for (int u = 0; u < 16; ++u) {
            const double expected = (16.5 + 2 * u) * 2 + (8.5 + 2 * v);
            EXPECT_NEAR(patch.view().row(v)[u], expected, 0.51) << u << "," << v;
        }
    }
}

TEST(UprightPatch, RotatedPatternComesBackUpright)
{
    const Point2f centre{80.3f, 61.7f};
    for (const double roll : {-30.0, -12.5, 7.0, 25.0, 35.0}) {
        const ImageBuffer scene = rotatedScene(160, 120, centre, roll);
        ImageBuffer patch(40, 40, PixelFormat::Gray8);
        ASSERT_TRUE(
            warpUpright(scene.view(), centre, static_cast<float>(roll), 40.f, patch.view()));
        EXPECT_LT(meanErrorToUpright(patch), 1.5) << roll;
        // The opposite sense (or no warp) does not straighten it.
        ASSERT_TRUE(
            warpUpright(scene.view(), centre, static_cast<float>(-roll), 40.f, patch.view()));
        EXPECT_GT(meanErrorToUpright(patch), 5.0) << roll;
    }
}

TEST(UprightPatch, OutsidePixelsRepeatTheBorder)
{
    ImageBuffer img(20, 10, PixelFormat::Gray8);
    for (int y = 0; y < 10; ++y) {
        for (int x = 0; x < 20; ++x)
            img.view().row(y)[x] = static_cast<std::uint8_t>(10 * x + y);
    }
    ImageBuffer patch(8, 8, PixelFormat::Gray8);
    // Centred on the top-left corner: the upper-left quarter of the patch is pixel (0, 0).
    ASSERT_TRUE(warpUpright(img.view(), {0.f, 0.f}, 0.f, 8.f, patch.view()));
    for (int v = 0; v < 4; ++v) {
        for (int u = 0; u < 4; ++u)
            EXPECT_EQ(patch.view().row(v)[u], 0);
    }
    EXPECT_EQ(patch.view().row(7)[7], img.view().row(3)[3]);
    EXPECT_EQ(patch.view().row(0)[7], img.view().row(0)[3]);
    // Far to the right: the right column repeated (rotated too: only its values, 190..199).
    ASSERT_TRUE(warpUpright(img.view(), {500.f, 4.f}, 0.f, 8.f, patch.view()));
    EXPECT_EQ(patch.view().row(4)[4], img.view().row(4)[19]);
    ASSERT_TRUE(warpUpright(img.view(), {500.f, 5.f}, 20.f, 8.f, patch.view()));
    for (int v = 0; v < 8; ++v) {
        for (int u = 0; u < 8; ++u)
            EXPECT_GE(patch.view().row(v)[u], 190);
    }
}

TEST(UprightPatch, RejectsBadArgumentsWithoutTouchingThePatch)
{
    ImageBuffer img(20, 10, PixelFormat::Gray8);
    ImageBuffer rgb(20, 10, PixelFormat::RGB24);
    ImageBuffer patch(8, 8, PixelFormat::Gray8);
    patch.view().row(0)[0] = 77;
    EXPECT_FALSE(warpUpright(rgb.view(), {5.f, 5.f}, 0.f, 8.f, patch.view()));
    EXPECT_FALSE(warpUpright(img.view(), {5.f, 5.f}, 0.f, 0.f, patch.view()));
    EXPECT_FALSE(warpUpright(img.view(), {5.f, 5.f}, NAN, 8.f, patch.view()));
    EXPECT_FALSE(warpUpright(img.view(), {1e9f, 5.f}, 0.f, 8.f, patch.view()));
    EXPECT_FALSE(warpUpright(img.view(), {5.f, 5.f}, 0.f, 8.f, rgb.view()));
    EXPECT_EQ(patch.view().row(0)[0], 77);
}

TEST(UprightPatch, WarpRotatedOfUnitOneIntoAWideRegionIsACopy)
{
    // The tracker's tilted scans: a region of any shape, one patch pixel per image pixel.
    const ImageBuffer img = noiseImage(64, 48, 5);
    ImageBuffer patch(40, 20, PixelFormat::Gray8);
    ASSERT_TRUE(warpRotated(img.view(), {30.f, 25.f}, 0.f, 1.f, 1.f, patch.view()));
    for (int v = 0; v < 20; ++v) {
        for (int u = 0; u < 40; ++u)
            ASSERT_EQ(patch.view().row(v)[u], img.view().row(15 + v)[10 + u]) << u << "," << v;
    }
}

TEST(UprightPatch, WarpUprightIsWarpRotatedWithTheSideOverThePatch)
{
    const Point2f centre{80.3f, 61.7f};
    const ImageBuffer scene = rotatedScene(160, 120, centre, 22.0);
    ImageBuffer a(36, 36, PixelFormat::Gray8);
    ImageBuffer b(36, 36, PixelFormat::Gray8);
    ASSERT_TRUE(warpUpright(scene.view(), centre, 22.f, 54.f, a.view()));
    ASSERT_TRUE(warpRotated(scene.view(), centre, 22.f, 1.5f, 1.5f, b.view()));
    for (int v = 0; v < 36; ++v) {
        for (int u = 0; u < 36; ++u)
            ASSERT_EQ(a.view().row(v)[u], b.view().row(v)[u]) << u << "," << v;
    }
}

TEST(UprightPatch, WarpRotatedStraightensAWideRegionAndScalesEachAxis)
{
    const Point2f centre{80.f, 60.f};
    for (const double roll : {-25.0, 25.0}) {
        const ImageBuffer scene = rotatedScene(160, 120, centre, roll);
        ImageBuffer wide(60, 30, PixelFormat::Gray8);
        ASSERT_TRUE(
            warpRotated(scene.view(), centre, static_cast<float>(roll), 1.f, 1.f, wide.view()));
        EXPECT_LT(meanErrorToUpright(wide), 1.5) << roll;
    }
    // Units per axis: a horizontal ramp sampled every 2 pixels across, every pixel down.
    ImageBuffer ramp(64, 48, PixelFormat::Gray8);
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 64; ++x)
            ramp.view().row(y)[x] = static_cast<std::uint8_t>(3 * x + y);
    }
    ImageBuffer patch(16, 16, PixelFormat::Gray8);
    ASSERT_TRUE(warpRotated(ramp.view(), {32.f, 24.f}, 0.f, 2.f, 1.f, patch.view()));
    // Patch pixel (u, v) is at source (16.5 + 2u, 16 + v) in pixel-centre coordinates.
    for (int v = 0; v < 16; ++v) {
        for (int u = 0; u < 16; ++u)
            EXPECT_NEAR(patch.view().row(v)[u], 3 * (16.5 + 2 * u) + 16 + v, 0.51) << u << v;
    }
}

TEST(UprightPatch, WarpRotatedRejectsBadUnits)
{
    ImageBuffer img(20, 10, PixelFormat::Gray8);
    ImageBuffer patch(8, 8, PixelFormat::Gray8);
    patch.view().row(0)[0] = 77;
    EXPECT_FALSE(warpRotated(img.view(), {5.f, 5.f}, 0.f, 0.f, 1.f, patch.view()));
    EXPECT_FALSE(warpRotated(img.view(), {5.f, 5.f}, 0.f, 1.f, -1.f, patch.view()));
    EXPECT_FALSE(warpRotated(img.view(), {5.f, 5.f}, 0.f, INFINITY, 1.f, patch.view()));
    EXPECT_EQ(patch.view().row(0)[0], 77);
}

// The clamped Q16 bilinear warp as warpRotated defines it, pixel by pixel: the reference for
// its unclamped path (taken when the whole patch samples inside the image).
void referenceWarp(const ConstImageView& g, Point2f centre, float rollDegrees, double unitX,
                   double unitY, ImageView patch)
{
    const double rad = static_cast<double>(rollDegrees) * kPi / 180.0;
    const double c = std::cos(rad);
    const double s = std::sin(rad);
    const double u0 = (0.5 - 0.5 * patch.width) * unitX;
    const double v0 = (0.5 - 0.5 * patch.height) * unitY;
    const double x0 = centre.x + c * u0 - s * v0 - 0.5;
    const double y0 = centre.y + s * u0 + c * v0 - 0.5;
    const auto q = [](double v) { return static_cast<std::int32_t>(std::lrint(v * 65536.0)); };
    for (int v = 0; v < patch.height; ++v) {
        std::int32_t sx = q(x0 - s * unitY * v);
        std::int32_t sy = q(y0 + c * unitY * v);
        for (int u = 0; u < patch.width; ++u, sx += q(c * unitX), sy += q(s * unitX)) {
            const auto fx = static_cast<std::uint32_t>((sx >> 8) & 255);
            const auto fy = static_cast<std::uint32_t>((sy >> 8) & 255);
            const auto at = [&](int x, int y) -> std::uint32_t {
                return g.row(std::clamp(y, 0, g.height - 1))[std::clamp(x, 0, g.width - 1)];
            };
            const int ix = sx >> 16;
            const int iy = sy >> 16;
            const std::uint32_t top = at(ix, iy) * (256 - fx) + at(ix + 1, iy) * fx;
            const std::uint32_t bottom = at(ix, iy + 1) * (256 - fx) + at(ix + 1, iy + 1) * fx;
            patch.row(v)[u] =
                static_cast<std::uint8_t>((top * (256 - fy) + bottom * fy + 32768) >> 16);
        }
    }
}

TEST(UprightPatch, WarpRotatedInsideAndAtTheBorderIsTheClampedBilinearWarp)
{
    // Patches well inside (the unclamped path), touching the last row or column, and reaching
    // beyond the image, at many angles and units: every pixel as the clamped reference.
    const ImageBuffer img = noiseImage(97, 71, 5);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> cx(-10.f, 107.f), cy(-10.f, 81.f), roll(-40.f, 40.f),
        unit(0.3f, 2.5f);
    ImageBuffer got(37, 29, PixelFormat::Gray8);
    ImageBuffer want(37, 29, PixelFormat::Gray8);
    int inside = 0;
    for (int i = 0; i < 3000; ++i) {
        // Every other patch small and about the middle: mostly inside.
        const bool middle = i % 2 == 0;
        const Point2f c = middle ? Point2f{48.f + 0.2f * cx(rng), 35.f + 0.2f * cy(rng)}
                                 : Point2f{cx(rng), cy(rng)};
        const float r = i % 7 == 0 ? 0.f : roll(rng);
        const double ux = middle ? 0.4 * unit(rng) : unit(rng);
        const double uy = i % 3 == 0 ? ux : middle ? 0.4 * unit(rng) : unit(rng);
        ASSERT_TRUE(warpRotated(img.view(), c, r, ux, uy, got.view()));
        referenceWarp(img.view(), c, r, ux, uy, want.view());
        for (int v = 0; v < got.view().height; ++v)
            for (int u = 0; u < got.view().width; ++u)
                ASSERT_EQ(got.view().row(v)[u], want.view().row(v)[u])
                    << "at " << u << "," << v << " centre " << c.x << "," << c.y << " roll " << r;
        const double reach = 0.75 * (37 * ux + 29 * uy);
        inside += c.x - reach > 1 && c.y - reach > 1 && c.x + reach < 96 && c.y + reach < 70;
    }
    EXPECT_GT(inside, 300);  // the unclamped path was taken
}

TEST(UprightPatch, NoHeapAllocation)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting unavailable";
    const ImageBuffer scene = rotatedScene(160, 120, {80.f, 60.f}, 15.0);
    ImageBuffer patch(48, 48, PixelFormat::Gray8);
    testing_support::AllocationScope scope;
    EXPECT_TRUE(warpUpright(scene.view(), {80.f, 60.f}, 15.f, 60.f, patch.view()));
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}

}  // namespace

#if defined(__aarch64__)
#include "upright_patch_kernels.hpp"

TEST(UprightPatchKernels, NeonRowsAreTheScalarRowsBitForBit)
{
    // In-image rows at every kind of step (both signs, steeper than one pixel, sub-pixel), of
    // widths around the NEON kernel's eight samples, against the scalar reference.
    const ImageBuffer img = noiseImage(200, 150, 11);
    const ConstImageView g = img.view();
    std::mt19937 rng(5);
    std::uniform_int_distribution<std::int32_t> step(-3 << 16, 3 << 16);
    std::vector<std::uint8_t> scalar(64), neon(64);
    for (int trial = 0; trial < 2000; ++trial) {
        const int width = 1 + trial % 40;
        const std::int32_t sx0 = step(rng), sy0 = step(rng);
        const std::int32_t dx = trial % 5 == 0 ? (1 << 16) : sx0 / 8;
        const std::int32_t dy = trial % 7 == 0 ? 0 : sy0 / 8;
        // Start where the whole row and its right and lower neighbours stay inside.
        const std::int32_t sx = (100 << 16) - dx * (width / 2) + (sx0 & 0xffff);
        const std::int32_t sy = (75 << 16) - dy * (width / 2) + (sy0 & 0xffff);
        upright_detail::warpRowInsideScalar(g.data, g.stride, sx, sy, dx, dy, 0, width,
                                            scalar.data());
        upright_detail::warpRowInsideNeon(g.data, g.stride, sx, sy, dx, dy, width, neon.data());
        ASSERT_TRUE(std::equal(scalar.begin(), scalar.begin() + width, neon.begin()))
            << "trial " << trial << " width " << width;
    }
}
#endif
