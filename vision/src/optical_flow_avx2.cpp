// AVX2 builds of pyramidal Lucas-Kanade's window kernels (lk_window.hpp), for an x86-64
// development machine; called only when simd::hasAvx2().
#if defined(__x86_64__)

#include "lk_window.hpp"

#include <immintrin.h>

namespace vision::lk_detail {

namespace {

/// Pairs (w00, w01) and (w10, w11) as 32-bit lanes, for _mm256_madd_epi16 on (p[c], p[c + 1]).
struct WeightPairs {
    __m256i top;
    __m256i bottom;
};

MIRROR_AVX2 inline WeightPairs weightPairs(const Bilinear& w) noexcept
{
    const auto pair = [](int lo, int hi) {
        return static_cast<int>(static_cast<std::uint32_t>(lo) |
                                (static_cast<std::uint32_t>(hi) << 16));
    };
    return {_mm256_set1_epi32(pair(w.w00, w.w01)), _mm256_set1_epi32(pair(w.w10, w.w11))};
}

/// 16 bilinear samples (5 fractional bits) from s0[0..16] and s1[0..16].
MIRROR_AVX2 inline __m256i bilinear16(const std::uint8_t* s0, const std::uint8_t* s1,
                                      const WeightPairs& wp) noexcept
{
    constexpr int shift = kWeightBits - kValueBits;
    const __m256i round = _mm256_set1_epi32(1 << (shift - 1));
    const __m256i a = _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(s0)));
    const __m256i b =
        _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(s0 + 1)));
    const __m256i c = _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(s1)));
    const __m256i d =
        _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(s1 + 1)));
    // unpacklo/hi work within 128-bit halves and packs undoes that, so the order is kept.
    __m256i lo = _mm256_add_epi32(_mm256_madd_epi16(_mm256_unpacklo_epi16(a, b), wp.top),
                                  _mm256_madd_epi16(_mm256_unpacklo_epi16(c, d), wp.bottom));
    __m256i hi = _mm256_add_epi32(_mm256_madd_epi16(_mm256_unpackhi_epi16(a, b), wp.top),
                                  _mm256_madd_epi16(_mm256_unpackhi_epi16(c, d), wp.bottom));
    lo = _mm256_srai_epi32(_mm256_add_epi32(lo, round), shift);
    hi = _mm256_srai_epi32(_mm256_add_epi32(hi, round), shift);
    return _mm256_packs_epi32(lo, hi);
}

/// 8 bilinear samples from s0[0..8] and s1[0..8] (reads no further).
MIRROR_AVX2 inline __m128i bilinear8(const std::uint8_t* s0, const std::uint8_t* s1,
                                     const WeightPairs& wp) noexcept
{
    constexpr int shift = kWeightBits - kValueBits;
    const __m128i round = _mm_set1_epi32(1 << (shift - 1));
    const __m128i top = _mm256_castsi256_si128(wp.top);
    const __m128i bottom = _mm256_castsi256_si128(wp.bottom);
    const __m128i a = _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(s0)));
    const __m128i b = _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(s0 + 1)));
    const __m128i c = _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(s1)));
    const __m128i d = _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(s1 + 1)));
    __m128i lo = _mm_add_epi32(_mm_madd_epi16(_mm_unpacklo_epi16(a, b), top),
                               _mm_madd_epi16(_mm_unpacklo_epi16(c, d), bottom));
    __m128i hi = _mm_add_epi32(_mm_madd_epi16(_mm_unpackhi_epi16(a, b), top),
                               _mm_madd_epi16(_mm_unpackhi_epi16(c, d), bottom));
    lo = _mm_srai_epi32(_mm_add_epi32(lo, round), shift);
    hi = _mm_srai_epi32(_mm_add_epi32(hi, round), shift);
    return _mm_packs_epi32(lo, hi);
}

/// Sum of the eight 32-bit lanes, exactly.
MIRROR_AVX2 inline std::int64_t sumLanes(__m256i v) noexcept
{
    const __m256i wide = _mm256_add_epi64(_mm256_cvtepi32_epi64(_mm256_castsi256_si128(v)),
                                          _mm256_cvtepi32_epi64(_mm256_extracti128_si256(v, 1)));
    const __m128i h =
        _mm_add_epi64(_mm256_castsi256_si128(wide), _mm256_extracti128_si256(wide, 1));
    return _mm_cvtsi128_si64(h) + _mm_extract_epi64(h, 1);
}

// Products of a value difference (|d| <= 255 * 32) and a gradient (|g| <= 16 * 255) stay under
// 2^26, two per multiply-add lane: 32-bit lane sums are flushed to 64 bits every 8 rows, before
// they could overflow (at most 2 chunks of 16 per row for windows up to 31).
constexpr int kFlushRows = 8;

}  // namespace

/// sampleInside with AVX2: whole 16-value chunks, the rest scalar.
MIRROR_AVX2 void sampleInsideAvx2(ConstImageView img, const Bilinear& w, int rows, int cols,
                                  int outStride, std::int16_t* out) noexcept
{
    constexpr int shift = kWeightBits - kValueBits;
    constexpr int round = 1 << (shift - 1);
    const WeightPairs wp = weightPairs(w);
    for (int r = 0; r < rows; ++r) {
        const std::uint8_t* s0 = img.row(w.y0 + r) + w.x0;
        const std::uint8_t* s1 = s0 + img.stride;
        std::int16_t* o = out + r * outStride;
        int c = 0;
        for (; c + 16 <= cols; c += 16) {
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + c), bilinear16(s0 + c, s1 + c, wp));
        }
        for (; c + 8 <= cols; c += 8) {
            _mm_storeu_si128(reinterpret_cast<__m128i*>(o + c), bilinear8(s0 + c, s1 + c, wp));
        }
        for (; c < cols; ++c) {
            o[c] = static_cast<std::int16_t>(
                (s0[c] * w.w00 + s0[c + 1] * w.w01 + s1[c] * w.w10 + s1[c + 1] * w.w11 + round) >>
                shift);
        }
    }
}

namespace {

/// (3 * a + 10 * b + 16) >> 5 for 16 pairs of int16, exactly (32-bit products in a multiply-add).
MIRROR_AVX2 inline __m256i scharrRound(__m256i a, __m256i b) noexcept
{
    const __m256i weights = _mm256_set1_epi32(3 | (10 << 16));
    const __m256i half = _mm256_set1_epi32(16);
    const __m256i lo = _mm256_srai_epi32(
        _mm256_add_epi32(_mm256_madd_epi16(_mm256_unpacklo_epi16(a, b), weights), half),
        kValueBits);
    const __m256i hi = _mm256_srai_epi32(
        _mm256_add_epi32(_mm256_madd_epi16(_mm256_unpackhi_epi16(a, b), weights), half),
        kValueBits);
    return _mm256_packs_epi32(lo, hi);
}

MIRROR_AVX2 inline __m256i load16(const std::int16_t* p) noexcept
{
    return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}

}  // namespace

/// windowGradients with AVX2, 16 values at a time. Differences of 5-bit fixed-point values fit
/// in 16 bits, and so do their sums across two rows; the 3/10 weighting is a multiply-add into
/// 32 bits. Needs kSlack values of slack after `patch`, `ival`, `ix` and `iy` (a last half chunk
/// of 8 reads and writes past its row; what lies past `win` is stored as 0).
MIRROR_AVX2 void windowGradientsAvx2(const std::int16_t* __restrict patch, int pstride, int win,
                                     int lanes, std::int16_t* __restrict ival,
                                     std::int16_t* __restrict ix, std::int16_t* __restrict iy,
                                     std::int64_t& a11, std::int64_t& a12,
                                     std::int64_t& a22) noexcept
{
    const __m256i index = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    std::int64_t t11 = 0;
    std::int64_t t12 = 0;
    std::int64_t t22 = 0;
    __m256i s11 = _mm256_setzero_si256();
    __m256i s12 = _mm256_setzero_si256();
    __m256i s22 = _mm256_setzero_si256();
    for (int r = 0; r < win; ++r) {
        const std::int16_t* up = patch + r * pstride;
        const std::int16_t* mid = up + pstride;
        const std::int16_t* dn = mid + pstride;
        std::int16_t* vi = ival + r * lanes;
        std::int16_t* gx = ix + r * lanes;
        std::int16_t* gy = iy + r * lanes;
        for (int c = 0; c < lanes; c += 16) {
            const __m256i keep =
                _mm256_cmpgt_epi16(_mm256_set1_epi16(static_cast<short>(win - c)), index);
            const __m256i u0 = load16(up + c);
            const __m256i u2 = load16(up + c + 2);
            const __m256i d0 = load16(dn + c);
            const __m256i d2 = load16(dn + c + 2);
            const __m256i x = _mm256_and_si256(
                keep,
                scharrRound(_mm256_add_epi16(_mm256_sub_epi16(u2, u0), _mm256_sub_epi16(d2, d0)),
                            _mm256_sub_epi16(load16(mid + c + 2), load16(mid + c))));
            const __m256i y = _mm256_and_si256(
                keep,
                scharrRound(_mm256_add_epi16(_mm256_sub_epi16(d0, u0), _mm256_sub_epi16(d2, u2)),
                            _mm256_sub_epi16(load16(dn + c + 1), load16(up + c + 1))));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(gx + c), x);
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(gy + c), y);
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(vi + c),
                                _mm256_and_si256(keep, load16(mid + c + 1)));
            s11 = _mm256_add_epi32(s11, _mm256_madd_epi16(x, x));
            s12 = _mm256_add_epi32(s12, _mm256_madd_epi16(x, y));
            s22 = _mm256_add_epi32(s22, _mm256_madd_epi16(y, y));
        }
        if (r % kFlushRows == kFlushRows - 1 || r == win - 1) {
            t11 += sumLanes(s11);
            t12 += sumLanes(s12);
            t22 += sumLanes(s22);
            s11 = _mm256_setzero_si256();
            s12 = _mm256_setzero_si256();
            s22 = _mm256_setzero_si256();
        }
    }
    a11 = t11;
    a12 = t12;
    a22 = t22;
}

/// mismatchInside with AVX2.
MIRROR_AVX2 void mismatchInsideAvx2(ConstImageView img, const Bilinear& w, int rows, int lanes,
                                    const std::int16_t* ival, const std::int16_t* ix,
                                    const std::int16_t* iy, std::int64_t& b1,
                                    std::int64_t& b2) noexcept
{
    const WeightPairs wp = weightPairs(w);
    std::int64_t t1 = 0;
    std::int64_t t2 = 0;
    __m256i acc1 = _mm256_setzero_si256();
    __m256i acc2 = _mm256_setzero_si256();
    for (int r = 0; r < rows; ++r) {
        const auto [s0, s1, vi, gx, gy] = windowRow(img, w, r, lanes, ival, ix, iy);
        int c = 0;
        for (; c + 16 <= lanes; c += 16) {
            const __m256i d =
                _mm256_sub_epi16(bilinear16(s0 + c, s1 + c, wp),
                                 _mm256_loadu_si256(reinterpret_cast<const __m256i*>(vi + c)));
            acc1 = _mm256_add_epi32(
                acc1,
                _mm256_madd_epi16(d, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(gx + c))));
            acc2 = _mm256_add_epi32(
                acc2,
                _mm256_madd_epi16(d, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(gy + c))));
        }
        if (c < lanes) {  // one chunk of 8 left
            const __m128i d =
                _mm_sub_epi16(bilinear8(s0 + c, s1 + c, wp),
                              _mm_loadu_si128(reinterpret_cast<const __m128i*>(vi + c)));
            acc1 = _mm256_add_epi32(
                acc1, _mm256_zextsi128_si256(_mm_madd_epi16(
                          d, _mm_loadu_si128(reinterpret_cast<const __m128i*>(gx + c)))));
            acc2 = _mm256_add_epi32(
                acc2, _mm256_zextsi128_si256(_mm_madd_epi16(
                          d, _mm_loadu_si128(reinterpret_cast<const __m128i*>(gy + c)))));
        }
        if (r % kFlushRows == kFlushRows - 1 || r == rows - 1) {
            t1 += sumLanes(acc1);
            t2 += sumLanes(acc2);
            acc1 = _mm256_setzero_si256();
            acc2 = _mm256_setzero_si256();
        }
    }
    b1 = t1;
    b2 = t2;
}

}  // namespace vision::lk_detail

#endif  // __x86_64__
