#pragma once
// OverlayControl: what the faces wear (§6). Loads the overlay catalogue into a FaceOverlayLayer,
// keeps who wears what (OverlaySelection) and the last choice across restarts
// (OverlayStateStore), moves the overlays with the smoothed faces (FaceSmoother), lit like the
// scene around each face, and answers the `overlay` command.

#include "automatic_overlays.hpp"
#include "firmware/command_shell.hpp"
#include "firmware/config.hpp"
#include "firmware/face_smoother.hpp"
#include "firmware/overlay_selection.hpp"
#include "firmware/overlay_state_store.hpp"
#include "platform/display.hpp"
#include "render/face_overlay_layer.hpp"
#include "render/renderer.hpp"
#include "vision/face_stage.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace firmware {

class OverlayControl {
public:
    /// Loads the catalogue when `faces` is there and `[overlay] enabled`; adds the layer to
    /// `renderer` (whose context must be current) and draws every overlay once into the
    /// display's framebuffer (not presented). A broken catalogue is one error line and no
    /// overlays (problem() says why). Everything given must outlive this.
    OverlayControl(const Config& config, const vision::FaceStage* faces, render::Renderer& renderer,
                   const platform::Display& display, vision::Size frameSize);

    /// Who wears what; null when nothing is loaded.
    OverlaySelection* selection() noexcept { return selection_.get(); }
    const OverlaySelection* selection() const noexcept { return selection_.get(); }
    /// Why overlays are off although enabled ("" when fine or disabled).
    const std::string& problem() const noexcept { return problem_; }

    /// After the vision stages of a good frame (`faces`, `fits`: FrameState's), on the loop's
    /// clock. A face whose AAM fit holds is drawn by its full pose (headPoseFromFit, §5.3), the
    /// others by their box (the 2D pose).
    void update(std::span<const vision::TrackedFace> faces, std::span<const vision::FaceFit> fits,
                std::int64_t nowNs) noexcept;
    /// `overlay [next|prev|off|list|NAME|mode global|per_face]`; `faces` as for update().
    void command(const Args& args, std::span<const vision::TrackedFace> faces,
                 Reply& reply) noexcept;
    /// For `status`: what is worn, today's and the weather's offers (when the forecast was
    /// fetched) and, per shown face, its overlay and the rule that chose it.
    void formatStatus(std::span<const vision::TrackedFace> faces, Reply& reply) const noexcept;

private:
    void load(const Config& config, vision::Size frameSize);
    void warmUp(vision::Size frameSize);
    void format(std::span<const vision::TrackedFace> faces, Reply& reply) const noexcept;

    const vision::FaceStage* faces_;
    render::Renderer& renderer_;
    const platform::Display& display_;
    std::unique_ptr<render::FaceOverlayLayer> layer_;
    std::unique_ptr<OverlaySelection> selection_;
    std::unique_ptr<OverlayStateStore> store_;
    std::unique_ptr<AutomaticOverlays> automatic_;
    std::uint32_t savedGeneration_ = 0;
    FaceSmoother smoother_;
    vision::Size frameSize_{};  ///< the camera image the faces are in (the overlays' camera)
    /// This frame's faces as the layer draws them (what each wears, its fade and light).
    std::array<render::FaceDrawing, render::FaceOverlayLayer::kMaxFaces> drawings_{};
    std::string problem_;
};

}  // namespace firmware
