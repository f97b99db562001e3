#pragma once
// mirror-eval card: runs the firmware's vision pipeline (frame check, [deinterlace,] chromaticity,
// card stage)
// over a recorded or generated sequence and scores the card tracker against its ground truth.

#include "card_metrics.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace mirror_eval {

struct CardEvalOptions {
    std::string video;           ///< a video file or a folder of frames (FileSource)
    std::string truth;           ///< truth.csv (truth_file.hpp)
    float trainFraction = 1.0f;  ///< central fraction of frame 0 that trains the colour model
    std::string perFrameCsv;     ///< when set, per-frame results are written there
    bool deinterlace = false;    ///< run the deinterlace stage first, as vision.deinterlace = true
};

/// The tracker's output for every frame of the sequence. Frame 0 trains (then is tracked as
/// usual, like the appliance's CardStage). Throws std::runtime_error with one line when the video
/// cannot be opened, a frame cannot be decoded, or the frame count differs from `truthRows`.
std::vector<TrackedFrame> runCardTracker(const CardEvalOptions& options, std::size_t truthRows,
                                         vision::Size& frameSize);

/// The whole sub-command: loads, runs, scores, prints the report and the final summary line to
/// `out`. Returns the process exit code; errors go to `err` as one line.
int runCardEval(const CardEvalOptions& options, std::FILE* out, std::FILE* err);

}  // namespace mirror_eval
