#pragma once
// FaceDebugLayer: the debug HUD of the face tracker (METHOD.md §3-4): for every track its box
// turned by the roll, the roll axis through the face, and the corners being tracked. Shown faces
// are green, tentative ones yellow, missed ones (within grace) orange. With the AAM (§5.3), each
// face's fitted mesh over it: white when the fit holds, red when it failed (the face then keeps
// the 2D pose).
#include "render/overlay_layer.hpp"
#include "vision/face_fit.hpp"
#include "vision/face_tracker.hpp"

#include <array>
#include <memory>
#include <span>
#include <utility>
#include <vector>

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
    /// The fitted meshes' triangles (start-up: the edges are kept, the buffers sized for them).
    void setMeshTriangles(std::span<const std::array<int, 3>> triangles);
    /// Copies this frame's fits (FrameState::fits); fits not ok are drawn red, not fitted ones not.
    void updateFits(std::span<const vision::FaceFit> fits) noexcept;
    void setVisible(bool visible) noexcept { visible_ = visible; }
    bool visible() const noexcept { return visible_; }
    void draw(const LayerContext& context) noexcept override;

private:
    struct Gl;
    std::unique_ptr<Gl> gl_;
    bool visible_ = false;
};

}  // namespace render
