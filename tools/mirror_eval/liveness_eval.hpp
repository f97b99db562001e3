#pragma once
// mirror-eval liveness: what a living face does over its first frames in view that a photograph
// on the wall does not (METHOD.md §3, "Detection": still regions are not faces), measured on the
// truth faces of a sequence (face_sequence.hpp), independently of the tracker's own decisions.
//
// A window starts every `every` frames on each truth face wholly in view: Shi-Tomasi corners in
// the inner 0.7 of its box on the motion stage's grey image, followed by pyramidal Lucas-Kanade
// frame to frame (the tracker's defaults), each step's pairs fitted by the robust similarity
// model of §3 and its outliers dropped, as the tracker's corner flow does. After 1 to 25
// steps the window's candidate cues are recorded:
//  - sway: |sum of the steps' median flows| (px), the corners' common displacement;
//  - sway_z: sway over its noise, the steps' corner scatter about their fit (sqrt(sum var/n));
//  - halves: the least, over the corners left, right, above and below the centre, of the
//    fraction of the common displacement that half's summed median flows followed (1: all as one);
//  - rigid: the translation (px) of the similarity fit from the corners' start to now;
//  - together: of the corners, the fraction that moved along that translation by half of it;
//  - nonrigid: the RMS residual (px) of that fit (eyes, mouth, expression; or tracking noise);
//  - change: the 90th percentile less the median of the 8x8 blocks' mean absolute grey change
//    since the start, the box's mean brightness change removed (blinks, a mouth opening);
//  - noise: the noise of one step's median flow (the corners' scatter about the fit / sqrt(n)).
// Faces are of four kinds: `living` (FGNet, a real person), `moving` (facegen's composed
// moving faces, photographs moved by the generator), `static` (facegen's background faces:
// photographs that never move; any composed truth with `moving` 0) and `passed` (a static face
// once a moving one came near: its corners can be dragged by the passer-by). The table gives,
// per kind, cue and step count, the smallest, 1st, 5th, 50th, 95th and 99th percentiles and the
// largest value; a cue separates a living face from a print when the living faces' low
// percentiles lie above the static faces' largest. Then the verdict of the tracker's own cue
// (vision/liveness_cue.hpp) fed the same steps: the fraction of each kind's windows it said
// swayed within k steps, and the last line
//   liveness: living_swayed_12=.. moving_swayed_12=.. static_swayed=.. passed_swayed=..
// (living and moving within 12 steps, half a second at 25 fps; static and passed within 25).

#include <cstdio>
#include <string>

namespace mirror_eval {

struct LivenessEvalOptions {
    std::string frames;      ///< folder of frames (png/jpg), in file-name order
    std::string truth;       ///< folder of .pts (FGNet) or .txt (composed) files
    int downscale = 2;       ///< the motion stage's working resolution (frame / downscale)
    int every = 10;          ///< a window starts on every face every this many frames
    int maxFrames = 0;       ///< 0: all frames
    bool perWindow = false;  ///< one line per window and step count
};

/// Runs, prints the table to `out`. Returns the exit code; errors go to `err` as one line.
int runLivenessEval(const LivenessEvalOptions& options, std::FILE* out, std::FILE* err);

}  // namespace mirror_eval
