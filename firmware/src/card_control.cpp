#include "card_control.hpp"

#include "firmware/log.hpp"
#include "platform/image_file.hpp"
#include "render/default_card_picture.hpp"

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

namespace firmware {

CardControl::CardControl(const Config& config, vision::CardStage& stage, render::Renderer& renderer,
                         vision::Size frameSize)
    : trainFraction_(config.card.trainFraction), stage_(stage)
{
    // The trained colour survives restarts; a corrupt file is reported and ignored.
    store_ = std::make_unique<CardModelStore>(config.state.dir);
    if (!store_->usable())
        MIRROR_LOG_WARN("card: %s; a trained colour will not be kept across restarts",
                        store_->lastError());
    std::string warning;
    if (const auto model = store_->load(warning)) {
        stage_.tracker().setModel(*model);
        MIRROR_LOG_INFO("card: colour loaded from %s", store_->path().c_str());
    } else if (!warning.empty()) {
        MIRROR_LOG_WARN("card: %s", warning.c_str());
    } else {
        MIRROR_LOG_INFO(
            "card: not trained yet (console: card train, with the card filling the "
            "middle of the view)");
    }

    // The picture: the configured file, else the built-in one; a file that cannot be read is
    // reported and the card's outline is drawn instead, so tracking still shows.
    vision::ImageBuffer picture;
    if (config.card.picture.empty()) {
        picture = render::defaultCardPicture({640, 452});
    } else {
        try {
            picture = platform::loadImageFile(config.card.picture, "card picture");
        } catch (const std::exception& e) {
            MIRROR_LOG_ERROR("%s; drawing the card's outline instead", e.what());
        }
    }
    const vision::ConstImageView view =
        picture.empty() ? vision::ConstImageView{} : vision::ConstImageView(picture.view());
    layer_ = std::make_unique<render::CardPictureLayer>(view, frameSize);
    renderer.addLayer(layer_.get());
}

void CardControl::requestTraining() noexcept
{
    // Step 1 of §2: the card stage learns the colour from the centre of the next good frame
    // (the card held there), the same way mirror-eval trains it.
    stage_.requestTraining(static_cast<float>(trainFraction_));
    trainPending_ = true;
}

const char* CardControl::update(const vision::FrameState& state) noexcept
{
    const bool trained = trainPending_ && !stage_.trainingPending();
    if (trained)
        reportTraining();
    const vision::CardState now =
        state.card ? state.card->state : stage_.tracker().observation().state;
    if (now != state_)
        MIRROR_LOG_INFO("card: %s -> %s", vision::cardStateName(state_),
                        vision::cardStateName(now));
    state_ = now;
    layer_->update(state.card);
    return trained ? report_ : nullptr;
}

void CardControl::reportTraining() noexcept
{
    trainPending_ = false;
    const double f = trainFraction_;
    char* line = report_;
    const vision::CardTracker& tracker = stage_.tracker();
    bool warn = false;  // refused, or trained but not kept (gone at the next start)
    const vision::CardTrainingCheck& check = stage_.lastTrainingCheck();
    if (!stage_.lastTrainingSucceeded() && check.sigma > 0.f && !check.ok()) {
        // The centre was not the card: say by how much, and keep what was trained before.
        const vision::CardTrainingLimits limits;
        std::snprintf(
            line, sizeof report_,
            "card: training refused: the central %.0f%% is not one uniform, saturated "
            "colour (spread %.1f, at most %.0f; saturation %.1f, at least %.0f; "
            "brightness %.0f, at least %.0f); %s\n",
            f * 100, static_cast<double>(check.sigma), static_cast<double>(limits.maxSigma),
            static_cast<double>(check.saturation), static_cast<double>(limits.minSaturation),
            static_cast<double>(check.brightness), static_cast<double>(limits.minBrightness),
            tracker.trainedModel().valid ? "the previous colour stays" : "still not trained");
        warn = true;
    } else if (!stage_.lastTrainingSucceeded()) {
        std::snprintf(line, sizeof report_,
                      "card: training failed (no usable pixels in the centre)\n");
    } else {
        const vision::CardColorModel& m = tracker.trainedModel();
        const bool saved = store_ && store_->save(m);
        warn = !saved;
        std::snprintf(
            line, sizeof report_,
            "card: trained on the central %.0f%% (r %.1f g %.1f b %.1f, sigma %.1f %.1f "
            "%.1f), %s %.400s\n",
            f * 100, static_cast<double>(m.mean[0]), static_cast<double>(m.mean[1]),
            static_cast<double>(m.mean[2]), static_cast<double>(m.sigma[0]),
            static_cast<double>(m.sigma[1]), static_cast<double>(m.sigma[2]),
            saved ? "saved to" : "NOT saved:",
            saved ? store_->path().c_str() : (store_ ? store_->lastError() : "no state folder"));
    }
    // A refusal, or a colour trained but not kept (lost at the next start): the technician must
    // see it.
    if (warn)
        MIRROR_LOG_WARN("%.*s", static_cast<int>(std::strlen(line)) - 1, line);
    else
        MIRROR_LOG_INFO("%.*s", static_cast<int>(std::strlen(line)) - 1, line);
}

void CardControl::command(const Args& args, Reply& reply) noexcept
{
    if (args.size() == 1) {
        format(reply);
    } else if (args[1] == "train" && args.size() == 2) {
        requestTraining();
        reply.printf(
            "card: hold the card in the middle of the view; training "
            "on the next frame\n");
    } else if (args[1] == "reset" && args.size() == 2) {
        stage_.tracker().reset();
        reply.printf("card: track reset, searching\n");
    } else if (args[1] == "forget" && args.size() == 2) {
        forget(reply);
    } else {
        reply.printf("error: usage: card [train|reset|forget]\n");
    }
}

void CardControl::forget(Reply& reply) noexcept
{
    stage_.tracker().forgetModel();
    if (!store_) {
        reply.printf("card: colour forgotten, not trained\n");
    } else if (store_->remove()) {
        MIRROR_LOG_INFO("card: colour forgotten, %s removed", store_->path().c_str());
        reply.printf("card: colour forgotten, %s removed; not trained\n", store_->path().c_str());
    } else {
        MIRROR_LOG_WARN("card: colour forgotten, but %s", store_->lastError());
        reply.printf("card: colour forgotten until the next start: %s\n", store_->lastError());
    }
}

void CardControl::format(Reply& reply) const noexcept
{
    const vision::CardTracker& tracker = stage_.tracker();
    const vision::CardObservation& o = tracker.observation();
    reply.printf("card: %s, confidence %.2f, area %d px\n", vision::cardStateName(o.state),
                 static_cast<double>(o.confidence), o.area);
    if (o.hasQuad)
        reply.printf("corners: (%.1f, %.1f) (%.1f, %.1f) (%.1f, %.1f) (%.1f, %.1f)\n",
                     static_cast<double>(o.quad[0].x), static_cast<double>(o.quad[0].y),
                     static_cast<double>(o.quad[1].x), static_cast<double>(o.quad[1].y),
                     static_cast<double>(o.quad[2].x), static_cast<double>(o.quad[2].y),
                     static_cast<double>(o.quad[3].x), static_cast<double>(o.quad[3].y));
    const vision::CardColorModel& m = tracker.trainedModel();
    if (m.valid)
        reply.printf("colour: r %.1f g %.1f b %.1f, sigma %.1f %.1f %.1f (%s)\n",
                     static_cast<double>(m.mean[0]), static_cast<double>(m.mean[1]),
                     static_cast<double>(m.mean[2]), static_cast<double>(m.sigma[0]),
                     static_cast<double>(m.sigma[1]), static_cast<double>(m.sigma[2]),
                     store_ ? store_->path().c_str() : "not kept");
    else
        reply.printf("colour: not trained (card train)\n");
    reply.printf("picture: %s\n",
                 layer_->outlineMode() ? "none (drawing the outline)" : "shown on the card");
}

}  // namespace firmware
