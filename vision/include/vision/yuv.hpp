#pragma once
// YUV camera formats (YUYV 4:2:2, NV12 4:2:0) to 8-bit RGB in fixed point, as cameras deliver them:
// ITU-R BT.601, limited ("studio") range, Y in 16..235 and U, V in 16..240. The exact integer
// formula, which every path in the vision core uses (so chromaticity from YUV is bit-exact across
// the scalar and SIMD paths):
//
//   C = Y - 16,  D = U - 128,  E = V - 128
//   R = clamp255((298 C           + 409 E + 128) >> 8)
//   G = clamp255((298 C - 100 D   - 208 E + 128) >> 8)
//   B = clamp255((298 C + 516 D           + 128) >> 8)
//
// (>> is an arithmetic shift: floor division by 256; clamp255 limits to 0..255.) The coefficients
// are 256 x (255/219 for luma; 1.402, 0.344, 0.714, 1.772 x 255/224 for chroma), rounded. The
// per-component products come from constant tables (§2, dissertation 4.3: tables with fixed
// addresses).
//
// Chroma is shared by a horizontal pair (YUYV: bytes Y0,U,Y1,V; NV12: one U,V pair per 2x2 block);
// it is not interpolated, so YUV input needs an even width (and, for NV12, an even height).

#include "vision/image.hpp"

#include <cstdint>

namespace vision {

/// One pixel by the formula above (the reference the tables are tested against).
struct Rgb8 {
    std::uint8_t r, g, b;
    friend constexpr bool operator==(Rgb8, Rgb8) = default;
};
Rgb8 yuvToRgb(int y, int u, int v) noexcept;

/// Converts YUYV, NV12, XRGB8888, BGR24 or RGB24 (a copy) to an RGB24 image of the same size,
/// with no allocation. Returns false and writes nothing on an unsupported format, a size
/// mismatch, or an odd width/height for YUV input.
bool convertToRgb24(const ConstImageView& input, const ImageView& output) noexcept;

/// True when convertToRgb24 accepts this input (format and size rules above).
bool convertibleToRgb24(const ConstImageView& input) noexcept;

/// Row pieces, for callers that convert in small chunks (chromaticity from YUV uses a
/// 256-pixel stack buffer). x0 and n must be even; out receives 3 n bytes R,G,B.
void yuyvRowToRgb24(const std::uint8_t* yuyvRow, int x0, int n, std::uint8_t* out) noexcept;
void nv12RowToRgb24(const std::uint8_t* yRow, const std::uint8_t* uvRow, int x0, int n,
                    std::uint8_t* out) noexcept;

}  // namespace vision
