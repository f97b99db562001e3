// warpUpright: the inverse rotation of a face's square into an upright patch, in fixed point.

#include "vision/upright_patch.hpp"

#include "vision/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vision {

namespace {

constexpr int kPosShift = 16;  // source positions in Q16
constexpr float kLimit = 16384.0f;

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
    // A row whose samples and their right and lower neighbours are all inside the image needs
    // no clamping (a face in view: the roll search warps it some thirty times). A row's
    // positions are linear in u, so its two ends bound them.
    const auto within = [](std::int64_t p, int max) {
        return (p >> kPosShift) >= 0 && (p >> kPosShift) < max;
    };
    const std::int64_t lastU = patch.width - 1;
    for (int v = 0; v < patch.height; ++v) {
        // Row starts from the exact start, so rounding does not accumulate down the patch.
        std::int32_t sx = q(x0 + dxv * v);
        std::int32_t sy = q(y0 + dyv * v);
        std::uint8_t* out = patch.row(v);
        if (within(sx, maxX) && within(sy, maxY) && within(sx + lastU * stepXu, maxX) &&
            within(sy + lastU * stepYu, maxY)) {
            // The same sums as below, without the clamps.
            for (int u = 0; u < patch.width; ++u, sx += stepXu, sy += stepYu) {
                const auto fx = static_cast<std::uint32_t>((sx >> (kPosShift - 8)) & 255);
                const auto fy = static_cast<std::uint32_t>((sy >> (kPosShift - 8)) & 255);
                const std::uint8_t* ra = gray.row(sy >> kPosShift) + (sx >> kPosShift);
                const std::uint8_t* rb = ra + gray.stride;
                const std::uint32_t top = ra[0] * (256 - fx) + ra[1] * fx;
                const std::uint32_t bottom = rb[0] * (256 - fx) + rb[1] * fx;
                out[u] = static_cast<std::uint8_t>((top * (256 - fy) + bottom * fy + 32768) >> 16);
            }
            continue;
        }
        for (int u = 0; u < patch.width; ++u, sx += stepXu, sy += stepYu) {
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
    return true;
}

}  // namespace vision
