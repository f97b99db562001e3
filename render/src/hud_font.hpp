#pragma once
// The HUD's built-in bitmap font: 5x8 pixel glyphs for printable ASCII (32..126), drawn for this
// project. Rows 0..6 hold capitals and the baseline is row 6; row 7 holds descenders (g j p q y _).

#include <cstdint>

namespace render::detail {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 8;
inline constexpr char kFirstGlyph = ' ';
inline constexpr char kLastGlyph = '~';
inline constexpr int kGlyphCount = kLastGlyph - kFirstGlyph + 1;

/// The kGlyphHeight rows of the glyph for `c`, top row first; in each row bit 4 is the leftmost
/// pixel and bit 0 the rightmost. Characters outside 32..126 get the glyph of '?'.
const std::uint8_t* glyphRows(char c) noexcept;

}  // namespace render::detail
