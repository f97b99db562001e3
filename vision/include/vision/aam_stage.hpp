#pragma once
// AamStage ("aam"): the AAM fit (§5.3) of every shown face, after the face stage, on the same
// reduced grey image the tracker ran on (the motion stage's). The fits are reported in frame
// coordinates through FrameState::fits, one per face of FrameState::faces, in the same order.
// Built only when a model is loaded (the firmware's pipeline builder).

#include "vision/face_stage.hpp"
#include "vision/motion_stage.hpp"
#include "vision/stage.hpp"
#include "vision/tracked_face_fitter.hpp"

#include <array>

namespace vision {

class AamStage final : public Stage {
public:
    /// Fits the faces of `faces` on `motion`'s grey image (both stages run before this one and
    /// outlive it). Throws std::invalid_argument (one line) for a model the fitter cannot use.
    AamStage(const MotionStage& motion, const FaceStage& faces, const AamModel& model,
             const TrackedFaceFitterOptions& options = {});

    const char* name() const noexcept override { return "aam"; }
    /// Skips invalid frames and frames the motion stage could not use (no fits then: every face
    /// keeps the 2D pose). Sets FrameState::fits either way.
    void process(FrameState& state) noexcept override;

    /// The last frame's fits in frame coordinates.
    std::span<const FaceFit> fits() const noexcept { return {fits_.data(), count_}; }
    const TrackedFaceFitter& fitter() const noexcept { return fitter_; }
    TrackedFaceFitter& fitter() noexcept { return fitter_; }

private:
    const MotionStage& motion_;
    const FaceStage& faces_;
    TrackedFaceFitter fitter_;
    std::array<FaceFit, TrackedFaceFitter::kMaxFaces> fits_{};
    std::size_t count_ = 0;
};

}  // namespace vision
