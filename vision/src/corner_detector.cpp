// Shi-Tomasi corners inside a rectangle (METHOD.md §3 tracking, §4 roll), in integer arithmetic
// up to the eigenvalue.
#include "vision/corner_detector.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vision {

CornerDetector::CornerDetector(Size maxImage, const CornerDetectorOptions& options)
    : options_(options), maxImage_(maxImage)
{
    if (maxImage.width <= 0 || maxImage.height <= 0) {
        throw std::runtime_error("CornerDetector: empty image size");
    }
    if (options.blockSize < 3 || options.blockSize > 7 || options.blockSize % 2 == 0 ||
        options.maxCorners < 1 || !(options.qualityLevel > 0.f && options.qualityLevel < 1.f)) {
        throw std::runtime_error(
            "CornerDetector: blockSize must be odd in 3..7, maxCorners >= 1, qualityLevel in "
            "(0,1)");
    }
    const std::size_t area = static_cast<std::size_t>(maxImage.width) * maxImage.height;
    dx_ = std::make_unique<std::int16_t[]>(area);
    dy_ = std::make_unique<std::int16_t[]>(area);
    score_ = std::make_unique<float[]>(area);
    candidates_ = std::make_unique<Candidate[]>(area);
    ring_ = std::make_unique<std::int32_t[]>(static_cast<std::size_t>(7) * 3 * maxImage.width);
    tensor_ = std::make_unique<std::int32_t[]>(static_cast<std::size_t>(3) * maxImage.width);
}

void CornerDetector::setMaxCorners(int count) noexcept
{
    options_.maxCorners = std::max(1, count);
}

std::int32_t* CornerDetector::ringRow(int slot) noexcept
{
    return ring_.get() + static_cast<std::ptrdiff_t>(slot) * 3 * maxImage_.width;
}

void CornerDetector::sumBlockColumns(const std::int16_t* dx, const std::int16_t* dy, int width,
                                     int side, std::int32_t* out) noexcept
{
    const std::ptrdiff_t plane = maxImage_.width;
    std::int32_t* __restrict xx = out;
    std::int32_t* __restrict xy = out + plane;
    std::int32_t* __restrict yy = out + 2 * plane;
    for (int x = 0; x < width; ++x) {
        xx[x] = dx[x] * dx[x];
        xy[x] = dx[x] * dy[x];
        yy[x] = dy[x] * dy[x];
    }
    for (int bx = 1; bx < side; ++bx) {
        const std::int16_t* __restrict px = dx + bx;
        const std::int16_t* __restrict py = dy + bx;
        for (int x = 0; x < width; ++x) {
            xx[x] += px[x] * px[x];
            xy[x] += px[x] * py[x];
            yy[x] += py[x] * py[x];
        }
    }
}

float CornerDetector::scoreRow(int side, float* __restrict out, int width) noexcept
{
    const std::ptrdiff_t plane = maxImage_.width;
    std::int32_t* __restrict sxx = tensor_.get();
    std::int32_t* __restrict sxy = sxx + plane;
    std::int32_t* __restrict syy = sxx + 2 * plane;
    // Each plane (xx, xy, yy) summed over the ring's rows on its own: simple loops vectorise.
    for (int p = 0; p < 3; ++p) {
        std::int32_t* __restrict dst = sxx + p * plane;
        const std::int32_t* __restrict first = ringRow(0) + p * plane;
        for (int x = 0; x < width; ++x)
            dst[x] = first[x];
        for (int k = 1; k < side; ++k) {
            const std::int32_t* __restrict src = ringRow(k) + p * plane;
            for (int x = 0; x < width; ++x)
                dst[x] += src[x];
        }
    }
    for (int x = 0; x < width; ++x) {
        const float a = static_cast<float>(sxx[x]);
        const float b = static_cast<float>(sxy[x]);
        const float c = static_cast<float>(syy[x]);
        out[x] = 0.5f * (a + c - std::sqrt((a - c) * (a - c) + 4.f * b * b));
    }
    // The row's largest score, apart: a running maximum would keep the loop above scalar.
    float best = 0.f;
    for (int x = 0; x < width; ++x)
        best = best < out[x] ? out[x] : best;
    return best;
}

int CornerDetector::detect(ConstImageView gray, Rect area, Corner* out, int capacity) noexcept
{
    if (gray.empty() || gray.format != PixelFormat::Gray8 || gray.width > maxImage_.width ||
        gray.height > maxImage_.height || capacity <= 0) {
        return 0;
    }
    const int r = options_.blockSize / 2;
    // Scored pixels: inside the area and far enough from the border for the block and Sobel.
    const int vx0 = r + 1;
    const int vy0 = r + 1;
    const int vx1 = gray.width - r - 1;  // exclusive
    const int vy1 = gray.height - r - 1;
    const int ax0 = std::max(area.x, vx0);
    const int ay0 = std::max(area.y, vy0);
    const int ax1 = std::min(area.x + area.width, vx1);
    const int ay1 = std::min(area.y + area.height, vy1);
    if (ax1 - ax0 < 1 || ay1 - ay0 < 1) {
        return 0;
    }
    // Scores over the area and a one-pixel rim (for the local-maximum test at its edge).
    const int sx0 = std::max(ax0 - 1, vx0);
    const int sy0 = std::max(ay0 - 1, vy0);
    const int sx1 = std::min(ax1 + 1, vx1);
    const int sy1 = std::min(ay1 + 1, vy1);
    const int sw = sx1 - sx0;
    const int sh = sy1 - sy0;
    // Gradients over the scored pixels and the block's rim.
    const int gx0 = sx0 - r;
    const int gy0 = sy0 - r;
    const int gw = sw + 2 * r;
    const int gh = sh + 2 * r;
    std::int16_t* dx = dx_.get();
    std::int16_t* dy = dy_.get();
    for (int y = 0; y < gh; ++y) {
        const std::uint8_t* up = gray.row(gy0 + y - 1) + gx0;
        const std::uint8_t* mid = gray.row(gy0 + y) + gx0;
        const std::uint8_t* dn = gray.row(gy0 + y + 1) + gx0;
        std::int16_t* ox = dx + y * gw;
        std::int16_t* oy = dy + y * gw;
        for (int x = 0; x < gw; ++x) {
            ox[x] = static_cast<std::int16_t>(
                (up[x + 1] - up[x - 1]) + 2 * (mid[x + 1] - mid[x - 1]) + (dn[x + 1] - dn[x - 1]));
            oy[x] = static_cast<std::int16_t>((dn[x - 1] - up[x - 1]) + 2 * (dn[x] - up[x]) +
                                              (dn[x + 1] - up[x + 1]));
        }
    }
    // Structure tensor over the block (int32: at most 49 * 1020^2) and its smaller eigenvalue,
    // a row at a time: the block's sums are those of its rows' sums over its columns, added in
    // the same int32 (exact), so the scores are those of summing the block pixel by pixel. Each
    // pass runs over a whole row (the compiler vectorises them); a gradient row's column sums
    // are kept in a ring of 2r + 1 rows.
    const int side = 2 * r + 1;
    float* score = score_.get();
    float best = 0.f;
    for (int g = 0; g < gh; ++g) {
        sumBlockColumns(dx + g * gw, dy + g * gw, sw, side, ringRow(g % side));
        if (g < side - 1)
            continue;
        const int y = g - (side - 1);
        best = std::max(best, scoreRow(side, score + y * sw, sw));
    }
    if (!(best > 0.f)) {
        return 0;
    }
    // Local maxima over 3x3 (neighbours outside the scored pixels count as zero) above the
    // quality threshold.
    const float threshold = best * options_.qualityLevel;
    Candidate* cand = candidates_.get();
    int count = 0;
    for (int y = ay0 - sy0; y < ay1 - sy0; ++y) {
        for (int x = ax0 - sx0; x < ax1 - sx0; ++x) {
            const float v = score[y * sw + x];
            if (v <= threshold) {
                continue;
            }
            bool isMax = true;
            for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, sh - 1) && isMax; ++ny) {
                for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, sw - 1); ++nx) {
                    if (score[ny * sw + nx] > v) {
                        isMax = false;
                        break;
                    }
                }
            }
            if (isMax) {
                cand[count++] = {v, y * sw + x};
            }
        }
    }
    std::sort(cand, cand + count, [](const Candidate& p, const Candidate& q) {
        return p.score > q.score || (p.score == q.score && p.index < q.index);
    });
    // Strongest first, each kept only when no kept corner is closer than minDistance.
    const int limit = std::min(options_.maxCorners, capacity);
    const float minD2 = options_.minDistance * options_.minDistance;
    int kept = 0;
    for (int i = 0; i < count && kept < limit; ++i) {
        const Point2f p{static_cast<float>(sx0 + cand[i].index % sw),
                        static_cast<float>(sy0 + cand[i].index / sw)};
        bool farEnough = true;
        for (int j = 0; j < kept; ++j) {
            const float ddx = out[j].position.x - p.x;
            const float ddy = out[j].position.y - p.y;
            if (ddx * ddx + ddy * ddy < minD2) {
                farEnough = false;
                break;
            }
        }
        if (farEnough) {
            out[kept++] = {p, cand[i].score};
        }
    }
    return kept;
}

}  // namespace vision
