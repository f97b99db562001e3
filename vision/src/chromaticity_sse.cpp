// x86-64 chromaticity kernels: SSE2 (the x86-64 baseline), SSE4.1, AVX2 and AVX-512. Arithmetic and
// its exactness argument: chromaticity_kernels.hpp and chromaticity.cpp. The SSE4.1, AVX2 and
// AVX-512 functions are compiled for their instruction sets with target attributes and only called
// when the CPU reports them (__builtin_cpu_supports, in chromaticity.cpp); the helpers they share
// with SSE2 use SSE2 instructions only.
#if defined(__x86_64__)

#include "chromaticity_kernels.hpp"

#include <immintrin.h>

#include <array>

#define MIRROR_INLINE __attribute__((always_inline)) inline
#define MIRROR_SSE41 __attribute__((target("sse4.1")))
#define MIRROR_AVX2 __attribute__((target("avx2,fma")))

namespace vision::chroma_detail {

namespace {

// ---- shared 128-bit arithmetic (SSE2 instructions only) ----------------------------------------

/// 65536 / s1 for 8 lanes s1 in 1..765 as two int32 vectors (truncated), by a reciprocal
/// estimate and one Newton step: relative error < 2^-21, far below the 2^-16 the proof needs.
MIRROR_INLINE void reciprocal8(__m128i s1, __m128i& m0, __m128i& m1) noexcept
{
    const __m128i zero = _mm_setzero_si128();
    const __m128 f0 = _mm_cvtepi32_ps(_mm_unpacklo_epi16(s1, zero));
    const __m128 f1 = _mm_cvtepi32_ps(_mm_unpackhi_epi16(s1, zero));
    const __m128 two = _mm_set1_ps(2.0f);
    const __m128 scale = _mm_set1_ps(65536.0f);
    const __m128 x0 = _mm_rcp_ps(f0);
    const __m128 x1 = _mm_rcp_ps(f1);
    m0 = _mm_cvttps_epi32(_mm_mul_ps(_mm_mul_ps(x0, scale), _mm_sub_ps(two, _mm_mul_ps(f0, x0))));
    m1 = _mm_cvttps_epi32(_mm_mul_ps(_mm_mul_ps(x1, scale), _mm_sub_ps(two, _mm_mul_ps(f1, x1))));
}

/// m = min(trunc(65536 / s1), 65535) as u16 lanes. SSE2 has only the signed 32->16 pack: bias
/// into the signed range and back (saturation gives the 65535 for s1 = 1).
MIRROR_INLINE __m128i reciprocal8Sse2(__m128i s1) noexcept
{
    __m128i m0, m1;
    reciprocal8(s1, m0, m1);
    const __m128i bias32 = _mm_set1_epi32(32768);
    const __m128i p = _mm_packs_epi32(_mm_sub_epi32(m0, bias32), _mm_sub_epi32(m1, bias32));
    return _mm_xor_si128(p, _mm_set1_epi16(static_cast<short>(0x8000)));
}

MIRROR_SSE41 MIRROR_INLINE __m128i reciprocal8Sse41(__m128i s1) noexcept
{
    __m128i m0, m1;
    reciprocal8(s1, m0, m1);
    return _mm_packus_epi32(m0, m1);
}

/// Per-pixel values every channel's quotient needs.
struct Sums8 {
    __m128i s1;    ///< max(sum, 1)
    __m128i s1m1;  ///< s1 - 1
    __m128i half;  ///< sum >> 1
    __m128i m;     ///< the reciprocal
};

/// The exact quotient round(255 c / sum) of 8 channel values c <= sum (u16 lanes).
MIRROR_INLINE __m128i quotient8(__m128i c, const Sums8& s) noexcept
{
    const __m128i n = _mm_add_epi16(_mm_mullo_epi16(c, _mm_set1_epi16(255)), s.half);
    const __m128i q0 = _mm_mulhi_epu16(n, s.m);
    const __m128i d = _mm_sub_epi16(n, _mm_mullo_epi16(q0, s.s1));
    return _mm_sub_epi16(q0, _mm_cmpgt_epi16(d, s.s1m1));  // d >= s1: one more
}

#define MIRROR_SUMS8(SUMS, SUM, RECIPROCAL)                \
    Sums8 SUMS;                                            \
    SUMS.s1 = _mm_max_epi16(SUM, _mm_set1_epi16(1));       \
    SUMS.s1m1 = _mm_sub_epi16(SUMS.s1, _mm_set1_epi16(1)); \
    SUMS.half = _mm_srli_epi16(SUM, 1);                    \
    SUMS.m = RECIPROCAL(SUMS.s1)

/// 8 pixels given as u16 channel vectors -> u16 quotients.
MIRROR_INLINE void pixels8Sse2(__m128i r, __m128i g, __m128i b, __m128i& qr, __m128i& qg,
                               __m128i& qb) noexcept
{
    const __m128i sum = _mm_add_epi16(_mm_add_epi16(r, g), b);
    MIRROR_SUMS8(s, sum, reciprocal8Sse2);
    qr = quotient8(r, s);
    qg = quotient8(g, s);
    qb = quotient8(b, s);
}

MIRROR_SSE41 MIRROR_INLINE void pixels8Sse41(__m128i r, __m128i g, __m128i b, __m128i& qr,
                                             __m128i& qg, __m128i& qb) noexcept
{
    const __m128i sum = _mm_add_epi16(_mm_add_epi16(r, g), b);
    MIRROR_SUMS8(s, sum, reciprocal8Sse41);
    qr = quotient8(r, s);
    qg = quotient8(g, s);
    qb = quotient8(b, s);
}

void tail(const std::uint8_t* p, int n, int step, int ri, int bi, std::uint8_t* r, std::uint8_t* g,
          std::uint8_t* b) noexcept
{
    for (int x = 0; x < n; ++x, p += step) {
        const int sum = p[0] + p[1] + p[2];
        r[x] = exactClamped(p[ri], sum);
        g[x] = exactClamped(p[1], sum);
        b[x] = exactClamped(p[bi], sum);
    }
}

/// The quotient kernel for tests: clamp c to sum as the table does, then the pixel arithmetic.
#define MIRROR_CHROMA_QUOTIENTS(RECIPROCAL)                                               \
    int i = 0;                                                                            \
    for (; i + 8 <= n; i += 8) {                                                          \
        const __m128i sum = _mm_loadu_si128(reinterpret_cast<const __m128i*>(sum16 + i)); \
        const __m128i cv =                                                                \
            _mm_min_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(c + i)), sum); \
        MIRROR_SUMS8(s, sum, RECIPROCAL);                                                 \
        const __m128i q = quotient8(cv, s);                                               \
        _mm_storel_epi64(reinterpret_cast<__m128i*>(out + i), _mm_packus_epi16(q, q));    \
    }                                                                                     \
    for (; i < n; ++i)                                                                    \
    out[i] = exactClamped(c[i], sum16[i])

inline std::int32_t load32(const std::uint8_t* p) noexcept
{
    std::int32_t v;
    __builtin_memcpy(&v, p, 4);
    return v;
}

}  // namespace

// ---- SSE2 --------------------------------------------------------------------------------------

void quotientsSse2(const std::uint16_t* c, const std::uint16_t* sum16, std::uint8_t* out,
                   int n) noexcept
{
    MIRROR_CHROMA_QUOTIENTS(reciprocal8Sse2);
}

void rowSse2(const ChromaticityTable&, const std::uint8_t* src, int n, Packing packing,
             std::uint8_t* r, std::uint8_t* g, std::uint8_t* b) noexcept
{
    const __m128i zero = _mm_setzero_si128();
    const __m128i low = _mm_set1_epi32(0xff);
    const bool four = packing == Packing::Xrgb8888;
    const int step = four ? 4 : 3;
    const int ri = packing == Packing::Rgb24 ? 0 : 2, bi = 2 - ri;
    int x = 0;
    // 8 pixels as two vectors of one pixel per 32-bit lane. 3-byte pixels (SSE2 has no byte
    // shuffle) are loaded as 4 bytes each, reading the next pixel's first byte: the loop stops
    // one pixel early so that byte is inside the row.
    for (; x + 8 + (four ? 0 : 1) <= n; x += 8) {
        const std::uint8_t* p = src + step * x;
        __m128i a, c;
        if (four) {
            a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
            c = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 16));
        } else {
            a = _mm_setr_epi32(load32(p), load32(p + 3), load32(p + 6), load32(p + 9));
            c = _mm_setr_epi32(load32(p + 12), load32(p + 15), load32(p + 18), load32(p + 21));
        }
        const __m128i c0 = _mm_packs_epi32(_mm_and_si128(a, low), _mm_and_si128(c, low));
        const __m128i c1 = _mm_packs_epi32(_mm_and_si128(_mm_srli_epi32(a, 8), low),
                                           _mm_and_si128(_mm_srli_epi32(c, 8), low));
        const __m128i c2 = _mm_packs_epi32(_mm_and_si128(_mm_srli_epi32(a, 16), low),
                                           _mm_and_si128(_mm_srli_epi32(c, 16), low));
        __m128i qr, qg, qb;
        if (ri == 0)
            pixels8Sse2(c0, c1, c2, qr, qg, qb);
        else
            pixels8Sse2(c2, c1, c0, qr, qg, qb);
        _mm_storel_epi64(reinterpret_cast<__m128i*>(r + x), _mm_packus_epi16(qr, zero));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(g + x), _mm_packus_epi16(qg, zero));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(b + x), _mm_packus_epi16(qb, zero));
    }
    tail(src + step * x, n - x, step, ri, bi, r + x, g + x, b + x);
}

// ---- SSE4.1 ------------------------------------------------------------------------------------

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

MIRROR_SSE41 MIRROR_INLINE __m128i gather3(__m128i a, __m128i b, __m128i c, int ch) noexcept
{
    return _mm_or_si128(_mm_or_si128(_mm_shuffle_epi8(a, _mm_load_si128(mask(ch, 0))),
                                     _mm_shuffle_epi8(b, _mm_load_si128(mask(ch, 1)))),
                        _mm_shuffle_epi8(c, _mm_load_si128(mask(ch, 2))));
}

/// 16 pixels as three byte vectors (r, g, b) -> the three planes.
MIRROR_SSE41 MIRROR_INLINE void pixels16Sse41(__m128i rv, __m128i gv, __m128i bv, std::uint8_t* r,
                                              std::uint8_t* g, std::uint8_t* b) noexcept
{
    const __m128i zero = _mm_setzero_si128();
    __m128i qr0, qg0, qb0, qr1, qg1, qb1;
    pixels8Sse41(_mm_cvtepu8_epi16(rv), _mm_cvtepu8_epi16(gv), _mm_cvtepu8_epi16(bv), qr0, qg0,
                 qb0);
    pixels8Sse41(_mm_unpackhi_epi8(rv, zero), _mm_unpackhi_epi8(gv, zero),
                 _mm_unpackhi_epi8(bv, zero), qr1, qg1, qb1);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(r), _mm_packus_epi16(qr0, qr1));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(g), _mm_packus_epi16(qg0, qg1));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(b), _mm_packus_epi16(qb0, qb1));
}

/// Bytes B,G,R,X of 4 pixels -> [B0..3 | G0..3 | R0..3 | X0..3].
alignas(16) constexpr std::int8_t kSplitXrgb[16] = {0, 4, 8,  12, 1, 5, 9,  13,
                                                    2, 6, 10, 14, 3, 7, 11, 15};

/// 16 XRGB pixels (64 bytes) to B, G, R byte vectors: one shuffle per load, then a dword
/// transpose.
MIRROR_SSE41 MIRROR_INLINE void splitXrgb16(const std::uint8_t* p, __m128i& bv, __m128i& gv,
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

}  // namespace

MIRROR_SSE41 void quotientsSse41(const std::uint16_t* c, const std::uint16_t* sum16,
                                 std::uint8_t* out, int n) noexcept
{
    MIRROR_CHROMA_QUOTIENTS(reciprocal8Sse41);
}

MIRROR_SSE41 void rowSse41(const ChromaticityTable&, const std::uint8_t* src, int n,
                           Packing packing, std::uint8_t* r, std::uint8_t* g,
                           std::uint8_t* b) noexcept
{
    int x = 0;
    if (packing == Packing::Xrgb8888) {
        for (; x + 16 <= n; x += 16) {
            __m128i bv, gv, rv;
            splitXrgb16(src + 4 * x, bv, gv, rv);
            pixels16Sse41(rv, gv, bv, r + x, g + x, b + x);
        }
        tail(src + 4 * x, n - x, 4, 2, 0, r + x, g + x, b + x);
        return;
    }
    const int ri = packing == Packing::Rgb24 ? 0 : 2, bi = 2 - ri;
    for (; x + 16 <= n; x += 16) {
        const auto* p = reinterpret_cast<const __m128i*>(src + 3 * x);
        const __m128i a = _mm_loadu_si128(p);
        const __m128i b1 = _mm_loadu_si128(p + 1);
        const __m128i c = _mm_loadu_si128(p + 2);
        const __m128i c0 = gather3(a, b1, c, 0);
        const __m128i c1 = gather3(a, b1, c, 1);
        const __m128i c2 = gather3(a, b1, c, 2);
        if (ri == 0)
            pixels16Sse41(c0, c1, c2, r + x, g + x, b + x);
        else
            pixels16Sse41(c2, c1, c0, r + x, g + x, b + x);
    }
    tail(src + 3 * x, n - x, 3, ri, bi, r + x, g + x, b + x);
}

// ---- AVX2 --------------------------------------------------------------------------------------
// The same arithmetic on 16 lanes. Pixels are de-interleaved per 128-bit half (pshufb works
// within halves): half 0 holds pixels 0-15, half 1 pixels 16-31; widening and the final pack also
// stay within halves, so the results come out in pixel order without lane-crossing permutes.

namespace {

MIRROR_AVX2 MIRROR_INLINE __m256i reciprocal16(__m256i s1) noexcept
{
    const __m256i zero = _mm256_setzero_si256();
    const __m256 f0 = _mm256_cvtepi32_ps(_mm256_unpacklo_epi16(s1, zero));
    const __m256 f1 = _mm256_cvtepi32_ps(_mm256_unpackhi_epi16(s1, zero));
    const __m256 two = _mm256_set1_ps(2.0f);
    const __m256 scale = _mm256_set1_ps(65536.0f);
    const __m256 x0 = _mm256_rcp_ps(f0);
    const __m256 x1 = _mm256_rcp_ps(f1);
    const __m256i m0 =
        _mm256_cvttps_epi32(_mm256_mul_ps(_mm256_mul_ps(x0, scale), _mm256_fnmadd_ps(f0, x0, two)));
    const __m256i m1 =
        _mm256_cvttps_epi32(_mm256_mul_ps(_mm256_mul_ps(x1, scale), _mm256_fnmadd_ps(f1, x1, two)));
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
        tail(src + 4 * x, n - x, 4, 2, 0, r + x, g + x, b + x);
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
    tail(src + 3 * x, n - x, 3, ri, bi, r + x, g + x, b + x);
}

// ---- AVX-512 (BW, VL, VBMI) --------------------------------------------------------------------
// 64 pixels per step: VBMI's two-source byte permute de-interleaves each channel of 3-byte pixels
// in two instructions, and compares write mask registers, so the correction is one masked add.
// Same arithmetic, 32 lanes.

#define MIRROR_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512vbmi,fma")))

// GCC 12's AVX-512 intrinsics start some results from _mm512_undefined_*(), which its
// -Wmaybe-uninitialized reports at every use (a known false positive of the headers).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace {

/// Byte indices for channel ch of 64 three-byte pixels: idx[0] into loads A,B (128 bytes; bit 6
/// selects B), idx[1] into load C for the pixels whose byte lies there (mask kFromC).
struct PermuteTables {
    std::uint8_t ab[3][64];
    std::uint8_t c[3][64];
    std::uint64_t fromC[3];
    std::uint8_t xrgbLow[3][64];   ///< channel bytes of pixels 0-31 from loads A,B into bytes 0-31
    std::uint8_t xrgbHigh[3][64];  ///< pixels 32-63 from loads C,D into bytes 32-63
};

constexpr PermuteTables makePermutes()
{
    PermuteTables t{};
    for (int ch = 0; ch < 3; ++ch) {
        t.fromC[ch] = 0;
        for (int p = 0; p < 64; ++p) {
            const int index = 3 * p + ch;
            if (index < 128) {
                t.ab[ch][p] = static_cast<std::uint8_t>(index);
            } else {
                t.c[ch][p] = static_cast<std::uint8_t>(index - 128);
                t.fromC[ch] |= std::uint64_t{1} << p;
            }
            // XRGB bytes B,G,R,X: channel byte (2 - ch) for R=0.. is chosen by the caller; here
            // ch means byte offset within the 4-byte pixel.
            const int x = 4 * (p % 32) + ch;  // 0..127 within the pair of loads
            (p < 32 ? t.xrgbLow : t.xrgbHigh)[ch][p] = static_cast<std::uint8_t>(x);
        }
    }
    return t;
}
alignas(64) constexpr PermuteTables kPermutes = makePermutes();

MIRROR_AVX512 MIRROR_INLINE __m512i loadIdx(const std::uint8_t* p) noexcept
{
    return _mm512_loadu_si512(p);
}

struct Sums32 {
    __m512i s1, half, m;
};

MIRROR_AVX512 MIRROR_INLINE Sums32 sums32(__m512i sum) noexcept
{
    Sums32 s;
    s.s1 = _mm512_max_epu16(sum, _mm512_set1_epi16(1));
    s.half = _mm512_srli_epi16(sum, 1);
    const __m512i zero = _mm512_setzero_si512();
    const __m512 f0 = _mm512_cvtepi32_ps(_mm512_unpacklo_epi16(s.s1, zero));
    const __m512 f1 = _mm512_cvtepi32_ps(_mm512_unpackhi_epi16(s.s1, zero));
    const __m512 two = _mm512_set1_ps(2.0f);
    const __m512 x0 = _mm512_rcp14_ps(f0);
    const __m512 x1 = _mm512_rcp14_ps(f1);
    // x * 65536 by adding 16 to the exponent (exact: x is a normal number near 1 / s1).
    const __m512i exp16 = _mm512_set1_epi32(16 << 23);
    const __m512 x0s = _mm512_castsi512_ps(_mm512_add_epi32(_mm512_castps_si512(x0), exp16));
    const __m512 x1s = _mm512_castsi512_ps(_mm512_add_epi32(_mm512_castps_si512(x1), exp16));
    const __m512i m0 = _mm512_cvttps_epi32(_mm512_mul_ps(x0s, _mm512_fnmadd_ps(f0, x0, two)));
    const __m512i m1 = _mm512_cvttps_epi32(_mm512_mul_ps(x1s, _mm512_fnmadd_ps(f1, x1, two)));
    s.m = _mm512_packus_epi32(m0, m1);
    return s;
}

MIRROR_AVX512 MIRROR_INLINE __m512i quotient32(__m512i c, const Sums32& s) noexcept
{
    // 255 c as 256 c - c: shift and subtract, leaving the multiplier pipes to the two products.
    const __m512i n = _mm512_add_epi16(_mm512_sub_epi16(_mm512_slli_epi16(c, 8), c), s.half);
    const __m512i q0 = _mm512_mulhi_epu16(n, s.m);
    const __m512i d = _mm512_sub_epi16(n, _mm512_mullo_epi16(q0, s.s1));
    return _mm512_mask_add_epi16(q0, _mm512_cmpge_epu16_mask(d, s.s1), q0, _mm512_set1_epi16(1));
}

/// 64 pixels as three byte vectors -> the three planes.
MIRROR_AVX512 MIRROR_INLINE void pixels64(__m512i rv, __m512i gv, __m512i bv, std::uint8_t* r,
                                          std::uint8_t* g, std::uint8_t* b) noexcept
{
    const __m512i zero = _mm512_setzero_si512();
    const __m512i r0 = _mm512_unpacklo_epi8(rv, zero), r1 = _mm512_unpackhi_epi8(rv, zero);
    const __m512i g0 = _mm512_unpacklo_epi8(gv, zero), g1 = _mm512_unpackhi_epi8(gv, zero);
    const __m512i b0 = _mm512_unpacklo_epi8(bv, zero), b1 = _mm512_unpackhi_epi8(bv, zero);
    const Sums32 s0 = sums32(_mm512_add_epi16(_mm512_add_epi16(r0, g0), b0));
    const Sums32 s1 = sums32(_mm512_add_epi16(_mm512_add_epi16(r1, g1), b1));
    _mm512_storeu_si512(r, _mm512_packus_epi16(quotient32(r0, s0), quotient32(r1, s1)));
    _mm512_storeu_si512(g, _mm512_packus_epi16(quotient32(g0, s0), quotient32(g1, s1)));
    _mm512_storeu_si512(b, _mm512_packus_epi16(quotient32(b0, s0), quotient32(b1, s1)));
}

MIRROR_AVX512 MIRROR_INLINE __m512i channel3(__m512i a, __m512i bb, __m512i c, int ch) noexcept
{
    const __m512i fromAb = _mm512_permutex2var_epi8(a, loadIdx(kPermutes.ab[ch]), bb);
    return _mm512_mask_permutexvar_epi8(fromAb, kPermutes.fromC[ch], loadIdx(kPermutes.c[ch]), c);
}

/// Byte `byte` of 64 four-byte pixels (loads a, b: pixels 0-31; c, d: pixels 32-63).
MIRROR_AVX512 MIRROR_INLINE __m512i channel4(__m512i a, __m512i bb, __m512i c, __m512i d,
                                             int byte) noexcept
{
    const __m512i low = _mm512_permutex2var_epi8(a, loadIdx(kPermutes.xrgbLow[byte]), bb);
    const __m512i high = _mm512_permutex2var_epi8(c, loadIdx(kPermutes.xrgbHigh[byte]), d);
    return _mm512_mask_blend_epi8(0xFFFFFFFF00000000ull, low, high);
}

}  // namespace

MIRROR_AVX512 void quotientsAvx512(const std::uint16_t* c, const std::uint16_t* sum16,
                                   std::uint8_t* out, int n) noexcept
{
    int i = 0;
    for (; i + 32 <= n; i += 32) {
        const __m512i sum = _mm512_loadu_si512(sum16 + i);
        const __m512i cv = _mm512_min_epu16(_mm512_loadu_si512(c + i), sum);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + i),
                            _mm512_cvtepi16_epi8(quotient32(cv, sums32(sum))));
    }
    for (; i < n; ++i)
        out[i] = exactClamped(c[i], sum16[i]);
}

MIRROR_AVX512 void rowAvx512(const ChromaticityTable&, const std::uint8_t* src, int n,
                             Packing packing, std::uint8_t* r, std::uint8_t* g,
                             std::uint8_t* b) noexcept
{
    int x = 0;
    if (packing == Packing::Xrgb8888) {
        for (; x + 64 <= n; x += 64) {
            const std::uint8_t* p = src + 4 * x;
            const __m512i a = _mm512_loadu_si512(p), bb = _mm512_loadu_si512(p + 64);
            const __m512i c = _mm512_loadu_si512(p + 128), d = _mm512_loadu_si512(p + 192);
            pixels64(channel4(a, bb, c, d, 2), channel4(a, bb, c, d, 1), channel4(a, bb, c, d, 0),
                     r + x, g + x, b + x);
        }
        tail(src + 4 * x, n - x, 4, 2, 0, r + x, g + x, b + x);
        return;
    }
    const int ri = packing == Packing::Rgb24 ? 0 : 2, bi = 2 - ri;
    for (; x + 64 <= n; x += 64) {
        const std::uint8_t* p = src + 3 * x;
        const __m512i a = _mm512_loadu_si512(p), bb = _mm512_loadu_si512(p + 64);
        const __m512i c = _mm512_loadu_si512(p + 128);
        pixels64(channel3(a, bb, c, ri), channel3(a, bb, c, 1), channel3(a, bb, c, bi), r + x,
                 g + x, b + x);
    }
    tail(src + 3 * x, n - x, 3, ri, bi, r + x, g + x, b + x);
}

#pragma GCC diagnostic pop
#undef MIRROR_AVX512

#undef MIRROR_CHROMA_QUOTIENTS
#undef MIRROR_SUMS8

}  // namespace vision::chroma_detail

#endif  // __x86_64__
