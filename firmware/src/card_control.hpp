#pragma once
// CardControl: the loop's side of the colour card (§2). The tracker runs in the pipeline's
// CardStage; this keeps its trained colour across restarts (CardModelStore), draws the picture
// on it (CardPictureLayer), trains on request and reports, logs state changes once, and answers
// the `card` command.

#include "firmware/card_model_store.hpp"
#include "firmware/command_shell.hpp"
#include "firmware/config.hpp"
#include "render/card_picture_layer.hpp"
#include "render/renderer.hpp"
#include "vision/card_stage.hpp"

#include <memory>

namespace firmware {

class CardControl {
public:
    /// Loads the kept colour into `stage` and adds the picture layer to `renderer` (whose
    /// context must be current). Both must outlive this.
    CardControl(const Config& config, vision::CardStage& stage, render::Renderer& renderer,
                vision::Size frameSize);

    /// Trains the colour on the next good frame (as `card train` does).
    void requestTraining() noexcept;
    /// After the vision stages of a good frame: saves and reports a finished training, logs a
    /// changed state, gives the picture layer the card. Returns the training report for the
    /// consoles (null when there is none this frame).
    const char* update(const vision::FrameState& state) noexcept;
    vision::CardState state() const noexcept { return state_; }
    float confidence() const noexcept { return stage_.tracker().observation().confidence; }
    /// `card [train|reset|forget]`.
    void command(const Args& args, Reply& reply) noexcept;

private:
    void reportTraining() noexcept;
    /// Back to untrained: the model in the stage and the saved file both go.
    void forget(Reply& reply) noexcept;
    void format(Reply& reply) const noexcept;

    double trainFraction_;
    vision::CardStage& stage_;
    std::unique_ptr<CardModelStore> store_;
    std::unique_ptr<render::CardPictureLayer> layer_;
    vision::CardState state_ = vision::CardState::Untrained;
    bool trainPending_ = false;  // asked for; reported once the stage has trained
    char report_[640] = "";
};

}  // namespace firmware
