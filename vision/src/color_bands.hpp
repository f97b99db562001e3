#pragma once
// Internal: the colour test of §2 step 2 (matchesColor, card_color_model.hpp) in the form row
// loops vectorise: no && and no ?: (branches), but 0/255 byte masks combined with &. Used by
// colorTest and by the frame difference's kernels; gives matchesColor's answer for every input.

#include "vision/card_color_model.hpp"

#include <cstdint>

namespace vision {

/// ColorBounds as wrapping byte ranges: channel c matches when (uint8_t)(v - lo[c]) <= span[c].
/// `none` is 0 when some band is empty (lo > hi: nothing matches), 255 otherwise.
struct ColorBands {
    std::uint8_t lo[3], span[3], none;
};

inline ColorBands bandsOf(const ColorBounds& bounds) noexcept
{
    const bool empty =
        bounds.lo[0] > bounds.hi[0] || bounds.lo[1] > bounds.hi[1] || bounds.lo[2] > bounds.hi[2];
    ColorBands b{};
    for (int c = 0; c < 3; ++c) {
        b.lo[c] = bounds.lo[c];
        b.span[c] = empty ? 0 : static_cast<std::uint8_t>(bounds.hi[c] - bounds.lo[c]);
    }
    b.none = empty ? 0 : 255;
    return b;
}

/// 255 where matchesColor(bounds, r, g, bl), else 0.
inline std::uint8_t matchMask(const ColorBands& b, std::uint8_t r, std::uint8_t g,
                              std::uint8_t bl) noexcept
{
    return static_cast<std::uint8_t>(-(static_cast<std::uint8_t>(r - b.lo[0]) <= b.span[0])) &
           static_cast<std::uint8_t>(-(static_cast<std::uint8_t>(g - b.lo[1]) <= b.span[1])) &
           static_cast<std::uint8_t>(-(static_cast<std::uint8_t>(bl - b.lo[2]) <= b.span[2])) &
           b.none;
}

}  // namespace vision
