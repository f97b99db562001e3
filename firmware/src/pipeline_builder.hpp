#pragma once
// The vision pipeline the config asks for: frame check, deinterlacer, chromaticity, the card
// tracker (§2), motion and faces (§3-§4), and the AAM fit of each face (§5.3) when a model is
// loaded, in the order they run.

#include "firmware/config.hpp"
#include "firmware/person_store.hpp"
#include "vision/aam_stage.hpp"
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
    vision::AamStage* aam = nullptr;  ///< null without `[faces] model` or when it did not load
    /// The loaded model's identity (PersonStore::modelIdOf): a person's signature is the model's.
    std::uint32_t modelId = 0;
};

/// Adds every configured stage for frames of `size` and `format` to `pipeline`. Throws on bad
/// options or a missing or broken face cascade (one line). The AAM model (`[faces] model`) is read
/// here: a missing or broken one is one warning line, and the faces keep the 2D pose.
VisionStages buildPipeline(const Config& config, vision::Size size, vision::PixelFormat format,
                           vision::Pipeline& pipeline);

}  // namespace firmware
