// The x86-64 development machine's chromaticity kernel: AVX2, 32 pixels per step. Arithmetic and
// its exactness argument: chromaticity_kernels.hpp and chromaticity.cpp. Built for AVX2 with
// MIRROR_AVX2 and called only when simd::hasAvx2() (simd.hpp).
#if defined(__x86_64__)

#include "chromaticity_kernels.hpp"
#include "simd.hpp"

#include <immintrin.h>

#include <array>

#define MIRROR_INLINE __attribute__((always_inline)) inline

namespace vision::chroma_detail {

namespace {

/// pshufb masks gathering channel ch (byte ch of each 3-byte pixel) of 16 pixels from the k-th of
/// three consecutive 16-byte loads; -128 (bit 7 set) clears the lanes other loads supply.
struct GatherMasks {
    std::array<std::int8_t, 16> m[9];  // [3 * ch + k]
};
constexpr GatherMasks makeMasks()
{
    GatherMasks g{};
    for (int ch = 0; ch < 3; ++ch)
        for (int k = 0; k < 3; ++k)
            for (int p = 0; p < 16; ++p) {
                const int index = 3 * p + ch;
                g.m[3 * ch + k][static_cast<std::size_t>(p)] =
                    index / 16 == k ? static_cast<std::int8_t>(index % 16)
                                    : static_cast<std::int8_t>(-128);
            }
    return g;
}
alignas(16) constexpr GatherMasks kMasks = makeMasks();

inline const __m128i* mask(int ch, int k) noexcept
{
    return reinterpret_cast<const __m128i*>(kMasks.m[3 * ch + k].data());
}

/// Bytes B,G,R,X of 4 pixels -> [B0..3 | G0..3 | R0..3 | X0..3].
alignas(16) constexpr std::int8_t kSplitXrgb[16] = {0, 4, 8,  12, 1, 5, 9,  13,
                                                    2, 6, 10, 14, 3, 7, 11, 15};

/// 16 XRGB pixels (64 bytes) to B, G, R byte vectors: one shuffle per load, then a dword
/// transpose.
MIRROR_AVX2 MIRROR_INLINE void splitXrgb16(const std::uint8_t* p, __m128i& bv, __m128i& gv,
                                           __m128i& rv) noexcept
{
    const __m128i split = _mm_load_si128(reinterpret_cast<const __m128i*>(kSplitXrgb));
    const auto* v = reinterpret_cast<const __m128i*>(p);
    const __m128i a0 = _mm_shuffle_epi8(_mm_loadu_si128(v), split);
    const __m128i a1 = _mm_shuffle_epi8(_mm_loadu_si128(v + 1), split);
    const __m128i a2 = _mm_shuffle_epi8(_mm_loadu_si128(v + 2), split);
    const __m128i a3 = _mm_shuffle_epi8(_mm_loadu_si128(v + 3), split);
    const __m128i t0 = _mm_unpacklo_epi32(a0, a1);  // B0-3 B4-7 G0-3 G4-7
    const __m128i t1 = _mm_unpacklo_epi32(a2, a3);  // B8-11 B12-15 G8-11 G12-15
    const __m128i t2 = _mm_unpackhi_epi32(a0, a1);  // R0-3 R4-7 X X
    const __m128i t3 = _mm_unpackhi_epi32(a2, a3);
    bv = _mm_unpacklo_epi64(t0, t1);
    gv = _mm_unpackhi_epi64(t0, t1);
    rv = _mm_unpacklo_epi64(t2, t3);
}

// The arithmetic on 16 lanes. Pixels are de-interleaved per 128-bit half (pshufb works within
// halves): half 0 holds pixels 0-15, half 1 pixels 16-31; widening and the final pack also stay
// within halves, so the results come out in pixel order without lane-crossing permutes.

/// m = min(trunc(65536 / s1), 65535) for 16 lanes s1 in 1..765, by a reciprocal estimate and one
/// Newton step: relative error < 2^-21, far below the 2^-16 the proof needs.
MIRROR_AVX2 MIRROR_INLINE __m256i reciprocal16(__m256i s1) noexcept
{
    const __m256i zero = _mm256_setzero_si256();
    const __m256 f0 = _mm256_cvtepi32_ps(_mm256_unpacklo_epi16(s1, zero));
    const __m256 f1 = _mm256_cvtepi32_ps(_mm256_unpackhi_epi16(s1, zero));
    const __m256 two = _mm256_set1_ps(2.0f);
    const __m256 scale = _mm256_set1_ps(65536.0f);
    const __m256 x0 = _mm256_rcp_ps(f0);
    const __m256 x1 = _mm256_rcp_ps(f1);
    const __m256i m0 = _mm256_cvttps_epi32(
        _mm256_mul_ps(_mm256_mul_ps(x0, scale), _mm256_sub_ps(two, _mm256_mul_ps(f0, x0))));
    const __m256i m1 = _mm256_cvttps_epi32(
        _mm256_mul_ps(_mm256_mul_ps(x1, scale), _mm256_sub_ps(two, _mm256_mul_ps(f1, x1))));
    return _mm256_packus_epi32(m0, m1);  // in-half unpack then pack: lane order restored
}

struct Sums16 {
    __m256i s1, s1m1, half, m;
};

MIRROR_AVX2 MIRROR_INLINE __m256i quotient16(__m256i c, const Sums16& s) noexcept
{
    const __m256i n = _mm256_add_epi16(_mm256_mullo_epi16(c, _mm256_set1_epi16(255)), s.half);
    const __m256i q0 = _mm256_mulhi_epu16(n, s.m);
    const __m256i d = _mm256_sub_epi16(n, _mm256_mullo_epi16(q0, s.s1));
    return _mm256_sub_epi16(q0, _mm256_cmpgt_epi16(d, s.s1m1));
}

MIRROR_AVX2 MIRROR_INLINE Sums16 sums16(__m256i sum) noexcept
{
    Sums16 s;
    s.s1 = _mm256_max_epi16(sum, _mm256_set1_epi16(1));
    s.s1m1 = _mm256_sub_epi16(s.s1, _mm256_set1_epi16(1));
    s.half = _mm256_srli_epi16(sum, 1);
    s.m = reciprocal16(s.s1);
    return s;
}

/// 16 pixels as u16 lanes -> u16 quotients.
MIRROR_AVX2 MIRROR_INLINE void pixels16Avx2(__m256i r, __m256i g, __m256i b, __m256i& qr,
                                            __m256i& qg, __m256i& qb) noexcept
{
    const Sums16 s = sums16(_mm256_add_epi16(_mm256_add_epi16(r, g), b));
    qr = quotient16(r, s);
    qg = quotient16(g, s);
    qb = quotient16(b, s);
}

/// 32 pixels as three byte vectors (half 0: pixels 0-15, half 1: 16-31) -> the three planes.
MIRROR_AVX2 MIRROR_INLINE void pixels32Avx2(__m256i rv, __m256i gv, __m256i bv, std::uint8_t* r,
                                            std::uint8_t* g, std::uint8_t* b) noexcept
{
    const __m256i zero = _mm256_setzero_si256();
    __m256i qr0, qg0, qb0, qr1, qg1, qb1;
    // lo: pixels 0-7 | 16-23, hi: 8-15 | 24-31; packus puts them back as 0-15 | 16-31.
    pixels16Avx2(_mm256_unpacklo_epi8(rv, zero), _mm256_unpacklo_epi8(gv, zero),
                 _mm256_unpacklo_epi8(bv, zero), qr0, qg0, qb0);
    pixels16Avx2(_mm256_unpackhi_epi8(rv, zero), _mm256_unpackhi_epi8(gv, zero),
                 _mm256_unpackhi_epi8(bv, zero), qr1, qg1, qb1);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(r), _mm256_packus_epi16(qr0, qr1));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(g), _mm256_packus_epi16(qg0, qg1));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(b), _mm256_packus_epi16(qb0, qb1));
}

MIRROR_AVX2 MIRROR_INLINE __m256i load2(const std::uint8_t* lo, const std::uint8_t* hi) noexcept
{
    return _mm256_inserti128_si256(
        _mm256_castsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(lo))),
        _mm_loadu_si128(reinterpret_cast<const __m128i*>(hi)), 1);
}

MIRROR_AVX2 MIRROR_INLINE __m256i broadcastMask(int ch, int k) noexcept
{
    return _mm256_broadcastsi128_si256(_mm_load_si128(mask(ch, k)));
}

}  // namespace

MIRROR_AVX2 void quotientsAvx2(const std::uint16_t* c, const std::uint16_t* sum16,
                               std::uint8_t* out, int n) noexcept
{
    int i = 0;
    for (; i + 16 <= n; i += 16) {
        const __m256i sum = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(sum16 + i));
        const __m256i cv =
            _mm256_min_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + i)), sum);
        const __m256i q = quotient16(cv, sums16(sum));
        const __m128i packed =
            _mm_packus_epi16(_mm256_castsi256_si128(q), _mm256_extracti128_si256(q, 1));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), packed);
    }
    for (; i < n; ++i)
        out[i] = exactClamped(c[i], sum16[i]);
}

MIRROR_AVX2 void rowAvx2(const ChromaticityTable&, const std::uint8_t* src, int n, Packing packing,
                         std::uint8_t* r, std::uint8_t* g, std::uint8_t* b) noexcept
{
    int x = 0;
    if (packing == Packing::Xrgb8888) {
        for (; x + 32 <= n; x += 32) {
            __m128i b0, g0, r0, b1, g1, r1;
            splitXrgb16(src + 4 * x, b0, g0, r0);
            splitXrgb16(src + 4 * x + 64, b1, g1, r1);
            pixels32Avx2(_mm256_set_m128i(r1, r0), _mm256_set_m128i(g1, g0),
                         _mm256_set_m128i(b1, b0), r + x, g + x, b + x);
        }
        rowTail(src + 4 * x, n - x, 4, 2, 0, r + x, g + x, b + x);
        return;
    }
    const int ri = packing == Packing::Rgb24 ? 0 : 2, bi = 2 - ri;
    const __m256i m00 = broadcastMask(0, 0), m01 = broadcastMask(0, 1), m02 = broadcastMask(0, 2);
    const __m256i m10 = broadcastMask(1, 0), m11 = broadcastMask(1, 1), m12 = broadcastMask(1, 2);
    const __m256i m20 = broadcastMask(2, 0), m21 = broadcastMask(2, 1), m22 = broadcastMask(2, 2);
    for (; x + 32 <= n; x += 32) {
        const std::uint8_t* p = src + 3 * x;
        const __m256i a = load2(p, p + 48);
        const __m256i bb = load2(p + 16, p + 64);
        const __m256i c = load2(p + 32, p + 80);
        const __m256i c0 = _mm256_or_si256(
            _mm256_or_si256(_mm256_shuffle_epi8(a, m00), _mm256_shuffle_epi8(bb, m01)),
            _mm256_shuffle_epi8(c, m02));
        const __m256i c1 = _mm256_or_si256(
            _mm256_or_si256(_mm256_shuffle_epi8(a, m10), _mm256_shuffle_epi8(bb, m11)),
            _mm256_shuffle_epi8(c, m12));
        const __m256i c2 = _mm256_or_si256(
            _mm256_or_si256(_mm256_shuffle_epi8(a, m20), _mm256_shuffle_epi8(bb, m21)),
            _mm256_shuffle_epi8(c, m22));
        if (ri == 0)
            pixels32Avx2(c0, c1, c2, r + x, g + x, b + x);
        else
            pixels32Avx2(c2, c1, c0, r + x, g + x, b + x);
    }
    rowTail(src + 3 * x, n - x, 3, ri, bi, r + x, g + x, b + x);
}

}  // namespace vision::chroma_detail

#endif  // __x86_64__
