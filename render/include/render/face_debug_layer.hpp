#pragma once
// FaceDebugLayer: the debug HUD of the face tracker (METHOD.md §3-4): for every track its box
// turned by the roll, the roll axis through the face, and the corners being tracked. Shown faces
// are green, tentative ones yellow, missed ones (within grace) orange.
#include "render/overlay_layer.hpp"
#include "vision/face_tracker.hpp"

#include <memory>
#include <span>

namespace render {

class FaceDebugLayer : public OverlayLayer {
public:
    static constexpr int kMaxFaces = 16;
    static constexpr int kMaxPointsPerFace = 64;

    /// Needs the GL context current. Throws std::runtime_error with one line when the shader or
    /// buffer cannot be made.
    FaceDebugLayer();
    ~FaceDebugLayer() override;
    FaceDebugLayer(const FaceDebugLayer&) = delete;
    FaceDebugLayer& operator=(const FaceDebugLayer&) = delete;

    const char* name() const noexcept override { return "face debug"; }
    /// Copies this frame's faces (camera-frame coordinates); extra faces and points are dropped.
    void update(std::span<const vision::TrackedFace> faces) noexcept;
    void setVisible(bool visible) noexcept { visible_ = visible; }
    bool visible() const noexcept { return visible_; }
    void draw(const LayerContext& context) noexcept override;

private:
    struct Gl;
    std::unique_ptr<Gl> gl_;
    bool visible_ = false;
};

}  // namespace render
