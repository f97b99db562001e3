#pragma once
// Internal: the per-row chromaticity kernels of each instruction set, called by
// convertChromaticity (chromaticity.cpp) after it has checked formats and sizes. Not installed.
//
// Every kernel computes exactly ChromaticityTable's entry row(sum)[min(c, sum)] for each channel,
// i.e. round(255 c / sum) with halves up, 0 for sum 0 (the clamp only matters for inputs that no
// real pixel produces, c > sum, and keeps the SIMD and table paths equal on every input).
//
// The SIMD kernels do not use the table (AVX2 and NEON have no byte gathers); per pixel, in
// 16-bit lanes (proof in chromaticity.cpp):
//   s1 = max(sum, 1)
//   m  = min(trunc(65536 / s1), 65535)    reciprocal in float (rcp + one Newton step on AVX2)
//   n  = 255 c + (sum >> 1)               < 2^16; round(255 c / sum) = floor(n / s1)
//   q0 = (n m) >> 16                      u16 multiply-high; q0 is q or q - 1
//   d  = n - s1 q0                        exact in wrapping 16-bit arithmetic (0 <= d < 2 s1)
//   q  = q0 + (d >= s1)
// (pixel kernels have c <= sum by construction; the test kernels clamp c to sum first).

#include "vision/chromaticity.hpp"

#include <cstdint>

namespace vision::chroma_detail {

/// Byte order of the packed RGB input a row kernel reads.
enum class Packing : std::uint8_t { Rgb24, Bgr24, Xrgb8888 };

/// Converts n pixels of one row. r, g, b receive one byte per pixel.
using RowKernel = void (*)(const ChromaticityTable& table, const std::uint8_t* src, int n,
                           Packing packing, std::uint8_t* r, std::uint8_t* g,
                           std::uint8_t* b) noexcept;

/// out[i] = exact(min(c[i], sum[i]), sum[i]) through a path's arithmetic (the exhaustive test).
using QuotientKernel = void (*)(const std::uint16_t* c, const std::uint16_t* sum, std::uint8_t* out,
                                int n) noexcept;

/// One pixel, exactly as the table stores it; the SIMD kernels use it for their row tails.
inline std::uint8_t exactClamped(int c, int sum) noexcept
{
    return ChromaticityTable::exact(c <= sum ? c : sum, sum);
}

/// The last n pixels of a row, fewer than a SIMD step, one at a time exactly as the table stores
/// them: `step` bytes a pixel, red at byte ri, green at 1, blue at bi.
inline void rowTail(const std::uint8_t* p, int n, int step, int ri, int bi, std::uint8_t* r,
                    std::uint8_t* g, std::uint8_t* b) noexcept
{
    for (int x = 0; x < n; ++x, p += step) {
        const int sum = p[0] + p[1] + p[2];
        r[x] = exactClamped(p[ri], sum);
        g[x] = exactClamped(p[1], sum);
        b[x] = exactClamped(p[bi], sum);
    }
}

#if defined(__x86_64__)
void rowAvx2(const ChromaticityTable&, const std::uint8_t*, int, Packing, std::uint8_t*,
             std::uint8_t*, std::uint8_t*) noexcept;
void quotientsAvx2(const std::uint16_t*, const std::uint16_t*, std::uint8_t*, int) noexcept;
#endif
#if defined(__aarch64__)
void rowNeon(const ChromaticityTable&, const std::uint8_t*, int, Packing, std::uint8_t*,
             std::uint8_t*, std::uint8_t*) noexcept;
void quotientsNeon(const std::uint16_t*, const std::uint16_t*, std::uint8_t*, int) noexcept;
#endif

}  // namespace vision::chroma_detail
