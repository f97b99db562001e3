// NEON row kernel of warpRotated (aarch64): eight samples a step. Their positions, fractions and
// offsets are computed in vectors; each sample's two pixel pairs (a, b above and below) are loaded
// as two 16-bit lanes (the one scalar part: NEON has no gather); the blends are done in 16-bit
// lanes (a row's blend is at most 255 x 256) and the rounding in 32-bit ones, by vaddhn (the high
// half of the sum with 32768 is the scalar's >> 16). The same bytes as warpRowInsideScalar.
#if defined(__aarch64__)

#include "upright_patch_kernels.hpp"

#include <arm_neon.h>

#include <cstring>
#include <utility>

namespace vision::upright_detail {

namespace {

/// Lane K of `pairs` := the two bytes at base + offsets[K] (little-endian: the left one low).
template <int K>
inline uint16x8_t loadPair(uint16x8_t pairs, const std::uint8_t* base,
                           const std::int32_t* offsets) noexcept
{
    std::uint16_t v;
    std::memcpy(&v, base + offsets[K], sizeof v);
    return vsetq_lane_u16(v, pairs, K);
}

template <int... K>
inline uint16x8_t loadPairs(const std::uint8_t* base, const std::int32_t* offsets,
                            std::integer_sequence<int, K...>) noexcept
{
    uint16x8_t pairs = vdupq_n_u16(0);
    ((pairs = loadPair<K>(pairs, base, offsets)), ...);
    return pairs;
}

/// The row blend a (256 - fx) + b fx of eight pairs.
inline uint16x8_t blendPairs(uint16x8_t pairs, uint16x8_t fx, uint16x8_t gx) noexcept
{
    const uint16x8_t a = vandq_u16(pairs, vdupq_n_u16(255));
    const uint16x8_t b = vshrq_n_u16(pairs, 8);
    return vmlaq_u16(vmulq_u16(a, gx), b, fx);
}

/// The 8-bit fraction of eight Q16 positions.
inline uint16x8_t fractions(int32x4_t lo, int32x4_t hi) noexcept
{
    const int32x4_t mask = vdupq_n_s32(255);
    return vcombine_u16(
        vmovn_u32(vreinterpretq_u32_s32(vandq_s32(vshrq_n_s32(lo, kPosShift - 8), mask))),
        vmovn_u32(vreinterpretq_u32_s32(vandq_s32(vshrq_n_s32(hi, kPosShift - 8), mask))));
}

}  // namespace

void warpRowInsideNeon(const std::uint8_t* base, std::ptrdiff_t stride, std::int32_t sx,
                       std::int32_t sy, std::int32_t stepX, std::int32_t stepY, int width,
                       std::uint8_t* out) noexcept
{
    const int32x4_t lanes = {0, 1, 2, 3};
    const int32x4_t stride4 = vdupq_n_s32(static_cast<std::int32_t>(stride));
    const uint16x8_t full = vdupq_n_u16(256);
    const uint32x4_t half = vdupq_n_u32(32768);
    const auto sequence = std::make_integer_sequence<int, 8>{};
    int u = 0;
    for (; u + 8 <= width; u += 8) {
        // Positions of samples u .. u + 7: the scalar's running sums, exactly.
        const int32x4_t x0 = vmlaq_n_s32(vdupq_n_s32(sx + u * stepX), lanes, stepX);
        const int32x4_t x1 = vaddq_s32(x0, vdupq_n_s32(4 * stepX));
        const int32x4_t y0 = vmlaq_n_s32(vdupq_n_s32(sy + u * stepY), lanes, stepY);
        const int32x4_t y1 = vaddq_s32(y0, vdupq_n_s32(4 * stepY));
        std::int32_t offsets[8];
        vst1q_s32(offsets, vmlaq_s32(vshrq_n_s32(x0, kPosShift), vshrq_n_s32(y0, kPosShift),
                                     stride4));
        vst1q_s32(offsets + 4, vmlaq_s32(vshrq_n_s32(x1, kPosShift),
                                         vshrq_n_s32(y1, kPosShift), stride4));
        const uint16x8_t fx = fractions(x0, x1);
        const uint16x8_t fy = fractions(y0, y1);
        const uint16x8_t gx = vsubq_u16(full, fx);
        const uint16x8_t gy = vsubq_u16(full, fy);
        const uint16x8_t top = blendPairs(loadPairs(base, offsets, sequence), fx, gx);
        const uint16x8_t bottom = blendPairs(loadPairs(base + stride, offsets, sequence), fx, gx);
        const uint32x4_t lo =
            vmlal_u16(vmull_u16(vget_low_u16(top), vget_low_u16(gy)), vget_low_u16(bottom),
                      vget_low_u16(fy));
        const uint32x4_t hi = vmlal_high_u16(vmull_high_u16(top, gy), bottom, fy);
        vst1_u8(out + u, vmovn_u16(vcombine_u16(vaddhn_u32(lo, half), vaddhn_u32(hi, half))));
    }
    warpRowInsideScalar(base, stride, sx, sy, stepX, stepY, u, width, out);
}

}  // namespace vision::upright_detail

#endif
