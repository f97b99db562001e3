#pragma once
// The truth of one headgen frame, as a small text file (truth/NNNNNN.txt beside
// frames/NNNNNN.png), read back by `mirror-eval aam --synthetic`:
//
//   # headgen truth: tools/headgen/README.md
//   source 04-1m                                   the IMM photograph the texture is from
//   pose YAW PITCH ROLL SCALE TX TY                degrees (roll clockwise on screen), px/unit, px
//   animation JAW LIPSTRETCH BROWLOWER OUTERBROW UPPERLIP LIPCORNER vision::kTrackedAnimationUnits
//   box X0 Y0 X1 Y1                                the projected mesh's bounding box, px
//   hand PRESENT X Y WIDTH ANGLE                   the occluder (hand_occluder.hpp); 0 0 0 0 0 if
//   none vertex INDEX CANDIDE X Y SEEN                  one per mesh vertex, in mesh order
//
// Errors are one line, "NAME:LINE: what".

#include "hand_occluder.hpp"
#include "head_projection.hpp"

#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace headgen {

struct TruthVertex {
    int candide = 0;  ///< CANDIDE-3's number
    Eigen::Vector2d image = Eigen::Vector2d::Zero();
    bool seen = false;  ///< facing the camera, not behind the head itself or the hand
};

struct HeadTruth {
    std::string source;
    HeadPose2d pose;
    Eigen::Vector4d box = Eigen::Vector4d::Zero();  ///< x0 y0 x1 y1
    Hand hand;
    std::vector<TruthVertex> vertices;
};

void writeHeadTruth(std::ostream& out, const HeadTruth& truth);
HeadTruth readHeadTruth(std::istream& in, const std::string& name);
/// Throws std::runtime_error "PATH: cannot open" when the file cannot be read.
HeadTruth loadHeadTruth(const std::string& path);

}  // namespace headgen
