// Shi-Tomasi corners: on a checkerboard's inner corners, inside the rectangle only, sorted by
// score, min distance and max count respected, flat images give none, no allocation.
#include "vision/corner_detector.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

using vision::Corner;
using vision::CornerDetector;
using vision::CornerDetectorOptions;
using vision::ImageBuffer;

namespace {

// Squares of `cell` pixels, the board's corner at (x0, y0), rows x cols squares, on grey.
ImageBuffer checkerboard(int w, int h, int x0, int y0, int cell, int rows, int cols)
{
    ImageBuffer img(w, h, vision::PixelFormat::Gray8);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t v = 128;
            const int cx = x - x0, cy = y - y0;
            if (cx >= 0 && cy >= 0 && cx < cols * cell && cy < rows * cell)
                v = ((cx / cell + cy / cell) % 2) ? 230 : 20;
            img.view().row(y)[x] = v;
        }
    return img;
}

}  // namespace

TEST(CornerDetector, FindsTheCheckerboardsInnerCorners)
{
    // 5x6 squares of 16 px at (40, 30): 4x5 = 20 inner corners at (40 + 16i, 30 + 16j) - 0.5.
    const ImageBuffer img = checkerboard(200, 160, 40, 30, 16, 5, 6);
    CornerDetector det({200, 160}, {.maxCorners = 100, .qualityLevel = 0.3f, .minDistance = 8.f});
    Corner c[100];
    const int n = det.detect(img.view(), {0, 0, 200, 160}, c, 100);
    int inner = 0;
    for (int j = 1; j < 5; ++j)
        for (int i = 1; i < 6; ++i) {
            const float x = 40.f + 16.f * i - 0.5f, y = 30.f + 16.f * j - 0.5f;
            bool hit = false;
            for (int k = 0; k < n; ++k)
                hit = hit || (std::fabs(c[k].position.x - x) <= 1.f &&
                              std::fabs(c[k].position.y - y) <= 1.f);
            inner += hit;
        }
    EXPECT_EQ(inner, 20);
    // Only the board's corners score: inner X-junctions and its outer corners, nothing else.
    EXPECT_LE(n, 20 + 4 + 2 * (4 + 5));
    for (int k = 1; k < n; ++k)
        EXPECT_GE(c[k - 1].score, c[k].score);
}

TEST(CornerDetector, RespectsTheRectangleMinDistanceAndMaxCount)
{
    const ImageBuffer img = checkerboard(200, 160, 10, 10, 6, 24, 30);
    CornerDetectorOptions opt;
    opt.maxCorners = 1000;
    opt.minDistance = 15.f;
    opt.qualityLevel = 0.05f;
    CornerDetector det({200, 160}, opt);
    Corner c[1000];
    const vision::Rect box{50, 40, 80, 70};
    const int n = det.detect(img.view(), box, c, 1000);
    ASSERT_GT(n, 10);
    for (int i = 0; i < n; ++i) {
        EXPECT_GE(c[i].position.x, box.x);
        EXPECT_LT(c[i].position.x, box.x + box.width);
        EXPECT_GE(c[i].position.y, box.y);
        EXPECT_LT(c[i].position.y, box.y + box.height);
        for (int j = 0; j < i; ++j)
            EXPECT_GE(
                std::hypot(c[i].position.x - c[j].position.x, c[i].position.y - c[j].position.y),
                15.f);
    }
    det.setMaxCorners(7);
    EXPECT_EQ(det.detect(img.view(), box, c, 1000), 7);
    det.setMaxCorners(100);
    EXPECT_EQ(det.detect(img.view(), box, c, 3), 3);  // the caller's capacity also limits
    det.setMinDistance(3.f);
    EXPECT_GT(det.detect(img.view(), box, c, 1000), n);
}

TEST(CornerDetector, BlobsGiveCornersNearThem)
{
    // Two bright squares (blobs) on black: their 8 corners.
    ImageBuffer img(120, 100, vision::PixelFormat::Gray8);
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 120; ++x)
            img.view().row(y)[x] = ((x >= 20 && x < 40 && y >= 20 && y < 45) ||
                                    (x >= 70 && x < 100 && y >= 50 && y < 80))
                                       ? 200
                                       : 10;
    CornerDetector det({120, 100}, {.maxCorners = 20, .qualityLevel = 0.2f, .minDistance = 5.f});
    Corner c[20];
    const int n = det.detect(img.view(), {0, 0, 120, 100}, c, 20);
    EXPECT_EQ(n, 8);
    const float xs[8] = {20, 39, 20, 39, 70, 99, 70, 99}, ys[8] = {20, 20, 44, 44, 50, 50, 79, 79};
    for (int k = 0; k < 8; ++k) {
        bool hit = false;
        for (int i = 0; i < n; ++i)
            hit = hit || std::hypot(c[i].position.x - xs[k], c[i].position.y - ys[k]) <= 1.5f;
        EXPECT_TRUE(hit) << k;
    }
}

TEST(CornerDetector, FlatImageOutsideAreaAndBadOptions)
{
    ImageBuffer flat(64, 48, vision::PixelFormat::Gray8);
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x)
            flat.view().row(y)[x] = 77;
    CornerDetector det({64, 48});
    Corner c[50];
    EXPECT_EQ(det.detect(flat.view(), {0, 0, 64, 48}, c, 50), 0);
    EXPECT_EQ(det.detect(flat.view(), {100, 100, 10, 10}, c, 50), 0);
    ImageBuffer big(65, 48, vision::PixelFormat::Gray8);
    EXPECT_EQ(det.detect(big.view(), {0, 0, 65, 48}, c, 50), 0);
    EXPECT_THROW(CornerDetector({64, 48}, {.blockSize = 4}), std::runtime_error);
    EXPECT_THROW(CornerDetector({0, 48}), std::runtime_error);
}

TEST(CornerDetector, DetectDoesNotAllocate)
{
    const ImageBuffer img = checkerboard(320, 240, 20, 20, 9, 20, 30);
    CornerDetector det({320, 240});
    Corner c[50];
    testing_support::AllocationScope scope;
    EXPECT_EQ(det.detect(img.view(), {0, 0, 320, 240}, c, 50), 50);
    EXPECT_GT(det.detect(img.view(), {60, 60, 100, 100}, c, 50), 0);
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}

// The scores are the smaller eigenvalue of the tensor summed over the block pixel by pixel (the
// definition): the detector sums it by rows, which in int32 is exact, so every corner must be the
// definition's and every score the definition's eigenvalue of the same sums, for each block size
// and for areas at the image's border. The eigenvalue's float formula is rounded as the compiler
// contracts it (fused multiply-adds on aarch64, not on x86-64 without -mfma), and it subtracts
// two numbers of the size of the trace: the same to a few float roundings of the trace.
TEST(CornerDetector, ScoresAreTheBlockSumsDefinition)
{
    const int w = 97, h = 61;
    ImageBuffer img(w, h, vision::PixelFormat::Gray8);
    std::uint32_t state = 12345;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            state = state * 1664525u + 1013904223u;
            // Smooth blobs plus noise: many local maxima, with ties unlikely.
            const double v = 128 + 60 * std::sin(x * 0.31) * std::cos(y * 0.23) + (state >> 28);
            img.view().row(y)[x] = static_cast<std::uint8_t>(v);
        }
    for (const int block : {3, 5, 7}) {
        for (const vision::Rect area : {vision::Rect{0, 0, w, h}, vision::Rect{10, 7, 40, 30},
                                        vision::Rect{70, 40, 40, 40}}) {
            CornerDetector det({w, h}, {.maxCorners = 400, .minDistance = 0.f, .blockSize = block});
            Corner got[400];
            const int n = det.detect(img.view(), area, got, 400);
            ASSERT_GT(n, 0);
            // The definition at each returned corner.
            const int r = block / 2;
            auto sobel = [&](int x, int y, bool wantX) {
                auto p = [&](int xx, int yy) { return static_cast<int>(img.view().row(yy)[xx]); };
                return wantX ? (p(x + 1, y - 1) - p(x - 1, y - 1)) +
                                   2 * (p(x + 1, y) - p(x - 1, y)) +
                                   (p(x + 1, y + 1) - p(x - 1, y + 1))
                             : (p(x - 1, y + 1) - p(x - 1, y - 1)) +
                                   2 * (p(x, y + 1) - p(x, y - 1)) +
                                   (p(x + 1, y + 1) - p(x + 1, y - 1));
            };
            for (int i = 0; i < n; ++i) {
                const int cx = static_cast<int>(got[i].position.x);
                const int cy = static_cast<int>(got[i].position.y);
                std::int32_t sxx = 0, sxy = 0, syy = 0;
                for (int by = -r; by <= r; ++by)
                    for (int bx = -r; bx <= r; ++bx) {
                        const int gx = sobel(cx + bx, cy + by, true);
                        const int gy = sobel(cx + bx, cy + by, false);
                        sxx += gx * gx;
                        sxy += gx * gy;
                        syy += gy * gy;
                    }
                const float a = static_cast<float>(sxx);
                const float b = static_cast<float>(sxy);
                const float c = static_cast<float>(syy);
                const float e = 0.5f * (a + c - std::sqrt((a - c) * (a - c) + 4.f * b * b));
                EXPECT_NEAR(got[i].score, e, 4e-7f * (a + c))
                    << "block " << block << " corner " << i;
                if (i > 0) {
                    EXPECT_GE(got[i - 1].score, got[i].score);
                }
            }
        }
    }
}
