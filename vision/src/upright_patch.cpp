// warpUpright: the inverse rotation of a face's square into an upright patch, in fixed point.

#include "vision/upright_patch.hpp"

#include "upright_patch_kernels.hpp"
#include "vision/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vision {

namespace {

using upright_detail::kPosShift;  // source positions in Q16
constexpr float kLimit = 16384.0f;

/// One in-image row (upright_patch_kernels.hpp): NEON where there is NEON and the image's
/// offsets fit its 32-bit lanes.
void warpRowInside(const ConstImageView& gray, std::int32_t sx, std::int32_t sy,
                   std::int32_t stepX, std::int32_t stepY, int width, std::uint8_t* out) noexcept
{
#if defined(__aarch64__)
    if (gray.stride * static_cast<std::ptrdiff_t>(gray.height) < (std::ptrdiff_t{1} << 31)) {
        upright_detail::warpRowInsideNeon(gray.data, gray.stride, sx, sy, stepX, stepY, width,
                                          out);
        return;
    }
#endif
    upright_detail::warpRowInsideScalar(gray.data, gray.stride, sx, sy, stepX, stepY, 0, width,
                                        out);
}

/// Samples u0 <= u < u1 of a row (sample u at (sx + u stepX, sy + u stepY), Q16), each of its
/// four pixels clamped to the image: the border repeated.
void warpRowClamped(const ConstImageView& gray, std::int32_t sx, std::int32_t sy,
                    std::int32_t stepX, std::int32_t stepY, int u0, int u1,
                    std::uint8_t* out) noexcept
{
    const int maxX = gray.width - 1;
    const int maxY = gray.height - 1;
    sx += u0 * stepX;
    sy += u0 * stepY;
    for (int u = u0; u < u1; ++u, sx += stepX, sy += stepY) {
        const int ix = sx >> kPosShift;  // floor (arithmetic shift)
        const int iy = sy >> kPosShift;
        const auto fx = static_cast<std::uint32_t>((sx >> (kPosShift - 8)) & 255);
        const auto fy = static_cast<std::uint32_t>((sy >> (kPosShift - 8)) & 255);
        const int xa = std::clamp(ix, 0, maxX);
        const int xb = std::clamp(ix + 1, 0, maxX);
        const std::uint8_t* ra = gray.row(std::clamp(iy, 0, maxY));
        const std::uint8_t* rb = gray.row(std::clamp(iy + 1, 0, maxY));
        const std::uint32_t top = ra[xa] * (256 - fx) + ra[xb] * fx;
        const std::uint32_t bottom = rb[xa] * (256 - fx) + rb[xb] * fx;
        out[u] = static_cast<std::uint8_t>((top * (256 - fy) + bottom * fy + 32768) >> 16);
    }
}

/// The run [first, end) of a row's samples for which `inside(u)` holds (0 <= position >> 16 <
/// max on both axes; the intersection of four half-lines in u, so one run): solved in doubles,
/// then settled exactly by `inside` at its ends. An empty run gives first == end.
template <class Inside>
void insideRun(std::int32_t sx, std::int32_t sy, std::int32_t stepX, std::int32_t stepY, int maxX,
               int maxY, int width, const Inside& inside, int& first, int& end) noexcept
{
    double lo = 0.0, hi = width;
    const auto clip = [&lo, &hi](double start, double step, double limit) {
        // 0 <= start + u step < limit.
        if (step == 0.0) {
            if (start < 0.0 || start >= limit)
                hi = lo;
            return;
        }
        const double a = -start / step, b = (limit - start) / step;
        lo = std::max(lo, std::min(a, b));
        hi = std::min(hi, std::max(a, b));
    };
    clip(sx, stepX, static_cast<double>(maxX) * (1 << kPosShift));
    clip(sy, stepY, static_cast<double>(maxY) * (1 << kPosShift));
    if (!(hi > lo)) {
        first = end = 0;
        return;
    }
    first = std::clamp(static_cast<int>(std::ceil(lo)), 0, width);
    end = std::clamp(static_cast<int>(std::ceil(hi)), first, width);
    while (first < end && !inside(first))
        ++first;
    while (end > first && !inside(end - 1))
        --end;
    if (first == end) {
        first = end = 0;
        return;
    }
    while (first > 0 && inside(first - 1))
        --first;
    while (end < width && inside(end))
        ++end;
}

}  // namespace

bool warpUpright(const ConstImageView& gray, Point2f centre, float rollDegrees, float sourceSide,
                 ImageView patch) noexcept
{
    if (patch.empty() || !(sourceSide > 0.0f) || !std::isfinite(sourceSide))
        return false;
    return warpRotated(gray, centre, rollDegrees, static_cast<double>(sourceSide) / patch.width,
                       static_cast<double>(sourceSide) / patch.height, patch);
}

Size rotatedCanvas(Size s, float degrees) noexcept
{
    const float c = std::fabs(std::cos(toRadians(degrees)));
    const float n = std::fabs(std::sin(toRadians(degrees)));
    const float w = static_cast<float>(s.width) * c + static_cast<float>(s.height) * n;
    const float h = static_cast<float>(s.width) * n + static_cast<float>(s.height) * c;
    return {static_cast<int>(std::ceil(w)) + 16, static_cast<int>(std::ceil(h)) + 16};
}

bool warpRotated(const ConstImageView& gray, Point2f centre, float rollDegrees, double unitX,
                 double unitY, ImageView patch) noexcept
{
    if (gray.empty() || gray.format != PixelFormat::Gray8 || patch.empty() ||
        patch.format != PixelFormat::Gray8) {
        return false;
    }
    if (!(unitX > 0.0) || !(unitY > 0.0) || !std::isfinite(unitX) || !std::isfinite(unitY) ||
        !std::isfinite(rollDegrees) || !std::isfinite(centre.x) || !std::isfinite(centre.y)) {
        return false;
    }
    const double rad = toRadians(static_cast<double>(rollDegrees));
    const double c = std::cos(rad);
    const double s = std::sin(rad);
    // One patch pixel is `unit` source pixels along the rotated axes.
    // Source position (in pixel-centre coordinates: minus 0.5) of patch pixel (0, 0)'s centre,
    // and the steps along a patch row (u) and down a column (v).
    const double u0 = (0.5 - 0.5 * patch.width) * unitX;
    const double v0 = (0.5 - 0.5 * patch.height) * unitY;
    const double x0 = centre.x + c * u0 - s * v0 - 0.5;
    const double y0 = centre.y + s * u0 + c * v0 - 0.5;
    const double dxu = c * unitX;
    const double dyu = s * unitX;
    const double dxv = -s * unitY;
    const double dyv = c * unitY;
    // Every position is within the square's bounding box: bound it so Q16 fits in int32.
    const double reach = std::fabs(dxu) * patch.width + std::fabs(dxv) * patch.height +
                         std::fabs(dyu) * patch.width + std::fabs(dyv) * patch.height;
    if (std::fabs(x0) + reach > kLimit + gray.width || std::fabs(y0) + reach > kLimit + gray.height)
        return false;

    const double one = 1 << kPosShift;
    const auto q = [one](double v) { return static_cast<std::int32_t>(std::lrint(v * one)); };
    const std::int32_t stepXu = q(dxu);
    const std::int32_t stepYu = q(dyu);
    const int maxX = gray.width - 1;
    const int maxY = gray.height - 1;
    // Samples whose pixels and their right and lower neighbours are all inside the image need no
    // clamping (a face in view: the roll search warps it some forty times a frame; a face at the
    // image's edge has most of each row inside).
    const auto within = [](std::int64_t p, int max) {
        return (p >> kPosShift) >= 0 && (p >> kPosShift) < max;
    };
    for (int v = 0; v < patch.height; ++v) {
        // Row starts from the exact start, so rounding does not accumulate down the patch.
        std::int32_t sx = q(x0 + dxv * v);
        std::int32_t sy = q(y0 + dyv * v);
        std::uint8_t* out = patch.row(v);
        // The samples whose four pixels are all inside form one run (the positions are linear
        // in u): blended there without clamps, and with them either side of it.
        const auto inside = [&](int u) {
            return within(sx + std::int64_t{u} * stepXu, maxX) &&
                   within(sy + std::int64_t{u} * stepYu, maxY);
        };
        int first = 0, end = patch.width;
        if (!(inside(0) && inside(patch.width - 1)))
            insideRun(sx, sy, stepXu, stepYu, maxX, maxY, patch.width, inside, first, end);
        warpRowClamped(gray, sx, sy, stepXu, stepYu, 0, first, out);
        if (first < end)
            warpRowInside(gray, sx + first * stepXu, sy + first * stepYu, stepXu, stepYu,
                          end - first, out + first);
        warpRowClamped(gray, sx, sy, stepXu, stepYu, end, patch.width, out);
    }
    return true;
}

}  // namespace vision
