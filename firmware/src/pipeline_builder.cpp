#include "pipeline_builder.hpp"

#include "firmware/log.hpp"
#include "vision/aam_model.hpp"
#include "vision/chromaticity_stage.hpp"
#include "vision/deinterlace_stage.hpp"
#include "vision/frame_check_stage.hpp"
#include "vision/haar_cascade.hpp"

#include <memory>
#include <stdexcept>

namespace firmware {

namespace {

constexpr const char* kTrackingNames[] = {"none", "translation", "similarity", "affine"};

vision::FaceTrackingMode trackingMode(FacesConfig::Tracking tracking) noexcept
{
    switch (tracking) {
        case FacesConfig::Tracking::None:
            return vision::FaceTrackingMode::None;
        case FacesConfig::Tracking::Translation:
            return vision::FaceTrackingMode::Translation;
        case FacesConfig::Tracking::Similarity:
            return vision::FaceTrackingMode::Similarity;
        case FacesConfig::Tracking::Affine:
            return vision::FaceTrackingMode::Affine;
    }
    return vision::FaceTrackingMode::Similarity;
}

vision::FaceTrackerOptions faceTrackerOptions(const Config& config)
{
    const FacesConfig& c = config.faces;
    vision::FaceTrackerOptions o;
    o.detector.scaleFactor = c.scaleFactor;
    o.detector.minNeighbors = c.minNeighbors;
    o.detector.minSize = {c.minSize, c.minSize};
    o.mode = trackingMode(c.tracking);
    // Where and how much to scan per frame.
    o.useMotionMask = c.motionMask;
    o.detectionWindowBudget = c.detectionBudget;
    o.tiltScanDegrees = static_cast<float>(c.tiltScanDeg);
    o.tiltWindowBudget = c.tiltWindowBudget;
    // Fig. 89: how many faces, n frames to show one, m misses to drop it.
    o.maxFaces = c.maxFaces;
    o.confirmFrames = c.confirmFrames;
    o.graceFrames = c.graceFrames;
    o.occludedGraceFrames = c.occludedGraceFrames;
    const double fps = config.source.fps > 0 ? config.source.fps : 30.0;
    o.staticDropFrames = static_cast<int>(c.staticDropS * fps + 0.5);
    return o;
}

/// §3: motion at reduced resolution, then detection and tracking on the same grey image.
void addFaceStages(const Config& config, vision::Size size, vision::Pipeline& pipeline,
                   VisionStages& stages)
{
    const FacesConfig& c = config.faces;
    vision::MotionStageOptions motion;
    motion.downscale = c.downscale;
    motion.detector.components = c.motionComponents;
    motion.detector.learningRate = static_cast<float>(c.motionLearningRate);
    auto motionStage = std::make_unique<vision::MotionStage>(size, motion);

    const vision::FaceTrackerOptions o = faceTrackerOptions(config);
    // The cascade is read once here; a missing or broken file stops start-up with one line.
    const vision::HaarCascade cascade = vision::loadHaarCascade(c.cascade);
    auto faceStage = std::make_unique<vision::FaceStage>(*motionStage, cascade, o);
    stages.motion = motionStage.get();
    stages.faces = faceStage.get();
    pipeline.add(std::move(motionStage));
    pipeline.add(std::move(faceStage));
    const vision::ConstImageView gray = stages.motion->gray();
    MIRROR_LOG_INFO("faces: %s at %dx%d, tracking %s", c.cascade.c_str(), gray.width, gray.height,
                    kTrackingNames[static_cast<int>(c.tracking)]);
}

/// §5.3: the AAM fit of every shown face, after the face stage, when `[faces] model` names a model
/// that loads. Anything wrong with it is one warning line: the mirror runs on with the 2D pose.
void addAamStage(const Config& config, vision::Pipeline& pipeline, VisionStages& stages)
{
    const std::string& path = config.faces.model;
    const vision::AamModelFile file = vision::loadAamModel(path);
    if (!file.ok) {
        MIRROR_LOG_WARN("faces: model %s; faces keep the 2D pose", file.problem.c_str());
        return;
    }
    try {
        auto stage = std::make_unique<vision::AamStage>(*stages.motion, *stages.faces, file.model);
        MIRROR_LOG_INFO("faces: model %s (%d vertices, %zu shape modes, %zu appearance modes)",
                        path.c_str(), stage->fitter().vertexCount(), file.model.shapeModeCount(),
                        file.model.appearanceModeCount());
        stages.aam = stage.get();
        stages.modelId = PersonStore::modelIdOf(path);
        pipeline.add(std::move(stage));
    } catch (const std::exception& e) {
        MIRROR_LOG_WARN("faces: model %s: %s; faces keep the 2D pose", path.c_str(), e.what());
    }
}

}  // namespace

VisionStages buildPipeline(const Config& config, vision::Size size, vision::PixelFormat format,
                           vision::Pipeline& pipeline)
{
    VisionStages stages;
    pipeline.add(std::make_unique<vision::FrameCheckStage>(size, format));
    if (config.vision.deinterlace)
        pipeline.add(std::make_unique<vision::DeinterlaceStage>(size, format));
    // The card's colour test works on chromaticity (§1): the tracker needs the planes.
    if (config.vision.chromaticity || config.card.enabled)
        pipeline.add(std::make_unique<vision::ChromaticityStage>(size));
    if (config.card.enabled) {
        vision::CardTrackerOptions options;
        options.threshold = static_cast<float>(config.card.threshold);
        options.alpha = static_cast<float>(config.card.alpha);
        options.beta = static_cast<float>(config.card.beta);
        auto stage = std::make_unique<vision::CardStage>(size, options);
        stages.card = stage.get();
        pipeline.add(std::move(stage));
    }
    if (config.faces.enabled) {
        addFaceStages(config, size, pipeline, stages);
        if (!config.faces.model.empty())
            addAamStage(config, pipeline, stages);
    }
    return stages;
}

}  // namespace firmware
