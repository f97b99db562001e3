// NEON frame difference (aarch64): vld3/vld4 de-interleave 16 pixels of this and the previous
// frame, the absolute differences are summed in 16-bit lanes (at most 765) and compared with the
// threshold, and the mask takes the colour test's answer by a bit select where the sum is above
// it. The previous row is overwritten in the same pass (no second pass of memcpy). The row's last
// w % 16 pixels go through the scalar reference.
#if defined(__aarch64__)

#include "frame_difference_kernels.hpp"

#include <arm_neon.h>

#include <algorithm>

namespace vision::difference_detail {

namespace {

struct BandVectors {
    uint8x16_t lo[3], span[3], none;
};

BandVectors vectorsOf(const ColorBands& b) noexcept
{
    BandVectors v;
    for (int c = 0; c < 3; ++c) {
        v.lo[c] = vdupq_n_u8(b.lo[c]);
        v.span[c] = vdupq_n_u8(b.span[c]);
    }
    v.none = vdupq_n_u8(b.none);
    return v;
}

/// 0xff where |d0| + |d1| + |d2| > limit16 (all lanes when `all`).
inline uint8x16_t changed16(uint8x16_t d0, uint8x16_t d1, uint8x16_t d2, uint16x8_t limit16,
                            uint8x16_t all) noexcept
{
    const uint16x8_t lo = vaddw_u8(vaddl_u8(vget_low_u8(d0), vget_low_u8(d1)), vget_low_u8(d2));
    const uint16x8_t hi = vaddw_high_u8(vaddl_high_u8(d0, d1), d2);
    const uint8x16_t above =
        vcombine_u8(vmovn_u16(vcgtq_u16(lo, limit16)), vmovn_u16(vcgtq_u16(hi, limit16)));
    return vorrq_u8(above, all);
}

/// 0xff where every chromaticity channel is in its band.
inline uint8x16_t match16(const Row& row, int x, const BandVectors& v) noexcept
{
    const uint8x16_t r = vcleq_u8(vsubq_u8(vld1q_u8(row.r + x), v.lo[0]), v.span[0]);
    const uint8x16_t g = vcleq_u8(vsubq_u8(vld1q_u8(row.g + x), v.lo[1]), v.span[1]);
    const uint8x16_t b = vcleq_u8(vsubq_u8(vld1q_u8(row.b + x), v.lo[2]), v.span[2]);
    return vandq_u8(vandq_u8(r, g), vandq_u8(b, v.none));
}

/// The 16 pixels at x, given their channel differences; returns the change mask.
inline uint8x16_t update16(const Row& row, int x, uint8x16_t d0, uint8x16_t d1, uint8x16_t d2,
                           uint16x8_t limit16, uint8x16_t all, const BandVectors& v) noexcept
{
    const uint8x16_t change = changed16(d0, d1, d2, limit16, all);
    const uint8x16_t old = vld1q_u8(row.mask + x);
    vst1q_u8(row.mask + x, vbslq_u8(change, match16(row, x, v), old));
    return change;
}

template <int Step>
int updateRowNeon(const Row& row, int w, int limit, const ColorBands& bands) noexcept
{
    const BandVectors v = vectorsOf(bands);
    // limit < 0: every pixel changed; above 765 none can be (the sum's largest value).
    const uint8x16_t all = vdupq_n_u8(limit < 0 ? 0xff : 0);
    const uint16x8_t limit16 = vdupq_n_u16(static_cast<std::uint16_t>(std::clamp(limit, 0, 765)));
    int changed = 0;
    int x = 0;
    uint8x16_t count = vdupq_n_u8(0);  // changed pixels per lane, flushed before it can wrap
    for (int steps = 0; x + 16 <= w; x += 16) {
        uint8x16_t change;
        if constexpr (Step == 3) {
            const uint8x16x3_t a = vld3q_u8(row.p + 3 * x);
            const uint8x16x3_t b = vld3q_u8(row.q + 3 * x);
            vst3q_u8(row.q + 3 * x, a);
            change = update16(row, x, vabdq_u8(a.val[0], b.val[0]), vabdq_u8(a.val[1], b.val[1]),
                              vabdq_u8(a.val[2], b.val[2]), limit16, all, v);
        } else {
            const uint8x16x4_t a = vld4q_u8(row.p + 4 * x);
            const uint8x16x4_t b = vld4q_u8(row.q + 4 * x);
            vst4q_u8(row.q + 4 * x, a);
            change = update16(row, x, vabdq_u8(a.val[0], b.val[0]), vabdq_u8(a.val[1], b.val[1]),
                              vabdq_u8(a.val[2], b.val[2]), limit16, all, v);
        }
        count = vsubq_u8(count, change);  // 0xff is -1
        if (++steps == 255) {
            changed += vaddlvq_u8(count);
            count = vdupq_n_u8(0);
            steps = 0;
        }
    }
    changed += vaddlvq_u8(count);
    changed += testRowScalar<Step>(row, x, w, limit, bands);
    std::memcpy(row.q + Step * x, row.p + Step * x, static_cast<std::size_t>(w - x) * Step);
    return changed;
}

}  // namespace

int updateRowNeon3(const Row& row, int w, int limit, const ColorBands& bands) noexcept
{
    return updateRowNeon<3>(row, w, limit, bands);
}

int updateRowNeon4(const Row& row, int w, int limit, const ColorBands& bands) noexcept
{
    return updateRowNeon<4>(row, w, limit, bands);
}

}  // namespace vision::difference_detail

#endif
