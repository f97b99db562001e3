#pragma once
// Ground truth of a card sequence: truth.csv, one row per frame,
//   frame,x0,y0,x1,y1,x2,y2,x3,y3
// corners clockwise on screen from the card's top-left corner, pixels, pixel centres at integer
// coordinates. A row with all eight corner fields empty ("17,,,,,,,,") means no card in view.
// An optional header line starting with "frame", blank lines and '#' comment lines are skipped;
// rows must be numbered 0, 1, 2, ... in order.

#include "vision/geometry.hpp"

#include <istream>
#include <string>
#include <vector>

namespace mirror_eval {

struct TruthRow {
    int frame = 0;
    bool hasCard = false;  ///< false: no card in view (empty corner fields)
    vision::Quad quad{};
};

/// Parses truth rows. `name` prefixes error messages. Throws std::runtime_error with one line,
/// "NAME:LINE: what" for a malformed row, "NAME: no truth rows" for an empty file.
std::vector<TruthRow> parseTruth(std::istream& in, const std::string& name);

/// Reads and parses a truth file; "truth PATH: cannot open" when it cannot be read.
std::vector<TruthRow> loadTruth(const std::string& path);

}  // namespace mirror_eval
