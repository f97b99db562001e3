#pragma once
// mirror-eval aam: the AAM fit (§5) scored against truth, beside dlib's 68-point shape predictor
// given the same face boxes (dlib's HOG detector's). Three inputs:
//  - --frames DIR --truth DIR: an annotated sequence (FGNet talking face .pts, or another scheme
//    of tools/aam's tables): NME on the points the truth's scheme and CANDIDE share, inner points
//    (eyes, nose, lips) and all, mean and 90th percentile over frames; frames lost; iterations and
//    ms per frame; jaw drop against the annotated mouth opening (Pearson). Final line
//    `aam: frames=.. nme=.. nme_p90=.. nme_all=.. dlib_nme=.. jaw_corr=.. iters=.. ms_per_frame=..
//    lost=..`;
//  - --synthetic DIR: headgen output: yaw / pitch / roll mean absolute error and animation RMSE,
//    without and with the hand, and the same NME; final line `aam-synthetic: ...`;
//  - --imm DIR: the IMM photographs of types 1 (frontal), 3 and 4 (turned about 30 degrees to the
//    person's right and left): the fitted yaw per type; final line `aam-imm: ...`.
// Our side is a HeadFitRunner (head_fit_runner.hpp); until vision's fit lands, the mean shape
// baseline, which every row and the final line label as a placeholder. See README.md.

#include "dlib_peer.hpp"

#include <cstdio>
#include <string>

namespace mirror_eval {

struct AamEvalOptions {
    std::string frames, truth;  ///< an annotated sequence
    std::string synthetic;      ///< a headgen folder
    std::string imm;            ///< the IMM face database folder
    std::string scheme = "fgnet";
    std::string fitter = "baseline";
    std::string model;  ///< the .aam file a real fit loads
    std::string dataDir = "../shared/data";
    std::string predictor = kDlibShapePredictor;
    std::string boxes;  ///< --frames: the HOG boxes kept between runs (box_cache.hpp)
    int start = 0;
    int maxFrames = 0;        ///< 0: all
    int upsample = 0;         ///< the HOG detector's pyramid_up passes
    bool allPersons = false;  ///< --imm: the persons the demo model was built from too
    bool perFrame = false;
};

/// Runs, prints the report and its final line to `out`. Returns 0; 2 for bad arguments and 1 for
/// unreadable data, each with one line on `err`.
int runAamEval(const AamEvalOptions& options, std::FILE* out, std::FILE* err);

}  // namespace mirror_eval
