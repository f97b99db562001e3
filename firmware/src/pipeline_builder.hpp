#pragma once
// The vision pipeline the config asks for: frame check, deinterlacer, chromaticity, the card
// tracker (§2), motion and faces (§3-§4), in the order they run.

#include "firmware/config.hpp"
#include "vision/card_stage.hpp"
#include "vision/face_stage.hpp"
#include "vision/motion_stage.hpp"
#include "vision/pipeline.hpp"

namespace firmware {

/// The stages the loop talks to besides running them (null when the config leaves them out);
/// they live in the pipeline.
struct VisionStages {
    vision::CardStage* card = nullptr;
    vision::MotionStage* motion = nullptr;
    vision::FaceStage* faces = nullptr;
};

/// Adds every configured stage for frames of `size` and `format` to `pipeline`. Throws on bad
/// options or a missing or broken face cascade (one line).
VisionStages buildPipeline(const Config& config, vision::Size size, vision::PixelFormat format,
                           vision::Pipeline& pipeline);

}  // namespace firmware
