#include "vision/motion_detector.hpp"

#include "alloc_counter.hpp"
#include "vision/motion_stage.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

using namespace vision;

namespace {

constexpr int kWidth = 320;  // small: the tests also run unoptimised and under qemu
constexpr int kHeight = 240;
constexpr int kSide = 48;  // square side at full resolution

/// A synthetic BGR24 camera: a static textured background with sensor noise, an optional
/// uniform square and a global brightness offset.
class Scene {
public:
    Scene() : frame_(kWidth, kHeight, PixelFormat::BGR24) {}

    ConstImageView render(int squareX, int squareY, int brightness = 0)
    {
        for (int y = 0; y < kHeight; ++y) {
            std::uint8_t* p = frame_.view().row(y);
            for (int x = 0; x < kWidth; ++x, p += 3) {
                const bool inSquare = squareX >= 0 && x >= squareX && x < squareX + kSide &&
                                      y >= squareY && y < squareY + kSide;
                const int base = inSquare ? 230 : 60 + ((x / 8) * 7 + (y / 8) * 13) % 97;
                for (int c = 0; c < 3; ++c) {
                    seed_ = seed_ * 1664525u + 1013904223u;
                    const int noise = static_cast<int>((seed_ >> 24) % 5) - 2;  // -2..2
                    p[c] = static_cast<std::uint8_t>(
                        std::clamp(base + brightness + noise + (c - 1) * 5, 0, 255));
                }
            }
        }
        return frame_.view();
    }

private:
    ImageBuffer frame_;
    std::uint32_t seed_ = 12345;
};

FrameState stateOf(ConstImageView image)
{
    FrameState s;
    s.frame.image = image;
    return s;
}

double fraction(const ConstImageView& mask)
{
    long n = 0;
    for (int y = 0; y < mask.height; ++y) {
        for (int x = 0; x < mask.width; ++x) {
            n += mask.row(y)[x] != 0;
        }
    }
    return static_cast<double>(n) / (mask.width * mask.height);
}

/// IoU of the mask with the half-resolution square at full-resolution (x, y).
double iouWithSquare(const ConstImageView& mask, int squareX, int squareY)
{
    const int x0 = squareX / 2, y0 = squareY / 2, x1 = x0 + kSide / 2, y1 = y0 + kSide / 2;
    long inter = 0, uni = 0;
    for (int y = 0; y < mask.height; ++y) {
        for (int x = 0; x < mask.width; ++x) {
            const bool truth = x >= x0 && x < x1 && y >= y0 && y < y1;
            const bool fg = mask.row(y)[x] != 0;
            inter += truth && fg;
            uni += truth || fg;
        }
    }
    return uni ? static_cast<double>(inter) / uni : 1.0;
}

/// Fraction of the half-resolution square region that is foreground.
double foregroundInSquare(const ConstImageView& mask, int squareX, int squareY)
{
    long n = 0;
    for (int y = squareY / 2; y < (squareY + kSide) / 2; ++y) {
        for (int x = squareX / 2; x < (squareX + kSide) / 2; ++x) {
            n += mask.row(y)[x] != 0;
        }
    }
    return static_cast<double>(n) / (kSide * kSide / 4);
}

}  // namespace

TEST(MotionDetector, StaticSceneHasNoForegroundAfterWarmUp)
{
    for (int k = 1; k <= 5; ++k) {
        Scene scene;
        MotionStageOptions options;
        options.detector.components = k;
        MotionStage stage({kWidth, kHeight}, options);
        EXPECT_EQ(stage.mask().width, kWidth / 2);
        EXPECT_EQ(stage.mask().height, kHeight / 2);
        for (int i = 0; i < 15; ++i) {
            FrameState s = stateOf(scene.render(-1, -1));
            stage.process(s);
            ASSERT_TRUE(stage.ok()) << stage.lastError();
        }
        EXPECT_LT(fraction(stage.mask()), 0.001) << "K=" << k;
        EXPECT_EQ(stage.maskIntegral().rectSum({0, 0, kWidth / 2, kHeight / 2}),
                  static_cast<std::uint32_t>(stage.foregroundPixels()) * 255u);
    }
}

TEST(MotionDetector, MovingSquareIsForegroundExactlyAroundIt)
{
    Scene scene;
    MotionStage stage({kWidth, kHeight});
    for (int i = 0; i < 10; ++i) {
        FrameState s = stateOf(scene.render(-1, -1));
        stage.process(s);
    }
    double minIou = 1.0;
    for (int i = 0; i < 20; ++i) {
        const int sx = 20 + 12 * i, sy = 40 + 4 * i;
        FrameState s = stateOf(scene.render(sx, sy));
        stage.process(s);
        ASSERT_TRUE(stage.ok());
        const double iou = iouWithSquare(stage.mask(), sx, sy);
        EXPECT_GT(iou, 0.8) << "frame " << i;
        minIou = std::min(minIou, iou);
        // The integral image answers the face detector's question for the square's window.
        EXPECT_GT(stage.maskIntegral().maskFraction({sx / 2, sy / 2, kSide / 2, kSide / 2}), 0.9f);
    }
    std::printf("moving square: smallest IoU with the true square %.3f\n", minIou);
}

TEST(MotionDetector, StoppedSquareBecomesBackgroundAfterTheModelledFrameCount)
{
    Scene scene;
    MotionStageOptions options;
    options.detector.learningRate = 0.02f;
    options.detector.backgroundRatio = 0.7f;
    MotionStage stage({kWidth, kHeight}, options);
    const int n = stage.detector().framesToBecomeBackground();
    EXPECT_EQ(n, 18);  // (1 - 0.02)^n <= 0.7
    for (int i = 0; i < 10; ++i) {
        FrameState s = stateOf(scene.render(-1, -1));
        stage.process(s);
    }
    // The square appears and stays: frame i (0 = appearance) is classified with the background
    // weight (1 - a)^i, foreground while that exceeds T.
    int firstBackground = -1;
    for (int i = 0; i < 3 * n; ++i) {
        FrameState s = stateOf(scene.render(120, 100));
        stage.process(s);
        const double fg = foregroundInSquare(stage.mask(), 120, 100);
        if (i < n - 2) {
            EXPECT_GT(fg, 0.99) << "frame " << i;
        }
        if (firstBackground < 0 && fg < 0.01) {
            firstBackground = i;
        }
    }
    std::printf("stopped square: background from frame %d, model says %d\n", firstBackground, n);
    EXPECT_GE(firstBackground, n - 2);
    EXPECT_LE(firstBackground, n + 1);
    EXPECT_LT(fraction(stage.mask()), 0.001);
}

TEST(MotionDetector, GlobalIlluminationChangeIsForegroundUntilRelearned)
{
    // Documented behaviour: a lamp switched on looks like a stopped object covering the frame.
    Scene scene;
    MotionStageOptions options;
    options.detector.learningRate = 0.02f;
    MotionStage stage({kWidth, kHeight}, options);
    for (int i = 0; i < 10; ++i) {
        FrameState s = stateOf(scene.render(-1, -1));
        stage.process(s);
    }
    FrameState lit = stateOf(scene.render(-1, -1, 40));
    stage.process(lit);
    EXPECT_GT(fraction(stage.mask()), 0.99);
    for (int i = 1; i <= stage.detector().framesToBecomeBackground() + 1; ++i) {
        FrameState s = stateOf(scene.render(-1, -1, 40));
        stage.process(s);
    }
    EXPECT_LT(fraction(stage.mask()), 0.001);
    // reset() is the immediate way out.
    stage.detector().reset();
    FrameState dark = stateOf(scene.render(-1, -1, -40));
    stage.process(dark);
    EXPECT_EQ(stage.foregroundPixels(), 0);
}

TEST(MotionDetector, ModelStaysNormalisedAndSorted)
{
    Scene scene;
    MotionDetectorOptions options;
    options.components = 4;
    options.learningRate = 0.05f;
    MotionStage stage({kWidth, kHeight}, {2, options});
    for (int i = 0; i < 30; ++i) {
        FrameState s = stateOf(scene.render(i % 3 == 0 ? -1 : 20 * i % 260, 100, i % 7));
        stage.process(s);
    }
    const MotionDetector& d = stage.detector();
    for (int y = 0; y < kHeight / 2; y += 3) {
        for (int x = 0; x < kWidth / 2; x += 2) {
            unsigned sum = 0;
            for (int k = 0; k < 4; ++k) {
                sum += d.weight(x, y, k);
                if (k > 0) {
                    ASSERT_LE(d.weight(x, y, k), d.weight(x, y, k - 1));
                }
                if (d.weight(x, y, k) != 0) {
                    ASSERT_GE(d.variance(x, y, k), 4 * 256);
                    ASSERT_LE(d.variance(x, y, k), 255 * 256);
                }
            }
            ASSERT_EQ(sum, 32768u);
        }
    }
}

TEST(MotionDetector, ProcessAllocatesNothing)
{
    if (!testing_support::allocationCountingAvailable()) {
        GTEST_SKIP() << "allocation counting not available in this build";
    }
    Scene scene;
    MotionStage stage({kWidth, kHeight});
    FrameState first = stateOf(scene.render(-1, -1));
    stage.process(first);
    const ConstImageView moving = scene.render(100, 100);
    ImageBuffer wrong(10, 10, PixelFormat::BGR24);
    testing_support::AllocationScope scope;
    for (int i = 0; i < 5; ++i) {
        FrameState s = stateOf(moving);
        stage.process(s);
    }
    FrameState bad = stateOf(wrong.view());
    stage.process(bad);
    const auto counts = scope.counts();
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
    EXPECT_FALSE(stage.ok());
    EXPECT_STREQ(stage.lastError(), "motion: cannot use a 10x10 BGR24 frame");
    EXPECT_TRUE(bad.valid);  // the other stages may still use the frame
    EXPECT_EQ(stage.foregroundPixels(), 0);
}

TEST(MotionDetector, RejectsBadOptionsAndMismatchedImages)
{
    MotionDetectorOptions bad;
    bad.components = 6;
    EXPECT_THROW(MotionDetector({10, 10}, bad), std::runtime_error);
    bad = {};
    bad.learningRate = 0.0f;
    EXPECT_THROW(MotionDetector({10, 10}, bad), std::runtime_error);
    bad = {};
    bad.maxVariance = 300.0f;
    EXPECT_THROW(MotionDetector({10, 10}, bad), std::runtime_error);
    EXPECT_THROW(MotionStage({720, 480}, {5, {}}), std::runtime_error);

    MotionDetector detector({10, 10});
    ImageBuffer gray(10, 10, PixelFormat::Gray8), mask(9, 10, PixelFormat::Gray8);
    EXPECT_EQ(detector.apply(gray.view(), mask.view()), -1);
}

TEST(DownscaleToGray, HalvingIsTheIntegerLumaOfEachBoxExactly)
{
    // The factor-2 path (NEON on aarch64 for 3-byte pixels, 8 outputs at a time, the rest
    // scalar): each output is (77 r + 150 g + 29 b + 512) >> 10 of the box's channel sums, for
    // widths with and without a remainder.
    for (const PixelFormat f : {PixelFormat::RGB24, PixelFormat::BGR24, PixelFormat::XRGB8888}) {
        for (const int width : {2, 16, 17, 38, 64, 101, 720}) {
            const int height = 6;
            ImageBuffer src(width, height, f);
            const int bpp = bytesPerPixel(f);
            std::uint32_t seed = 7u + static_cast<std::uint32_t>(width);
            for (int y = 0; y < height; ++y) {
                for (int i = 0; i < width * bpp; ++i) {
                    seed = seed * 1664525u + 1013904223u;
                    // Extremes too: the largest sums must not overflow a lane.
                    const std::uint8_t v = static_cast<std::uint8_t>(seed >> 24);
                    src.view().row(y)[i] = y == 0 ? 255 : (y == 1 ? 0 : v);
                }
            }
            ImageBuffer dst(width / 2, height / 2, PixelFormat::Gray8);
            ASSERT_TRUE(downscaleToGray(src.view(), 2, dst.view()));
            const RgbLayout lay = rgbLayout(f);
            for (int y = 0; y < height / 2; ++y) {
                for (int x = 0; x < width / 2; ++x) {
                    unsigned sum[3] = {0, 0, 0};
                    for (int dy = 0; dy < 2; ++dy) {
                        for (int dx = 0; dx < 2; ++dx) {
                            const std::uint8_t* p =
                                src.view().row(2 * y + dy) + (2 * x + dx) * bpp;
                            sum[0] += p[lay.r];
                            sum[1] += p[lay.g];
                            sum[2] += p[lay.b];
                        }
                    }
                    const unsigned want = (77 * sum[0] + 150 * sum[1] + 29 * sum[2] + 512) >> 10;
                    ASSERT_EQ(dst.view().row(y)[x], want)
                        << pixelFormatName(f) << " width " << width << " at " << x << "," << y;
                }
            }
        }
    }
}

TEST(DownscaleToGray, BoxFilterMatchesFloatingPointReference)
{
    const PixelFormat formats[] = {PixelFormat::RGB24, PixelFormat::BGR24, PixelFormat::XRGB8888,
                                   PixelFormat::Gray8};
    for (const PixelFormat f : formats) {
        for (int factor = 1; factor <= 4; ++factor) {
            ImageBuffer src(37, 29, f);
            const int bpp = bytesPerPixel(f);
            std::uint32_t seed = 99;
            for (int y = 0; y < 29; ++y) {
                for (int i = 0; i < 37 * bpp; ++i) {
                    seed = seed * 1664525u + 1013904223u;
                    src.view().row(y)[i] = static_cast<std::uint8_t>(seed >> 24);
                }
            }
            ImageBuffer dst(37 / factor, 29 / factor, PixelFormat::Gray8);
            ASSERT_TRUE(downscaleToGray(src.view(), factor, dst.view()));
            const RgbLayout lay = rgbLayout(f);
            for (int y = 0; y < dst.view().height; ++y) {
                for (int x = 0; x < dst.view().width; ++x) {
                    double sum = 0;
                    for (int dy = 0; dy < factor; ++dy) {
                        for (int dx = 0; dx < factor; ++dx) {
                            const std::uint8_t* p =
                                src.view().row(y * factor + dy) + (x * factor + dx) * bpp;
                            sum += f == PixelFormat::Gray8
                                       ? p[0]
                                       : (77.0 * p[lay.r] + 150.0 * p[lay.g] + 29.0 * p[lay.b]) /
                                             256.0;
                        }
                    }
                    const double expected = sum / (factor * factor);
                    ASSERT_NEAR(dst.view().row(y)[x], expected, 0.51)
                        << pixelFormatName(f) << " factor " << factor << " at " << x << "," << y;
                }
            }
        }
    }
    ImageBuffer src(20, 20, PixelFormat::YUYV), dst(10, 10, PixelFormat::Gray8);
    EXPECT_FALSE(downscaleToGray(src.view(), 2, dst.view()));
    ImageBuffer rgb(20, 20, PixelFormat::RGB24), small(9, 10, PixelFormat::Gray8);
    EXPECT_FALSE(downscaleToGray(rgb.view(), 2, small.view()));
}
