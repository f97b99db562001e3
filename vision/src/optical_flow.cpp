// Pyramidal Lucas-Kanade in fixed point (METHOD.md §3, tracking).
#include "vision/optical_flow.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#endif

namespace vision {

namespace {

constexpr int kWeightBits = 14;  // bilinear weights sum to 1 << 14
constexpr int kValueBits = 5;    // sampled values keep 5 fractional bits (0..255 * 32)
// OpenCV's scale of the gradient matrix for its minimum-eigenvalue test (gradients are Scharr
// responses of 8-bit pixels, summed products scaled by 2^-20, then divided by the window area).
constexpr double kEigScale = 1.0 / (1 << 20);
// Values of slack after each window buffer: a SIMD kernel may run a last half chunk of 8 on 16.
constexpr std::size_t kSlack = 16;

// The scalar kernels are the reference (and what aarch64 runs, auto-vectorised for NEON). On
// x86-64 the same integer arithmetic is also written with AVX2 intrinsics (pairs of pixels times
// pairs of 14-bit weights in one multiply-add), chosen at run time; the sums are exact integers,
// so both paths give identical results.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define MIRROR_LK_AVX2 1
#else
#define MIRROR_LK_AVX2 0
#endif

inline int floorToInt(float v) noexcept
{
    return static_cast<int>(std::floor(v));
}

/// Top-left pixel and 14-bit weights of a bilinear sample at (x, y).
struct Bilinear {
    int x0 = 0;
    int y0 = 0;
    int w00 = 0;
    int w01 = 0;
    int w10 = 0;
    int w11 = 0;
};

Bilinear bilinearAt(float x, float y) noexcept
{
    Bilinear w;
    w.x0 = floorToInt(x);
    w.y0 = floorToInt(y);
    const float a = x - static_cast<float>(w.x0);
    const float b = y - static_cast<float>(w.y0);
    constexpr float one = static_cast<float>(1 << kWeightBits);
    w.w00 = static_cast<int>((1.f - a) * (1.f - b) * one + 0.5f);
    w.w01 = static_cast<int>(a * (1.f - b) * one + 0.5f);
    w.w10 = static_cast<int>((1.f - a) * b * one + 0.5f);
    w.w11 = (1 << kWeightBits) - w.w00 - w.w01 - w.w10;
    return w;
}

/// Bilinear samples of a window wholly inside the image (one more column and row included).
void sampleInside(ConstImageView img, const Bilinear& w, int rows, int cols, int outStride,
                  std::int16_t* out) noexcept
{
    constexpr int shift = kWeightBits - kValueBits;
    constexpr int round = 1 << (shift - 1);
    for (int r = 0; r < rows; ++r) {
        const std::uint8_t* s0 = img.row(w.y0 + r) + w.x0;
        const std::uint8_t* s1 = s0 + img.stride;
        std::int16_t* o = out + r * outStride;
        for (int c = 0; c < cols; ++c) {
            o[c] = static_cast<std::int16_t>(
                (s0[c] * w.w00 + s0[c + 1] * w.w01 + s1[c] * w.w10 + s1[c + 1] * w.w11 + round) >>
                shift);
        }
    }
}

/// From the sampled window with its one-value rim (rows `pstride` apart): the window's values and
/// Scharr gradients rescaled to the response on 8-bit pixels (5 fractional bits dropped, rounded),
/// rows of `lanes` values with zeros past `win`, and the gradient matrix sums.
void windowGradients(const std::int16_t* __restrict patch, int pstride, int win, int lanes,
                     std::int16_t* __restrict ival, std::int16_t* __restrict ix,
                     std::int16_t* __restrict iy, std::int64_t& a11, std::int64_t& a12,
                     std::int64_t& a22) noexcept
{
    std::int64_t t11 = 0;
    std::int64_t t12 = 0;
    std::int64_t t22 = 0;
    for (int r = 0; r < win; ++r) {
        const std::int16_t* __restrict up = patch + r * pstride;
        const std::int16_t* __restrict mid = up + pstride;
        const std::int16_t* __restrict dn = mid + pstride;
        std::int16_t* __restrict vi = ival + r * lanes;
        std::int16_t* __restrict gx = ix + r * lanes;
        std::int16_t* __restrict gy = iy + r * lanes;
        for (int c = 0; c < lanes; ++c) {
            const int dx = 3 * (up[c + 2] - up[c] + dn[c + 2] - dn[c]) + 10 * (mid[c + 2] - mid[c]);
            const int dy =
                3 * (dn[c] - up[c] + dn[c + 2] - up[c + 2]) + 10 * (dn[c + 1] - up[c + 1]);
            vi[c] = mid[c + 1];
            gx[c] = static_cast<std::int16_t>((dx + 16) >> kValueBits);
            gy[c] = static_cast<std::int16_t>((dy + 16) >> kValueBits);
        }
        for (int c = win; c < lanes; ++c) {
            vi[c] = 0;
            gx[c] = 0;
            gy[c] = 0;
        }
        std::int32_t s11 = 0;
        std::int32_t s12 = 0;
        std::int32_t s22 = 0;
        for (int c = 0; c < lanes; ++c) {
            s11 += gx[c] * gx[c];
            s12 += gx[c] * gy[c];
            s22 += gy[c] * gy[c];
        }
        t11 += s11;
        t12 += s12;
        t22 += s22;
    }
    a11 = t11;
    a12 = t12;
    a22 = t22;
}

/// The mismatch vector b = sum (J - I) * grad I over the window, J sampled at `w` straight from
/// the image (the window and one more column and row inside it). Rows of `lanes` values; the
/// padding lanes have zero gradients, so they add nothing. One fused pass, no stores.
void mismatchInside(ConstImageView img, const Bilinear& w, int rows, int lanes,
                    const std::int16_t* ival, const std::int16_t* ix, const std::int16_t* iy,
                    std::int64_t& b1, std::int64_t& b2) noexcept
{
    constexpr int shift = kWeightBits - kValueBits;
    constexpr int round = 1 << (shift - 1);
    std::int64_t t1 = 0;
    std::int64_t t2 = 0;
    for (int r = 0; r < rows; ++r) {
        const std::uint8_t* s0 = img.row(w.y0 + r) + w.x0;
        const std::uint8_t* s1 = s0 + img.stride;
        const std::int16_t* vi = ival + r * lanes;
        const std::int16_t* gx = ix + r * lanes;
        const std::int16_t* gy = iy + r * lanes;
        std::int32_t a1 = 0;
        std::int32_t a2 = 0;
        for (int c = 0; c < lanes; ++c) {
            const int j =
                (s0[c] * w.w00 + s0[c + 1] * w.w01 + s1[c] * w.w10 + s1[c + 1] * w.w11 + round) >>
                shift;
            const int d = j - vi[c];
            a1 += d * gx[c];
            a2 += d * gy[c];
        }
        t1 += a1;
        t2 += a2;
    }
    b1 = t1;
    b2 = t2;
}

#if MIRROR_LK_AVX2

#define MIRROR_LK_TARGET __attribute__((target("avx2")))

bool cpuHasAvx2() noexcept
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
}

const bool kHasAvx2 = cpuHasAvx2();

/// Pairs (w00, w01) and (w10, w11) as 32-bit lanes, for _mm256_madd_epi16 on (p[c], p[c + 1]).
struct WeightPairs {
    __m256i top;
    __m256i bottom;
};

MIRROR_LK_TARGET inline WeightPairs weightPairs(const Bilinear& w) noexcept
{
    const auto pair = [](int lo, int hi) {
        return static_cast<int>(static_cast<std::uint32_t>(lo) |
                                (static_cast<std::uint32_t>(hi) << 16));
    };
    return {_mm256_set1_epi32(pair(w.w00, w.w01)), _mm256_set1_epi32(pair(w.w10, w.w11))};
}

/// 16 bilinear samples (5 fractional bits) from s0[0..16] and s1[0..16].
MIRROR_LK_TARGET inline __m256i bilinear16(const std::uint8_t* s0, const std::uint8_t* s1,
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
MIRROR_LK_TARGET inline __m128i bilinear8(const std::uint8_t* s0, const std::uint8_t* s1,
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
MIRROR_LK_TARGET inline std::int64_t sumLanes(__m256i v) noexcept
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

/// sampleInside with AVX2: whole 16-value chunks, the rest scalar.
MIRROR_LK_TARGET void sampleInsideAvx2(ConstImageView img, const Bilinear& w, int rows, int cols,
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

/// (3 * a + 10 * b + 16) >> 5 for 16 pairs of int16, exactly (32-bit products in a multiply-add).
MIRROR_LK_TARGET inline __m256i scharrRound(__m256i a, __m256i b) noexcept
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

MIRROR_LK_TARGET inline __m256i load16(const std::int16_t* p) noexcept
{
    return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}

/// windowGradients with AVX2, 16 values at a time. Differences of 5-bit fixed-point values fit
/// in 16 bits, and so do their sums across two rows; the 3/10 weighting is a multiply-add into
/// 32 bits. Needs kSlack values of slack after `patch`, `ival`, `ix` and `iy` (a last half chunk
/// of 8 reads and writes past its row; what lies past `win` is stored as 0).
MIRROR_LK_TARGET void windowGradientsAvx2(const std::int16_t* __restrict patch, int pstride,
                                          int win, int lanes, std::int16_t* __restrict ival,
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
MIRROR_LK_TARGET void mismatchInsideAvx2(ConstImageView img, const Bilinear& w, int rows, int lanes,
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
        const std::uint8_t* s0 = img.row(w.y0 + r) + w.x0;
        const std::uint8_t* s1 = s0 + img.stride;
        const std::int16_t* vi = ival + r * lanes;
        const std::int16_t* gx = ix + r * lanes;
        const std::int16_t* gy = iy + r * lanes;
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

#endif  // MIRROR_LK_AVX2

}  // namespace

PyramidalLucasKanade::PyramidalLucasKanade(const OpticalFlowOptions& options) : options_(options)
{
    const int w = options.window;
    if (w < 3 || w > 31 || w % 2 == 0) {
        throw std::runtime_error("PyramidalLucasKanade: window " + std::to_string(w) +
                                 " must be odd and within 3..31");
    }
    if (options.maxLevel < 0 || options.maxIterations < 1) {
        throw std::runtime_error("PyramidalLucasKanade: maxLevel must be >= 0, maxIterations >= 1");
    }
    lanes_ = (w + 7) & ~7;
    const std::size_t area = static_cast<std::size_t>(w) * static_cast<std::size_t>(lanes_);
    patch_ = std::make_unique<std::int16_t[]>(
        static_cast<std::size_t>(w + 2) * static_cast<std::size_t>(lanes_ + 2) + kSlack);
    ival_ = std::make_unique<std::int16_t[]>(area + kSlack);
    ix_ = std::make_unique<std::int16_t[]>(area + kSlack);
    iy_ = std::make_unique<std::int16_t[]>(area + kSlack);
    edge_ = std::make_unique<std::uint8_t[]>(static_cast<std::size_t>(w + 3) *
                                             static_cast<std::size_t>(lanes_ + 3));
}

ConstImageView PyramidalLucasKanade::edgeCopy(ConstImageView img, int x0, int y0, int rows,
                                              int cols) noexcept
{
    const int maxX = img.width - 1;
    const int maxY = img.height - 1;
    const int stride = lanes_ + 3;
    std::uint8_t* dst = edge_.get();
    for (int r = 0; r <= rows; ++r) {
        const std::uint8_t* s = img.row(std::clamp(y0 + r, 0, maxY));
        std::uint8_t* d = dst + r * stride;
        int c = 0;
        for (; c <= cols && x0 + c < 0; ++c) {
            d[c] = s[0];
        }
        const int inside = std::min(cols + 1, maxX - x0 + 1) - c;
        if (inside > 0) {
            std::copy_n(s + x0 + c, inside, d + c);
            c += inside;
        }
        for (; c <= cols; ++c) {
            d[c] = s[maxX];
        }
    }
    return {dst, cols + 1, rows + 1, stride, PixelFormat::Gray8};
}

void PyramidalLucasKanade::sampleWindow(ConstImageView img, float x, float y, int rows, int cols,
                                        int outStride, std::int16_t* out) noexcept
{
    Bilinear w = bilinearAt(x, y);
    if (!(w.x0 >= 0 && w.y0 >= 0 && w.x0 + cols < img.width && w.y0 + rows < img.height)) {
        img = edgeCopy(img, w.x0, w.y0, rows, cols);
        w.x0 = 0;
        w.y0 = 0;
    }
#if MIRROR_LK_AVX2
    if (kHasAvx2) {
        sampleInsideAvx2(img, w, rows, cols, outStride, out);
        return;
    }
#endif
    sampleInside(img, w, rows, cols, outStride, out);
}

bool PyramidalLucasKanade::trackPoint(const ImagePyramid& prev, const ImagePyramid& next,
                                      Point2f from, Point2f guess, Point2f& to) noexcept
{
    to = from;
    const int levels = std::min({prev.levels(), next.levels(), options_.maxLevel + 1});
    if (levels < 1 || prev.size() != next.size() || prev.level(0).empty() ||
        next.level(0).empty()) {
        return false;
    }
    const int win = options_.window;
    const int side = win + 2;
    const float half = static_cast<float>(win - 1) * 0.5f;
    const int area = win * win;
    std::int16_t* patch = patch_.get();
    std::int16_t* ival = ival_.get();
    std::int16_t* ix = ix_.get();
    std::int16_t* iy = iy_.get();
    const int lanes = lanes_;
    const float eps2 = options_.epsilon * options_.epsilon;

    const float topScale = 1.f / static_cast<float>(1 << (levels - 1));
    Point2f est{guess.x * topScale, guess.y * topScale};
    bool ok = true;
    for (int level = levels - 1; level >= 0; --level) {
        const float s = 1.f / static_cast<float>(1 << level);
        const Point2f p{from.x * s, from.y * s};
        if (level != levels - 1) {
            est = {est.x * 2.f, est.y * 2.f};
        }
        const ConstImageView imgI = prev.level(level);
        const ConstImageView imgJ = next.level(level);
        // Written so that NaN fails too (it would make the pixel index undefined).
        if (!(p.x >= -half && p.y >= -half && p.x <= static_cast<float>(imgI.width) + half &&
              p.y <= static_cast<float>(imgI.height) + half)) {
            ok = level != 0 && ok;
            continue;
        }
        // On a coarse level a window reaching far past the border is mostly repeated edge
        // pixels, which pull the estimate; such levels are skipped, the finer ones do the work.
        const float inner = 0.5f * half;
        if (level > 0 &&
            (p.x < inner || p.y < inner || p.x > static_cast<float>(imgI.width - 1) - inner ||
             p.y > static_cast<float>(imgI.height - 1) - inner)) {
            continue;
        }

        // The previous frame's window with a one-pixel rim, then its Scharr gradients rescaled
        // to the response on 8-bit pixels (the 5 fractional bits dropped, rounded).
        sampleWindow(imgI, p.x - half - 1.f, p.y - half - 1.f, side, lanes + 2, lanes + 2, patch);
        std::int64_t a11 = 0;
        std::int64_t a12 = 0;
        std::int64_t a22 = 0;
#if MIRROR_LK_AVX2
        if (kHasAvx2) {
            windowGradientsAvx2(patch, lanes + 2, win, lanes, ival, ix, iy, a11, a12, a22);
        } else {
            windowGradients(patch, lanes + 2, win, lanes, ival, ix, iy, a11, a12, a22);
        }
#else
        windowGradients(patch, lanes + 2, win, lanes, ival, ix, iy, a11, a12, a22);
#endif
        const double g11 = static_cast<double>(a11) * kEigScale;
        const double g12 = static_cast<double>(a12) * kEigScale;
        const double g22 = static_cast<double>(a22) * kEigScale;
        const double det = g11 * g22 - g12 * g12;
        const double minEig =
            (g11 + g22 - std::sqrt((g11 - g22) * (g11 - g22) + 4.0 * g12 * g12)) / (2.0 * area);
        if (minEig < static_cast<double>(options_.minEigThreshold) || det < 1.19e-7) {
            ok = level != 0 && ok;
            continue;
        }
        const double invDet = 1.0 / det;

        Point2f prevDelta{0.f, 0.f};
        for (int it = 0; it < options_.maxIterations; ++it) {
            if (!(est.x >= -half && est.y >= -half &&
                  est.x <= static_cast<float>(imgJ.width) + half &&
                  est.y <= static_cast<float>(imgJ.height) + half)) {
                ok = level != 0 && ok;
                break;
            }
            std::int64_t b1 = 0;
            std::int64_t b2 = 0;
            Bilinear bw = bilinearAt(est.x - half, est.y - half);
            ConstImageView src = imgJ;
            if (!(bw.x0 >= 0 && bw.y0 >= 0 && bw.x0 + lanes < imgJ.width &&
                  bw.y0 + win < imgJ.height)) {
                src = edgeCopy(imgJ, bw.x0, bw.y0, win, lanes);
                bw.x0 = 0;
                bw.y0 = 0;
            }
#if MIRROR_LK_AVX2
            if (kHasAvx2) {
                mismatchInsideAvx2(src, bw, win, lanes, ival, ix, iy, b1, b2);
            } else {
                mismatchInside(src, bw, win, lanes, ival, ix, iy, b1, b2);
            }
#else
            mismatchInside(src, bw, win, lanes, ival, ix, iy, b1, b2);
#endif
            // Values are 32 x pixels and Scharr responses 32 x the slope: the scales cancel.
            const double e1 = static_cast<double>(b1) * kEigScale;
            const double e2 = static_cast<double>(b2) * kEigScale;
            const Point2f delta{static_cast<float>((g12 * e2 - g22 * e1) * invDet),
                                static_cast<float>((g12 * e1 - g11 * e2) * invDet)};
            est.x += delta.x;
            est.y += delta.y;
            if (delta.x * delta.x + delta.y * delta.y <= eps2) {
                break;
            }
            // Oscillating between two positions: settle half way, as OpenCV does.
            if (it > 0 && std::fabs(delta.x + prevDelta.x) < 0.01f &&
                std::fabs(delta.y + prevDelta.y) < 0.01f) {
                est.x -= delta.x * 0.5f;
                est.y -= delta.y * 0.5f;
                break;
            }
            prevDelta = delta;
        }
    }
    const ConstImageView base = next.level(0);
    if (!ok || !std::isfinite(est.x) || !std::isfinite(est.y) || est.x < 0.f || est.y < 0.f ||
        est.x > static_cast<float>(base.width - 1) || est.y > static_cast<float>(base.height - 1)) {
        return false;
    }
    to = est;
    return true;
}

int PyramidalLucasKanade::track(const ImagePyramid& prev, const ImagePyramid& next,
                                const Point2f* prevPts, Point2f* nextPts, FlowStatus* status, int n,
                                float* fbError) noexcept
{
    int tracked = 0;
    for (int i = 0; i < n; ++i) {
        if (fbError) {
            fbError[i] = -1.f;
        }
        Point2f to;
        if (!trackPoint(prev, next, prevPts[i], prevPts[i], to)) {
            nextPts[i] = prevPts[i];
            status[i] = FlowStatus::Lost;
            continue;
        }
        nextPts[i] = to;
        if (options_.fbThreshold > 0.f) {
            Point2f back;
            float d = 1e30f;
            if (trackPoint(next, prev, to, to, back)) {
                d = std::hypot(back.x - prevPts[i].x, back.y - prevPts[i].y);
            }
            if (fbError) {
                fbError[i] = d;
            }
            if (d > options_.fbThreshold) {
                status[i] = FlowStatus::ForwardBackwardFailed;
                continue;
            }
        }
        status[i] = FlowStatus::Tracked;
        ++tracked;
    }
    return tracked;
}

}  // namespace vision
