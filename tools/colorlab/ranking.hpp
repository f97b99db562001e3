#pragma once
// The ranking of the colour spaces for one recording.
//
// Criterion: each space gets three ranks (1 = best): invariance (lower mean normalised standard
// deviation of the chromatic components, % of range), mean DP over all pairs (higher), and minimum
// DP (higher: the worst-separated pair). The spaces are ordered by the sum of the three ranks;
// ties go to the higher mean DP. Ranks rather than a weighted sum because the three measures have
// no common unit.

#include "statistics.hpp"

#include <string>
#include <vector>

namespace colorlab {

struct RankedSpace {
    vision::ColorSpace space{};
    int invarianceRank = 0;
    int dpMeanRank = 0;
    int dpMinRank = 0;
    int score = 0;  ///< sum of the three ranks, lower is better
};

/// Best first.
std::vector<RankedSpace> rankSpaces(const std::vector<SpaceStats>& stats);

/// "ranking: chromaticity > c1c2c3 > ..."
std::string rankingLine(const std::vector<RankedSpace>& ranking);

}  // namespace colorlab
