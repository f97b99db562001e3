#pragma once
// Internal: FrameDifference's per-row kernels (frame_difference.cpp). Not installed.
//
// A kernel tests one row and remembers it: where |dR| + |dG| + |dB| between the row `p` and the
// previous frame's row `q` exceeds `limit` (-1: everywhere), the mask byte becomes the colour
// test's answer (255 when every chromaticity channel is in its band, else 0); then `q` receives
// `p`. It returns the number of changed pixels. `Step` is 3 (RGB24/BGR24) or 4 (XRGB8888): the
// bytes of a pixel, of which the first three are summed (their order does not matter).

#include "color_bands.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace vision::difference_detail {

/// One row's inputs, as pointers at its first pixel.
struct Row {
    const std::uint8_t* p;          ///< this frame, Step bytes a pixel
    std::uint8_t* q;                ///< the previous frame, same layout; receives p
    const std::uint8_t *r, *g, *b;  ///< chromaticity planes
    std::uint8_t* mask;
};

/// The scalar reference for pixels [x0, w) of a row, without remembering it. Written without
/// branches (0/255 masks combined with & and |) so that compilers vectorise it where they can.
template <int Step>
int testRowScalar(const Row& row, int x0, int w, int limit, const ColorBands& bands) noexcept
{
    // Local restrict copies: a store through the mask (a byte pointer) could otherwise alias `row`.
    const std::uint8_t* __restrict p = row.p;
    const std::uint8_t* __restrict q = row.q;
    const std::uint8_t* __restrict pr = row.r;
    const std::uint8_t* __restrict pg = row.g;
    const std::uint8_t* __restrict pb = row.b;
    std::uint8_t* __restrict pm = row.mask;
    int changed = 0;
    for (int x = x0; x < w; ++x) {
        const int d = std::abs(p[Step * x] - q[Step * x]) +
                      std::abs(p[Step * x + 1] - q[Step * x + 1]) +
                      std::abs(p[Step * x + 2] - q[Step * x + 2]);
        const std::uint8_t match = matchMask(bands, pr[x], pg[x], pb[x]);
        const std::uint8_t change = static_cast<std::uint8_t>(-(d > limit));
        pm[x] = static_cast<std::uint8_t>((match & change) | (pm[x] & ~change));
        changed += change & 1;
    }
    return changed;
}

template <int Step>
int updateRowScalar(const Row& row, int w, int limit, const ColorBands& bands) noexcept
{
    const int changed = testRowScalar<Step>(row, 0, w, limit, bands);
    std::memcpy(row.q, row.p, static_cast<std::size_t>(w) * Step);
    return changed;
}

#if defined(__aarch64__)
/// NEON, 16 pixels a step (frame_difference_neon.cpp); the same bytes as updateRowScalar.
int updateRowNeon3(const Row& row, int w, int limit, const ColorBands& bands) noexcept;
int updateRowNeon4(const Row& row, int w, int limit, const ColorBands& bands) noexcept;
#endif

}  // namespace vision::difference_detail
