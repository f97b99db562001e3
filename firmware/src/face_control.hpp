#pragma once
// FaceControl: the loop's side of the faces (§3-§4). The tracker runs in the pipeline's
// MotionStage and FaceStage; this logs changes of the shown-face count once, feeds the debug HUD
// (FaceDebugLayer: boxes, corners, roll axes, and the fitted meshes of the AAM, §5.3, when its
// stage runs) and answers the `faces` command (with the AAM: each face's pose, animation values,
// fit error and iterations).

#include "firmware/command_shell.hpp"
#include "render/face_debug_layer.hpp"
#include "render/renderer.hpp"
#include "vision/aam_stage.hpp"
#include "vision/face_stage.hpp"
#include "vision/motion_stage.hpp"

#include <memory>
#include <span>

namespace firmware {

class FaceControl {
public:
    /// Adds the debug layer to `renderer` (whose context must be current), shown when
    /// `debugHud`. The stages and the renderer must outlive this; `aam` may be null (no model).
    FaceControl(vision::MotionStage& motion, vision::FaceStage& faces, vision::AamStage* aam,
                render::Renderer& renderer, bool debugHud);

    /// After the vision stages of a good frame: `faces` and `fits` are FrameState's.
    void update(std::span<const vision::TrackedFace> faces,
                std::span<const vision::FaceFit> fits = {}) noexcept;
    /// Faces shown in the last good frame.
    int shown() const noexcept { return shown_; }
    /// The tracks are stale (the camera was away): start afresh with a whole-image scan.
    void forgetTracks() noexcept
    {
        faces_.tracker().reset();
        if (aam_ != nullptr)
            aam_->fitter().reset();
    }
    void setDebugHud(bool on) noexcept { debug_->setVisible(on); }
    bool debugHud() const noexcept { return debug_->visible(); }
    /// The AAM's stage runs (a model loaded, §5.3).
    bool aamLoaded() const noexcept { return aam_ != nullptr; }
    /// Writes what `faces` prints: the counts, then one line per tracked face.
    void format(Reply& reply) const noexcept;

private:
    vision::MotionStage& motion_;
    vision::FaceStage& faces_;
    vision::AamStage* aam_;
    std::unique_ptr<render::FaceDebugLayer> debug_;
    int shown_ = 0;  // shown faces last frame, for logging changes once
    long cuts_ = 0;  // scene cuts logged
};

}  // namespace firmware
