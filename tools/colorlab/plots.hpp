#pragma once
// PNG plots like the dissertation's figures, drawn with OpenCV: each space's components over time
// (one panel per sample, as Figures 12-66) and the DP bar chart per space (Figures 68 on), plus a
// summary of the ranking measures. Throws std::runtime_error when a file cannot be written.

#include "sampling.hpp"
#include "statistics.hpp"

#include <string>
#include <vector>

namespace colorlab {

/// Panels drawn per series plot at most (a 64x64 grid would make an unreadable picture).
inline constexpr int kMaxPanels = 64;

/// DIR/plots/series_<space>.png
void plotSeries(const std::string& dir, const Recording& rec, const std::vector<bool>& useRow,
                vision::ColorSpace space);

/// DIR/plots/dp_<space>.png: one bar per pair, a line at DP = 1.
void plotDp(const std::string& dir, const Recording& rec, const SpaceStats& stats);

/// DIR/plots/summary.png: invariance (% of range) and mean/min DP per space.
void plotSummary(const std::string& dir, const std::vector<SpaceStats>& stats);

}  // namespace colorlab
