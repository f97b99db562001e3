// The AAM fit's integer kernels in NEON (aarch64): 8 pixels at a time, the same integers as the
// scalar reference (aam_kernels.hpp). The dot product widens each product into int32 lanes
// (vmlal), 16 products per lane per chunk, and adds each chunk's lanes into int64 (vpadal).
#if defined(__aarch64__)

#include "aam_kernels.hpp"

#include <arm_neon.h>

#include <algorithm>

namespace vision::aam {

void errorImageNeon(const std::int16_t* warped, const std::int16_t* mean, const std::int16_t* mask,
                    std::int32_t gain, std::int32_t bias, std::int16_t* error, int n) noexcept
{
    const int32x4_t vBias = vdupq_n_s32(bias);
    const int32x4_t low = vdupq_n_s32(-kErrorLimit), high = vdupq_n_s32(kErrorLimit);
    int i = 0;
    for (; i + 8 <= n; i += 8) {
        const int16x8_t a = vld1q_s16(mean + i);
        const int16x8_t w = vld1q_s16(warped + i);
        int32x4_t m0 = vshrq_n_s32(vmlaq_n_s32(vBias, vmovl_s16(vget_low_s16(a)), gain), 12);
        int32x4_t m1 = vshrq_n_s32(vmlaq_n_s32(vBias, vmovl_high_s16(a), gain), 12);
        int32x4_t e0 = vsubq_s32(vshll_n_s16(vget_low_s16(w), 4), m0);
        int32x4_t e1 = vsubq_s32(vshll_high_n_s16(w, 4), m1);
        e0 = vminq_s32(vmaxq_s32(e0, low), high);
        e1 = vminq_s32(vmaxq_s32(e1, low), high);
        const int16x8_t e = vcombine_s16(vmovn_s32(e0), vmovn_s32(e1));
        vst1q_s16(error + i, vandq_s16(e, vld1q_s16(mask + i)));
    }
    errorImageScalar(warped + i, mean + i, mask + i, gain, bias, error + i, n - i);
}

std::int64_t dotProductNeon(const std::int16_t* a, const std::int16_t* b, int n) noexcept
{
    int64x2_t total = vdupq_n_s64(0);
    int i = 0;
    while (i + 8 <= n) {
        const int end = std::min(n, i + kDotChunk);
        int32x4_t chunk = vdupq_n_s32(0);
        for (; i + 8 <= end; i += 8) {
            const int16x8_t va = vld1q_s16(a + i), vb = vld1q_s16(b + i);
            chunk = vmlal_s16(chunk, vget_low_s16(va), vget_low_s16(vb));
            chunk = vmlal_high_s16(chunk, va, vb);
        }
        total = vpadalq_s32(total, chunk);
    }
    return vaddvq_s64(total) + dotProductScalar(a + i, b + i, n - i);
}

}  // namespace vision::aam

#endif
