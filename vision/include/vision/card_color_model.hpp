#pragma once
// The card's colour model (METHOD.md §2 steps 1, 2, 7): one Gaussian per chromaticity channel.
//
// Step 1 trains mean and sigma over a region; step 2 tests |x - mu| < t sigma per channel, turned
// once per frame into integer lower/upper bounds so the per-pixel test is six byte compares; step 7
// blends mu' = a mu_train + (1 - a)(b mu_prev + (1 - b) mu_cur), the same for sigma.

#include "vision/card_tracker.hpp"
#include "vision/chromaticity.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <cstdint>

namespace vision {

/// Inclusive per-channel bounds of the colour test (r, g, b chromaticity, 0..255). lo > hi on a
/// channel means nothing matches.
struct ColorBounds {
    std::uint8_t lo[3] = {1, 1, 1};
    std::uint8_t hi[3] = {0, 0, 0};
};

/// Integer bounds equivalent to |x - mu| < t sigma for integer x.
ColorBounds colorBounds(const CardColorModel& model, float t) noexcept;

/// The smallest bounds holding both (per channel; an empty channel of one gives the other's).
ColorBounds joinedBounds(const ColorBounds& a, const ColorBounds& b) noexcept;

inline bool matchesColor(const ColorBounds& b, std::uint8_t r, std::uint8_t g,
                         std::uint8_t bl) noexcept
{
    // Unsigned wrap-around turns each two-sided test into one compare.
    return static_cast<std::uint8_t>(r - b.lo[0]) <= static_cast<std::uint8_t>(b.hi[0] - b.lo[0]) &&
           static_cast<std::uint8_t>(g - b.lo[1]) <= static_cast<std::uint8_t>(b.hi[1] - b.lo[1]) &&
           static_cast<std::uint8_t>(bl - b.lo[2]) <=
               static_cast<std::uint8_t>(b.hi[2] - b.lo[2]) &&
           b.lo[0] <= b.hi[0] && b.lo[1] <= b.hi[1] && b.lo[2] <= b.hi[2];
}

/// Step 1: mean and sigma (floored at minSigma) of the chromaticity planes over `region` (clipped
/// to the planes). False (out unchanged) when the clipped region is empty.
bool trainColorModel(const ChromaticityPlanes& chroma, Rect region, float minSigma,
                     CardColorModel& out) noexcept;

/// Mean and sigma over the pixels where `mask` is non-zero inside `region`, sampling every
/// `step`-th row and column. False (out unchanged) when fewer than `minPixels` pixels are sampled.
bool measureColorModel(const ChromaticityPlanes& chroma, const ConstImageView& mask, Rect region,
                       int step, float minSigma, int minPixels, CardColorModel& out) noexcept;

/// Step 7: a * trained + (1 - a) * (b * previous + (1 - b) * current), for mean and sigma.
CardColorModel blendColorModel(const CardColorModel& trained, const CardColorModel& previous,
                               const CardColorModel& current, float alpha, float beta) noexcept;

/// Step 2 over `region`: mask = 255 where the pixel matches, 0 elsewhere (outside `region` the
/// mask is not touched).
void colorTest(const ChromaticityPlanes& chroma, const ColorBounds& bounds, Rect region,
               const ImageView& mask) noexcept;

/// How well a measured model's mean agrees with `model`: 1 when equal, 0 when some channel is
/// t sigma or more away (a confidence term).
float colorFit(const CardColorModel& model, const CardColorModel& sample, float t) noexcept;

}  // namespace vision
