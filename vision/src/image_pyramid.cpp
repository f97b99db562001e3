// Grey image pyramid (METHOD.md §3, tracking): 5-tap binomial reduction in integer arithmetic.
#include "vision/image_pyramid.hpp"

#include "simd.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace vision {

namespace {

/// Reflect-101 index into [0, n): -1 -> 1, n -> n - 2 (cv::BORDER_REFLECT_101, as cv::pyrDown).
inline int reflect101(int i, int n) noexcept
{
    if (i < 0) {
        i = -i;
    }
    if (i >= n) {
        i = 2 * n - 2 - i;
    }
    return i;
}

// The filters are the hot loops of the frame's pyramid: the vertical one a plain loop the compiler
// vectorises, the horizontal one hand-written for AVX2; on x86-64 the AVX2 builds are chosen by
// simd::hasAvx2(), aarch64 runs its NEON baseline.

/// Five source rows filtered vertically by [1 4 6 4 1] at full width (sums up to 16 * 255).
MIRROR_SIMD_BODY void filterColumnsBody(const std::uint8_t* r0, const std::uint8_t* r1,
                                        const std::uint8_t* r2, const std::uint8_t* r3,
                                        const std::uint8_t* r4, int w, std::uint16_t* out) noexcept
{
    for (int x = 0; x < w; ++x) {
        out[x] = static_cast<std::uint16_t>(r0[x] + r4[x] + 4 * (r1[x] + r3[x]) + 6 * r2[x]);
    }
}

#if defined(__x86_64__)
MIRROR_AVX2 void filterColumnsAvx2(const std::uint8_t* r0, const std::uint8_t* r1,
                                   const std::uint8_t* r2, const std::uint8_t* r3,
                                   const std::uint8_t* r4, int w, std::uint16_t* out) noexcept
{
    filterColumnsBody(r0, r1, r2, r3, r4, w, out);
}
#endif

void filterColumns(const std::uint8_t* r0, const std::uint8_t* r1, const std::uint8_t* r2,
                   const std::uint8_t* r3, const std::uint8_t* r4, int w,
                   std::uint16_t* out) noexcept
{
#if defined(__x86_64__)
    if (simd::hasAvx2())
        return filterColumnsAvx2(r0, r1, r2, r3, r4, w, out);
#endif
    filterColumnsBody(r0, r1, r2, r3, r4, w, out);
}

#if defined(__x86_64__)

/// Outputs x0, x0 + 1, ... of filterRowDown while 16 at a time fit (taps up to v[2x + 17] read):
/// the stride-2 taps are the low and high halves of 32-bit lanes, weighted in multiply-adds
/// (taps up to 16 * 255 are safe as signed 16-bit, sums up to 256 * 255). Returns the first
/// output not written.
MIRROR_AVX2 int filterRowDownAvx2(const std::uint16_t* v, int w, std::uint8_t* out, int x0) noexcept
{
    const __m256i w14 = _mm256_set1_epi32(1 | (4 << 16));
    const __m256i w64 = _mm256_set1_epi32(6 | (4 << 16));
    const __m256i low = _mm256_set1_epi32(0xffff);
    const __m256i round = _mm256_set1_epi32(128);
    const auto eight = [&](int x) MIRROR_AVX2 {
        const std::uint16_t* p = v + 2 * x;
        const __m256i l0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p - 2));
        const __m256i l1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
        const __m256i l2 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + 2));
        const __m256i sum = _mm256_add_epi32(
            _mm256_add_epi32(_mm256_madd_epi16(l0, w14), _mm256_madd_epi16(l1, w64)),
            _mm256_and_si256(l2, low));
        return _mm256_srli_epi32(_mm256_add_epi32(sum, round), 8);
    };
    int x = x0;
    for (; 2 * (x + 8) + 17 < w; x += 16) {
        // packus works within 128-bit halves: reorder the quarters, then narrow to bytes.
        const __m256i words =
            _mm256_permute4x64_epi64(_mm256_packus_epi32(eight(x), eight(x + 8)), 0xD8);
        const __m128i bytes =
            _mm_packus_epi16(_mm256_castsi256_si128(words), _mm256_extracti128_si256(words, 1));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x), bytes);
    }
    return x;
}
#endif

/// The vertically filtered row filtered horizontally, subsampled by 2, rounded to 8 bits.
void filterRowDown(const std::uint16_t* v, int w, std::uint8_t* out, int dw) noexcept
{
    const int last = (w - 3) / 2;  // largest x with 2x + 2 <= w - 1: all taps inside
    int first = 1;
#if defined(__x86_64__)
    if (simd::hasAvx2()) {
        first = filterRowDownAvx2(v, w, out, 1);
    }
#endif
    for (int x = first; x <= last; ++x) {
        const std::uint16_t* p = v + 2 * x;
        const std::uint32_t sum = static_cast<std::uint32_t>(p[-2]) + p[2] +
                                  4u * (static_cast<std::uint32_t>(p[-1]) + p[1]) + 6u * p[0];
        out[x] = static_cast<std::uint8_t>((sum + 128u) >> 8);
    }
    auto edge = [&](int x) {
        const int c = 2 * x;
        const std::uint32_t sum =
            static_cast<std::uint32_t>(v[reflect101(c - 2, w)]) + v[reflect101(c + 2, w)] +
            4u * (static_cast<std::uint32_t>(v[reflect101(c - 1, w)]) + v[reflect101(c + 1, w)]) +
            6u * v[c];
        out[x] = static_cast<std::uint8_t>((sum + 128u) >> 8);
    };
    edge(0);
    for (int x = std::max(last + 1, 1); x < dw; ++x) {
        edge(x);
    }
}

}  // namespace

ImagePyramid::ImagePyramid(Size size, int levels) : size_(size)
{
    if (size.width <= 0 || size.height <= 0) {
        throw std::runtime_error("ImagePyramid: empty frame size");
    }
    if (levels < 1 || levels > kMaxLevels) {
        throw std::runtime_error("ImagePyramid: " + std::to_string(levels) + " levels asked, 1.." +
                                 std::to_string(kMaxLevels) + " allowed");
    }
    levels_ = 1;
    int w = size.width;
    int h = size.height;
    while (levels_ < levels && (w + 1) / 2 >= 8 && (h + 1) / 2 >= 8) {
        w = (w + 1) / 2;
        h = (h + 1) / 2;
        buffers_[levels_] = ImageBuffer(w, h, PixelFormat::Gray8);
        ++levels_;
    }
    rowSums_ = std::make_unique<std::uint16_t[]>(static_cast<std::size_t>(size.width));
}

bool ImagePyramid::build(ConstImageView gray) noexcept
{
    if (gray.empty() || gray.format != PixelFormat::Gray8 || gray.size() != size_) {
        return false;
    }
    views_[0] = gray;
    for (int i = 1; i < levels_; ++i) {
        ImageView dst = buffers_[i].view();
        pyramidDown(views_[i - 1], dst, rowSums_.get());
        views_[i] = dst;
    }
    return true;
}

void pyramidDown(ConstImageView src, ImageView dst, std::uint16_t* rows) noexcept
{
    // Vertical first, over contiguous full-width rows, then horizontal with the halving: the
    // stride-2 pass runs on half the rows.
    const int h = src.height;
    for (int y = 0; y < dst.height; ++y) {
        const int c = 2 * y;
        filterColumns(src.row(reflect101(c - 2, h)), src.row(reflect101(c - 1, h)), src.row(c),
                      src.row(reflect101(c + 1, h)), src.row(reflect101(c + 2, h)), src.width,
                      rows);
        filterRowDown(rows, src.width, dst.row(y), dst.width);
    }
}

}  // namespace vision
