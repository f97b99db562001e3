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
}

void CornerDetector::setMaxCorners(int count) noexcept
{
    options_.maxCorners = std::max(1, count);
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
    // Structure tensor over the block (int32: at most 49 * 1020^2) and its smaller eigenvalue.
    float* score = score_.get();
    float best = 0.f;
    for (int y = 0; y < sh; ++y) {
        for (int x = 0; x < sw; ++x) {
            std::int32_t sxx = 0;
            std::int32_t sxy = 0;
            std::int32_t syy = 0;
            for (int by = 0; by <= 2 * r; ++by) {
                const std::int16_t* px = dx + (y + by) * gw + x;
                const std::int16_t* py = dy + (y + by) * gw + x;
                for (int bx = 0; bx <= 2 * r; ++bx) {
                    sxx += px[bx] * px[bx];
                    sxy += px[bx] * py[bx];
                    syy += py[bx] * py[bx];
                }
            }
            const float a = static_cast<float>(sxx);
            const float b = static_cast<float>(sxy);
            const float c = static_cast<float>(syy);
            const float e = 0.5f * (a + c - std::sqrt((a - c) * (a - c) + 4.f * b * b));
            score[y * sw + x] = e;
            best = std::max(best, e);
        }
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
