#pragma once
// Internal: warpRotated's row kernel for a row whose samples and their right and lower neighbours
// all lie inside the image (upright_patch.cpp). Not installed.
//
// Sample u of the row is at (sx + u stepX, sy + u stepY) in Q16 source pixels (minus 0.5, as
// warpRotated sets them up); its value is the bilinear blend of the four pixels about it with
// 8-bit weights, rounded: ((top (256 - fy) + bottom fy + 32768) >> 16), top and bottom the rows'
// blends a (256 - fx) + b fx. The scalar loop is the reference; the NEON kernel gives the same
// bytes.

#include <cstddef>
#include <cstdint>

namespace vision::upright_detail {

constexpr int kPosShift = 16;  // source positions in Q16

/// Samples u0 <= u < width of an in-image row into out[u].
inline void warpRowInsideScalar(const std::uint8_t* base, std::ptrdiff_t stride, std::int32_t sx,
                                std::int32_t sy, std::int32_t stepX, std::int32_t stepY, int u0,
                                int width, std::uint8_t* out) noexcept
{
    sx += u0 * stepX;
    sy += u0 * stepY;
    for (int u = u0; u < width; ++u, sx += stepX, sy += stepY) {
        const auto fx = static_cast<std::uint32_t>((sx >> (kPosShift - 8)) & 255);
        const auto fy = static_cast<std::uint32_t>((sy >> (kPosShift - 8)) & 255);
        const std::uint8_t* ra =
            base + static_cast<std::ptrdiff_t>(sy >> kPosShift) * stride + (sx >> kPosShift);
        const std::uint8_t* rb = ra + stride;
        const std::uint32_t top = ra[0] * (256 - fx) + ra[1] * fx;
        const std::uint32_t bottom = rb[0] * (256 - fx) + rb[1] * fx;
        out[u] = static_cast<std::uint8_t>((top * (256 - fy) + bottom * fy + 32768) >> 16);
    }
}

#if defined(__aarch64__)
/// NEON, eight samples a step (upright_patch_neon.cpp); the same bytes as the scalar loop. The
/// image's offsets must fit in int32 (stride x height < 2^31).
void warpRowInsideNeon(const std::uint8_t* base, std::ptrdiff_t stride, std::int32_t sx,
                       std::int32_t sy, std::int32_t stepX, std::int32_t stepY, int width,
                       std::uint8_t* out) noexcept;
#endif

}  // namespace vision::upright_detail
