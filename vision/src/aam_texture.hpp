#pragma once
// The fitted face's texture descriptor (beyond §6, as its future work allows): uniform local
// binary patterns (8 neighbours, 59 bins) over a grid of cells of the AAM's mean-shape frame, on
// the image already warped there for the appearance parameters. Private to vision/src.

#include "aam_fit_tables.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vision::aam {

inline constexpr std::uint8_t kNoCell = 0xff;

/// Where each frame pixel's pattern goes, built once from the tables: the span arrays laid out
/// as the frame's rectangle, each model pixel whose 8 neighbours are all in a span given its cell.
struct TextureLayout {
    int width = 0, height = 0, grid = 0, cells = 0;
    std::vector<std::int32_t> frameOfSpan;  ///< span pixel -> y * width + x
    std::vector<std::uint8_t> cellOf;       ///< frame pixel -> its cell, or kNoCell
    std::vector<std::uint16_t> cellPixels;  ///< patterns counted per cell
    int bins() const noexcept { return cells * kAamLbpBins; }
};

/// `grid` x `grid` cells over the model pixels' bounding box (grid 0: no texture).
TextureLayout textureLayout(const Tables& t, int grid);

/// The uniform-pattern bin (0..58) of each 8-bit pattern: the 58 patterns with at most two 0/1
/// transitions round the circle in increasing order, every other pattern 58.
const std::array<std::uint8_t, 256>& uniformPatternBins() noexcept;

/// The descriptor of `warped` (span pixels): each cell's histogram of uniform patterns (a
/// neighbour at least as bright as the centre sets its bit), as 255 * sqrt(share of the cell), so
/// that the Euclidean distance is the Hellinger distance. `frame` (width * height) and
/// `histogram` (bins()) are scratch. Writes layout.bins() values into `out` and returns how many
/// (0 when `out` is too small or there is no grid). Integer but the final square roots.
int textureOf(const TextureLayout& layout, const std::int16_t* warped, std::int16_t* frame,
              std::uint16_t* histogram, std::span<std::uint8_t> out) noexcept;

}  // namespace vision::aam
