#pragma once
// What each headgen frame shows, drawn from a seed: the head's pose and expression, which
// texture and background, and the hand. Two kinds:
//  - a sequence: one person over one background, every value a smooth function of time (two
//    sines each, at 30 frames per second), as a person turning and talking in front of the
//    mirror; the hand, when asked for, rests on the chin over the middle third of the frames;
//  - single frames: every frame drawn afresh (person, background, pose, expression); the hand,
//    when asked for, on every other frame.
// Where the text is silent: yaw within +-maxYaw (the targets' 30 degrees), pitch within +-20, roll
// within +-20, each animation unit within aam::kAnimationRange (the model's training range).

#include "hand_occluder.hpp"
#include "head_projection.hpp"

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace headgen {

enum class HandMode { None, Some, All };
/// "none", "some" or "all"; throws std::invalid_argument otherwise.
HandMode handModeNamed(const std::string& name);

struct MotionOptions {
    int frames = 60;
    std::uint32_t seed = 1;
    cv::Size size{640, 480};
    bool sequence = true;
    HandMode hand = HandMode::None;
    double maxYawDeg = 30, maxPitchDeg = 20, maxRollDeg = 20;
};

struct FramePlan {
    HeadPose2d pose;  ///< pose.scale and translation in frame pixels
    int texture = 0;
    int background = 0;
    bool hand = false;
    double handAngleDeg = 0;  ///< the fingers' direction, relative to the face's roll
    double handSide = 0;      ///< -1..1: where under the mouth the palm sits, across the face
};

/// One plan per frame, the same for the same options. `textures` and `backgrounds` are the
/// counts to choose from (>= 1).
std::vector<FramePlan> planFrames(const MotionOptions& options, int textures, int backgrounds);

}  // namespace headgen
