#pragma once
// The window arithmetic of pyramidal Lucas-Kanade (METHOD.md §3, tracking) that its scalar kernels
// (optical_flow.cpp, the reference, and what aarch64 runs auto-vectorised for NEON) share with
// their AVX2 builds (optical_flow_avx2.cpp, chosen by simd::hasAvx2()). The sums are exact
// integers, so both paths give identical results. Private to vision/src.
#include "simd.hpp"
#include "vision/image.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace vision::lk_detail {

constexpr int kWeightBits = 14;  // bilinear weights sum to 1 << 14
constexpr int kValueBits = 5;    // sampled values keep 5 fractional bits (0..255 * 32)
// Values of slack after each window buffer: a SIMD kernel may run a last half chunk of 8 on 16.
constexpr std::size_t kSlack = 16;

inline int floorToInt(float v) noexcept
{
    return static_cast<int>(std::floor(v));
}

/// Top-left pixel and 14-bit weights of a bilinear sample at (x, y).
struct Bilinear {
    int x0 = 0, y0 = 0;                      ///< the top-left pixel
    int w00 = 0, w01 = 0, w10 = 0, w11 = 0;  ///< its weights, then its right, lower, lower-right
};

inline Bilinear bilinearAt(float x, float y) noexcept
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

/// One row of the mismatch pass: the image rows the bilinear samples read (from the sample's left
/// column) and the window's values and gradients in that row.
struct WindowRow {
    const std::uint8_t* s0;
    const std::uint8_t* s1;
    const std::int16_t* values;
    const std::int16_t* gx;
    const std::int16_t* gy;
};

inline WindowRow windowRow(ConstImageView img, const Bilinear& w, int r, int lanes,
                           const std::int16_t* ival, const std::int16_t* ix,
                           const std::int16_t* iy) noexcept
{
    const std::uint8_t* s0 = img.row(w.y0 + r) + w.x0;
    const int at = r * lanes;
    return {s0, s0 + img.stride, ival + at, ix + at, iy + at};
}

#if defined(__x86_64__)
/// The scalar kernels of optical_flow.cpp with AVX2 intrinsics (pairs of pixels times pairs of
/// 14-bit weights in one multiply-add); same arguments, same results.
void sampleInsideAvx2(ConstImageView img, const Bilinear& w, int rows, int cols, int outStride,
                      std::int16_t* out) noexcept;
void windowGradientsAvx2(const std::int16_t* __restrict patch, int pstride, int win, int lanes,
                         std::int16_t* __restrict ival, std::int16_t* __restrict ix,
                         std::int16_t* __restrict iy, std::int64_t& a11, std::int64_t& a12,
                         std::int64_t& a22) noexcept;
void mismatchInsideAvx2(ConstImageView img, const Bilinear& w, int rows, int lanes,
                        const std::int16_t* ival, const std::int16_t* ix, const std::int16_t* iy,
                        std::int64_t& b1, std::int64_t& b2) noexcept;
#endif

}  // namespace vision::lk_detail
