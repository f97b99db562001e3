#pragma once
// mirror-eval track: the firmware's face pipeline (MotionStage + FaceStage, METHOD.md §3-4) over
// a folder of frames in order, scored against per-frame truth, for the configurations of the
// dissertation's Table 6: detector only / + motion mask / + translation tracking / + similarity
// tracking with roll-warped verification. Shown faces are TrackedFace::shown(). `start` (the
// command's --start N) runs from frame N cold: nothing of the frames before it is seen or scored,
// so a face in view at N must be found and shown as at power-on.
//
// Truth layouts (--truth DIR, matched to the frames by file stem):
//  - FGNet talking face: DIR/<stem>.pts, 68 points. One face, always in view. Truth box = the
//    landmarks' bounding box, against which our square face box is matched as the
//    landmark box it implies (face_match.hpp: landmarkConventionBox); truth roll = the line
//    through eye midpoint, nose tip and mouth centre (face_truth.hpp); truth centre = the truth
//    box's centre.
//  - composed (tools/facegen): DIR/<stem>.txt, "id cx cy size roll_deg moving" per face; truth
//    box = the square of `size` about (cx, cy). A shown face on a static face (moving 0) is a
//    false positive; a moving face wholly in the frame that no shown face matches is a false
//    negative. A moving face partly out of view (entering, leaving) is optional: a shown face on
//    it, by IoU with its box or with the part of it in view, is neither a true nor a false
//    positive (counted apart), and missing it is no false negative.
// Matching: shown faces and truth boxes paired one to one by IoU >= minIou, highest first
// (face_match.hpp). Unmatched shown faces are false positives.

#include <cstdio>
#include <string>
#include <vector>

namespace mirror_eval {

struct TrackEvalOptions {
    std::string frames;          ///< folder of frames (png/jpg), in file-name order
    std::string truth;           ///< folder of .pts (FGNet) or .txt (composed) files
    std::string cascade;         ///< empty: detect_eval.hpp's default
    std::string config = "all";  ///< detector | motion | translation | similarity | all
    int downscale = 2;           ///< the motion stage's working resolution (frame / downscale)
    int minSize = 0;             ///< detector min face side in working pixels (0: the window's)
    /// Detector windows per frame (FaceTrackerOptions::detectionWindowBudget) of the tracking
    /// configurations; 0: every scan completes in its frame. The mirror ships
    /// faces.detection_window_budget = 5000.
    long budget = 0;
    float minIou = 0.5f;
    /// The first frame run and scored (index in file-name order): the pipeline starts there
    /// cold (fresh motion model and tracker, as at power-on), and earlier frames are not read.
    int start = 0;
    int maxFrames = 0;      ///< 0: all frames from `start`; else the first N of them (tests)
    bool perFrame = false;  ///< print every frame's shown faces and truth
    /// The static-face rule without LivenessCue (FaceTrackerOptions::livenessBySway = false):
    /// how the tracker did before a calm face's sway counted, for comparison.
    bool noSway = false;
};

/// Table 6 counts for one configuration.
struct TrackScore {
    std::string config;
    long frames = 0;
    long truePositives = 0;
    long falsePositives = 0;
    long falsePositivesOnStatic = 0;  ///< of falsePositives: shown on a static face
    long falseNegatives = 0;
    /// Shown faces on a moving face partly out of view (matched by its box or by the part in
    /// view): neither true nor false positives, as a miss of such a face is no false negative.
    long partlyInView = 0;
    long sceneCuts = 0;  ///< frames the pipeline took for a scene cut (vision::SceneCut)
    std::vector<double> rollErrors;     ///< |roll - truth roll| per true positive
    std::vector<double> centreSteps;    ///< |(c - g)_t - (c - g)_{t-1}| per continued match, px
    std::vector<double> ious;           ///< IoU of every true positive
    std::vector<double> eyeRollErrors;  ///< FGNet: |roll - eye line's roll| per true positive
    /// Composed: motion-mask foreground fraction inside static / moving truth boxes (from frame
    /// 30, once the background model has settled).
    std::vector<double> staticMaskFractions;
    std::vector<double> movingMaskFractions;
    double precision() const;
    double recall() const;
    double rollMeanError() const;
    double jitterMean() const;
};

/// Runs, prints the table and the final line `track: precision=.. recall=..
/// roll_mean_err_deg=..` (the last configuration run) to `out`. Returns the exit code; errors go
/// to `err` as one line.
int runTrackEval(const TrackEvalOptions& options, std::FILE* out, std::FILE* err);

}  // namespace mirror_eval
