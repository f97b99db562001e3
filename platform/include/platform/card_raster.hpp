#pragma once
// The one card renderer: an anti-aliased, shaded, perspective quad of solid colour. Used by the
// demo scene (CardSceneSource) and the evaluation sequences (cardgen), so both draw the same card.

#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <cstdint>

namespace platform {

/// Appearance of the card surface for one frame.
struct CardPaint {
    std::uint8_t red = 40;  ///< nominal colour (RGB, whatever the image's byte order)
    std::uint8_t green = 172;
    std::uint8_t blue = 76;
    double brightness = 1.0;  ///< at the card centre (1 = nominal colour)
    double gradientU = 0.0;   ///< its slope along the card's own u axis (u in [-1, 1] edge to edge)
    double gradientV = 0.0;   ///< and along v: light = brightness + gradientU u + gradientV v
    int noise = 0;            ///< per-pixel noise, +- grey levels, deterministic
    std::uint32_t noiseSeed = 0;  ///< e.g. the frame's sequence number
};

/// Draws the card with corners `quad` (clockwise on screen from the card's top-left corner; may
/// lie partly or wholly outside the image) into `image` (RGB24, BGR24 or XRGB8888). Pixel (x, y)
/// has its centre at (x, y); coverage of each edge pixel is estimated from 4x4 subsamples, so the
/// drawn edges sit on the true lines within a few hundredths of a pixel on average. The card's
/// own coordinates (u, v) follow the perspective mapping of the unit square onto `quad`. Returns
/// false (draws nothing) for an unsupported format or an empty image. Never allocates.
bool drawCardQuad(vision::ImageView image, const vision::Quad& quad,
                  const CardPaint& paint) noexcept;

/// Projective mapping from card coordinates (u, v in [-1, 1], (-1,-1) at quad[0], (1,-1) at
/// quad[1], (1,1) at quad[2]) to pixels, as a row-major 3x3 matrix. Degenerate quads give a
/// singular matrix.
void cardToImageHomography(const vision::Quad& quad, double m[9]) noexcept;

}  // namespace platform
