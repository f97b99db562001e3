#pragma once
// FaceOverlayLayer: the 3D hats and glasses of the overlay catalogue drawn on every shown face
// (§6), with a perspective camera matched to the video, ambient + directional lighting, and
// depth occlusion by the head.
//
// Each draw():
//  1. clears the depth buffer where overlays can land (the window rectangles of their projected
//     vertices; all of it when those are large) and draws, for every face that wears an overlay,
//     an invisible head proxy (HeadModel's rounded box-like ellipsoid, its front half) into the
//     depth buffer only (colour writes off, scissored to those rectangles), so the parts of an
//     overlay behind the head (temple arms, the back of a brim) fail the depth test;
//  2. draws the opaque meshes of every face, lit per vertex (Gouraud: the meshes are dense
//     enough; an untextured mesh gets its whole colour per vertex, so software GL's fragments
//     only copy it) by an ambient and one directional light whose strength follows the face's
//     brightness; closed meshes with their back faces culled (see OverlayMaterial::doubleSided);
//     a face fading in or out (alpha < 1) is drawn in two passes (depth, then colour where the
//     depth is its own) so only its front surface is blended;
//  3. draws the transparent meshes (lenses) blended, depth-tested but not depth-writing, far faces
//     first.
// The camera is a pinhole with the video's image size and a configurable vertical field of view;
// a face's HeadPose (vision/head_pose.hpp) places the head in it. Camera pixels go to the screen
// through LayerContext::imageToNdc, so overlays are mirrored (and cropped) exactly as the video.
// Lighting is computed in the camera frame, so a mirrored head is lit like its mirror image.
//
// The bound framebuffer needs a depth buffer (the headless display's FBO and the window EGL config
// have one); without it nothing is hidden. GL objects are made in the constructor (a current
// GLES2 context is needed); draw() and setFaces() never allocate and never throw.

#include "render/head_model.hpp"
#include "render/overlay_catalogue.hpp"
#include "render/overlay_layer.hpp"
#include "vision/face_fit.hpp"
#include "vision/face_tracker.hpp"
#include "vision/head_pose.hpp"

#include <array>
#include <memory>
#include <span>

namespace render {

struct FaceOverlayOptions {
    float verticalFovDegrees = 50.f;  ///< the camera's, for the perspective of the overlays
    HeadModel head{};
    float ambient = 0.45f;  ///< light from everywhere, times the face's brightness
    float diffuse = 0.7f;   ///< the directional light at brightness 1
    float specular = 0.4f;  ///< highlight strength for shiny materials
    /// Towards the light, camera frame (x right, y down, z forward): above, left, in front.
    std::array<float, 3> lightDirection{-0.35f, -0.6f, -0.7f};
    bool headProxy = true;  ///< false draws no head proxy: nothing is hidden by the head
    float nearMetres = 0.05f;
    float farMetres = 20.f;
};

/// One face to draw this frame and what it wears. Who wears what, and its fade, belong to the
/// caller (the firmware's OverlaySelection): the layer keeps nothing of a face between frames.
struct FaceDrawing {
    vision::TrackedFace face;  ///< camera image coordinates; only a shown() face is drawn
    int overlay = -1;          ///< an index of the catalogue; -1 draws nothing
    float alpha = 1.f;         ///< opacity 0..1, for fading in and out
    float brightness = 1.f;    ///< light relative to normal (1; 0.5 darker; > 1 brighter)
    /// With hasPose, `pose` places the head (a full 6-DoF pose); without it the pose comes from
    /// the face box (vision::headPoseFromFace: yaw and pitch zero).
    bool hasPose = false;
    vision::HeadPose pose{};
    /// With hasPose, the fitted face's animation values (vision::FaceFit::animation): overlays
    /// that follow them (OverlayFollow) change with the face.
    std::array<float, vision::kAamAnimationUnits> animation{};
};

class FaceOverlayLayer final : public OverlayLayer {
public:
    static constexpr int kMaxFaces = 16;

    /// Uploads every mesh and texture of `catalogue` (not kept) and builds the shaders. Throws
    /// std::runtime_error with one line on a GL failure or bad options.
    FaceOverlayLayer(const OverlayCatalogue& catalogue, const FaceOverlayOptions& options = {});
    ~FaceOverlayLayer() override;
    FaceOverlayLayer(const FaceOverlayLayer&) = delete;
    FaceOverlayLayer& operator=(const FaceOverlayLayer&) = delete;

    const char* name() const noexcept override { return "face-overlays"; }
    void draw(const LayerContext& context) noexcept override;

    /// This frame's faces, at most kMaxFaces (the rest are not drawn), kept until the next
    /// call. False when an overlay index is outside the catalogue (that face wears nothing).
    bool setFaces(std::span<const FaceDrawing> faces) noexcept;

    /// Changes the options for the next draws (head.proxySquareness excepted: the proxy mesh is
    /// made by the constructor).
    void setOptions(const FaceOverlayOptions& options) noexcept { options_ = options; }
    const FaceOverlayOptions& options() const noexcept { return options_; }
    int overlayCount() const noexcept;
    /// What went wrong in the last draw() ("" when nothing), e.g. no depth buffer.
    const char* lastError() const noexcept { return lastError_; }

private:
    struct Gl;  // GL objects; defined in the source so this header needs no GL header

    std::unique_ptr<Gl> gl_;
    FaceOverlayOptions options_;
    std::array<FaceDrawing, kMaxFaces> faces_{};
    int faceCount_ = 0;
    char lastError_[128] = "";
};

}  // namespace render
