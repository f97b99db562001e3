#pragma once
// The illumination experiment (3.2-3.4) on one recording: read the frames, sample them, and write
// the series, tables, plots and ranking into the output folder.

#include "ranking.hpp"
#include "report.hpp"
#include "sampling.hpp"
#include "statistics.hpp"

#include <string>
#include <vector>

namespace colorlab {

struct AnalysisOptions {
    std::string input;            ///< video file, folder of frames, or glob (platform::FileSource)
    std::string samplesFile;      ///< `name x y [radius]` lines; or empty with `grid`
    std::string grid;             ///< "NxM"; used when samplesFile is empty
    int radius = kDefaultRadius;  ///< for grid samples
    std::string outDir;
    bool excludeSaturated = false;
    long maxFrames = 0;  ///< 0: every frame
    bool plots = true;
};

struct AnalysisResult {
    Recording recording;
    FrameUse frames;
    std::vector<SpaceStats> stats;  ///< in the order of vision::colorSpaces()
    std::vector<RankedSpace> ranking;
    std::string rankingText;  ///< as written to ranking.txt, last line `ranking: ...`
};

/// Opens the input (std::runtime_error on a missing or undecodable file, exit 1) and the sample
/// list (SampleError, exit 2), measures every frame.
Recording readRecording(const AnalysisOptions& options);

/// Which rows count: all, or those without a saturated sample when excluding.
std::vector<bool> usedRows(const Recording& recording, bool excludeSaturated);

/// Statistics and ranking of a recording (throws std::runtime_error when no frame is usable).
AnalysisResult analyseRecording(Recording recording, bool excludeSaturated);

/// readRecording + analyseRecording + every output file in options.outDir.
AnalysisResult runAnalysis(const AnalysisOptions& options);

}  // namespace colorlab
