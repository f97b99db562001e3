// NEON chromaticity kernel (aarch64): the same arithmetic as the AVX2 kernel
// (chromaticity_kernels.hpp), with vld3/vld4 de-interleaving the pixels. The reciprocal uses the
// IEEE division aarch64 has (correctly rounded), so m = trunc(65536 / s1) exactly.
#if defined(__aarch64__)

#include "chromaticity_kernels.hpp"

#include <arm_neon.h>

namespace vision::chroma_detail {

namespace {

/// m = min(trunc(65536 / s1), 65535) for s1 in 1..765 (saturating narrow gives the 65535).
inline uint16x8_t reciprocal8(uint16x8_t s1) noexcept
{
    const float32x4_t scale = vdupq_n_f32(65536.0f);
    const float32x4_t f0 = vcvtq_f32_u32(vmovl_u16(vget_low_u16(s1)));
    const float32x4_t f1 = vcvtq_f32_u32(vmovl_u16(vget_high_u16(s1)));
    return vcombine_u16(vqmovn_u32(vcvtq_u32_f32(vdivq_f32(scale, f0))),
                        vqmovn_u32(vcvtq_u32_f32(vdivq_f32(scale, f1))));
}

struct Sums8 {
    uint16x8_t s1, half, m;
};

inline Sums8 sums8(uint16x8_t sum) noexcept
{
    Sums8 s;
    s.s1 = vmaxq_u16(sum, vdupq_n_u16(1));
    s.half = vshrq_n_u16(sum, 1);
    s.m = reciprocal8(s.s1);
    return s;
}

/// The exact quotient round(255 c / sum) of 8 channel values c <= sum.
inline uint16x8_t quotient8(uint16x8_t c, const Sums8& s) noexcept
{
    const uint16x8_t n = vmlaq_n_u16(s.half, c, 255);
    const uint16x8_t q0 =
        vcombine_u16(vshrn_n_u32(vmull_u16(vget_low_u16(n), vget_low_u16(s.m)), 16),
                     vshrn_n_u32(vmull_u16(vget_high_u16(n), vget_high_u16(s.m)), 16));
    const uint16x8_t d = vmlsq_u16(n, q0, s.s1);  // in [0, 2 s1)
    return vsubq_u16(q0, vcgeq_u16(d, s.s1));     // all-ones mask is -1
}

inline void pixels8(uint16x8_t r, uint16x8_t g, uint16x8_t b, uint16x8_t& qr, uint16x8_t& qg,
                    uint16x8_t& qb) noexcept
{
    const Sums8 s = sums8(vaddq_u16(vaddq_u16(r, g), b));
    qr = quotient8(r, s);
    qg = quotient8(g, s);
    qb = quotient8(b, s);
}

inline void pixels16(uint8x16_t rv, uint8x16_t gv, uint8x16_t bv, std::uint8_t* r, std::uint8_t* g,
                     std::uint8_t* b) noexcept
{
    uint16x8_t qr0, qg0, qb0, qr1, qg1, qb1;
    pixels8(vmovl_u8(vget_low_u8(rv)), vmovl_u8(vget_low_u8(gv)), vmovl_u8(vget_low_u8(bv)), qr0,
            qg0, qb0);
    pixels8(vmovl_u8(vget_high_u8(rv)), vmovl_u8(vget_high_u8(gv)), vmovl_u8(vget_high_u8(bv)), qr1,
            qg1, qb1);
    vst1q_u8(r, vcombine_u8(vqmovn_u16(qr0), vqmovn_u16(qr1)));
    vst1q_u8(g, vcombine_u8(vqmovn_u16(qg0), vqmovn_u16(qg1)));
    vst1q_u8(b, vcombine_u8(vqmovn_u16(qb0), vqmovn_u16(qb1)));
}

}  // namespace

void quotientsNeon(const std::uint16_t* c, const std::uint16_t* sum, std::uint8_t* out,
                   int n) noexcept
{
    int i = 0;
    for (; i + 8 <= n; i += 8) {
        const uint16x8_t s = vld1q_u16(sum + i);
        const uint16x8_t q = quotient8(vminq_u16(vld1q_u16(c + i), s), sums8(s));
        vst1_u8(out + i, vqmovn_u16(q));
    }
    for (; i < n; ++i)
        out[i] = exactClamped(c[i], sum[i]);
}

void rowNeon(const ChromaticityTable&, const std::uint8_t* src, int n, Packing packing,
             std::uint8_t* r, std::uint8_t* g, std::uint8_t* b) noexcept
{
    int x = 0;
    if (packing == Packing::Xrgb8888) {
        for (; x + 16 <= n; x += 16) {
            const uint8x16x4_t v = vld4q_u8(src + 4 * x);  // B, G, R, X
            pixels16(v.val[2], v.val[1], v.val[0], r + x, g + x, b + x);
        }
        rowTail(src + 4 * x, n - x, 4, 2, 0, r + x, g + x, b + x);
        return;
    }
    const bool rgb = packing == Packing::Rgb24;
    for (; x + 16 <= n; x += 16) {
        const uint8x16x3_t v = vld3q_u8(src + 3 * x);
        if (rgb)
            pixels16(v.val[0], v.val[1], v.val[2], r + x, g + x, b + x);
        else
            pixels16(v.val[2], v.val[1], v.val[0], r + x, g + x, b + x);
    }
    rowTail(src + 3 * x, n - x, 3, rgb ? 0 : 2, rgb ? 2 : 0, r + x, g + x, b + x);
}

}  // namespace vision::chroma_detail

#endif  // __aarch64__
