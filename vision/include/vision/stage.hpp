#pragma once
// Stage: one step of the vision pipeline, run once per frame in a fixed order. The firmware times
// each stage; stages share results through FrameState. process() never throws and never allocates:
// everything a stage needs is allocated in its constructor, sized from the configured resolution.

#include "vision/card_tracker.hpp"
#include "vision/chromaticity.hpp"
#include "vision/face_fit.hpp"
#include "vision/face_tracker.hpp"
#include "vision/image.hpp"

#include <span>

namespace vision {

/// Everything the stages know about the current frame. Reset by the pipeline for every frame.
struct FrameState {
    Frame frame;
    /// False once a stage found the frame unusable; later stages then skip their work.
    bool valid = true;
    /// Why the frame is unusable (a static string), "" while valid.
    const char* problem = "";
    /// Chromaticity planes (§1) when the chromaticity stage ran, empty views otherwise.
    ChromaticityPlanes chroma{};
    /// The colour card (§2) when the card stage ran, null otherwise.
    const CardObservation* card = nullptr;
    /// The motion stage's foreground mask (reduced resolution, 255 = moving), empty otherwise.
    ConstImageView motionMask{};
    /// Tracked faces (§3) in frame coordinates when the face stage ran (shown() ones are the
    /// confirmed faces), empty otherwise. Valid until the next frame.
    std::span<const TrackedFace> faces{};
    /// The AAM fits (§5.3) of `faces` in frame coordinates, one per face in the same order, when
    /// the AAM stage ran (a model is loaded), empty otherwise. Valid until the next frame.
    std::span<const FaceFit> fits{};
};

class Stage {
public:
    virtual ~Stage() = default;
    Stage() = default;
    Stage(const Stage&) = delete;
    Stage& operator=(const Stage&) = delete;

    /// Short name for timing tables and logs, e.g. "chromaticity".
    virtual const char* name() const noexcept = 0;
    virtual void process(FrameState& state) noexcept = 0;
};

}  // namespace vision
