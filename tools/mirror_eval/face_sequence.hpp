#pragma once
// A folder of frames with per-frame face truth, as `mirror-eval track` and `liveness` read it:
// the frames (PNG/JPEG) in file-name order, each matched by its stem to a truth file in the
// truth folder, in one of two layouts (face_truth.hpp):
//  - FGNet talking face: <stem>.pts, 68 points; one face, always in view. Truth box = the
//    landmarks' bounding box, centre = its centre, roll = the line through eye midpoint, nose tip
//    and mouth centre;
//  - composed (tools/facegen): <stem>.txt, one face per line; box = the square of `size` about
//    (cx, cy); `moving` 0 marks a static face of the background (a photograph on the wall).

#include "face_match.hpp"
#include "vision/geometry.hpp"

#include <string>
#include <vector>

namespace mirror_eval {

/// One truth face of a frame in the common form of both layouts.
struct TruthFace {
    int id = 0;
    BoxF box{};
    vision::Point2f centre{};
    double rollDegrees = 0.0;
    double eyeRollDegrees = 0.0;  ///< FGNet: the eye line's roll (diagnostic)
    bool moving = true;
};

struct FaceSequence {
    bool composed = false;
    std::vector<std::string> frames;            ///< paths, in order
    std::vector<std::vector<TruthFace>> truth;  ///< per frame
};

/// The frames of `framesDir` from index `start` on (the first `maxFrames` of them; 0: all) and
/// their truth from `truthDir`. Throws std::runtime_error with a one-line reason (not a folder,
/// no frames, `start` beyond the last frame, a truth file missing or malformed).
FaceSequence loadFaceSequence(const std::string& framesDir, const std::string& truthDir,
                              int start = 0, int maxFrames = 0);

}  // namespace mirror_eval
