#pragma once
// mirror-bench --ratios: times the target pairs of issue 3 in one run and prints the raw times,
// then one line per target:
//   ratio chroma_vs_opencv_exact <x>   OpenCV's faster exact float formulation / ours (higher is
//   better) ratio chroma_vs_seed_lut <x>       the dissertation's Table 5 loop (-O3) / ours (higher
//   is better) ratio card_tracker_ms <ms>         median ms per 720x480 frame: chromaticity +
//   CardTracker::process

namespace bench {

class ChromaticityCases;
class CardTrackerCase;

void printRatios(ChromaticityCases& chroma, CardTrackerCase& card);

}  // namespace bench
