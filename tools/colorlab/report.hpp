#pragma once
// colorlab's tables: the per-sample series (CSV), the standard deviation and discriminative-power
// tables (CSV for tools, TXT for people) and the ranking. Each writer throws std::runtime_error
// with one line naming the file when it cannot write.

#include "ranking.hpp"
#include "sampling.hpp"
#include "statistics.hpp"

#include <string>
#include <vector>

namespace colorlab {

/// How the frames were used, for the headers of the tables.
struct FrameUse {
    int total = 0;
    int saturated = 0;
    bool excluded = false;  ///< --exclude-saturated
    int used() const noexcept { return excluded ? total - saturated : total; }
};

/// DIR/series/<sample>_<space>.csv: `frame,<components>,saturated` for every used frame.
void writeSeries(const std::string& dir, const Recording& rec, const std::vector<bool>& useRow);

/// DIR/saturated.txt: the frame numbers with a clipped channel in some sample's disc.
void writeSaturatedFrames(const std::string& dir, const Recording& rec);

/// DIR/stdev.csv and DIR/stdev.txt.
void writeStdevTables(const std::string& dir, const Recording& rec,
                      const std::vector<SpaceStats>& stats, const FrameUse& use);

/// DIR/dp.csv and DIR/dp.txt.
void writeDpTables(const std::string& dir, const Recording& rec,
                   const std::vector<SpaceStats>& stats, const FrameUse& use);

/// The ranking table with its criterion, ending in the `ranking: a > b > ...` line.
std::string rankingText(const std::vector<SpaceStats>& stats,
                        const std::vector<RankedSpace>& ranking);

/// Writes `text` to DIR/NAME.
void writeText(const std::string& dir, const std::string& name, const std::string& text);

}  // namespace colorlab
