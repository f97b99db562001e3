#include "render/face_overlay_layer.hpp"

#include "gl_program.hpp"

#include <GLES2/gl2.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace render {
namespace {

// Lighting per vertex (Gouraud): the meshes are dense enough that it looks the same as per
// fragment, and llvmpipe spends its time on fragments (hats cover much of the screen).
constexpr const char* kShadeVertexShader = R"(#version 100
attribute vec3 aPosition;  // model axes and units
attribute vec3 aNormal;
attribute vec2 aUv;
uniform mat4 uModelView;   // model -> camera frame (metres, x right, y down, z forward)
uniform mat4 uProjection;  // camera frame -> clip, mirrored and cropped as the video
uniform mat3 uNormalMatrix;
uniform vec3 uLightDirection;  // towards the light, camera frame, unit
uniform vec3 uLight;           // ambient, diffuse, specular, already times the face's brightness
uniform float uShininess;      // 0: matt
varying vec3 vDiffuse;   // multiplies the material colour
varying vec3 vSpecular;  // added
varying vec2 vUv;
void main()
{
    vec4 p = uModelView * vec4(aPosition, 1.0);
    vec3 n = normalize(uNormalMatrix * aNormal);
    vec3 view = normalize(-p.xyz);
    // Two-sided: the side of the surface the camera sees.
    if (dot(n, view) < 0.0)
        n = -n;
    vDiffuse = vec3(uLight.x + uLight.y * max(dot(n, uLightDirection), 0.0));
    vSpecular = vec3(0.0);
    if (uShininess > 0.0) {
        vec3 h = normalize(uLightDirection + view);
        vSpecular = vec3(uLight.z * pow(max(dot(n, h), 0.0), uShininess));
    }
    vUv = aUv;
    gl_Position = uProjection * p;
}
)";

constexpr const char* kShadeFragmentShader = R"(#version 100
precision mediump float;
uniform vec4 uColor;
uniform sampler2D uTexture;
uniform float uUseTexture;
uniform float uAlpha;  // the face's fade
varying vec3 vDiffuse;
varying vec3 vSpecular;
varying vec2 vUv;
void main()
{
    vec4 base = uColor;
    if (uUseTexture > 0.5)
        base *= texture2D(uTexture, vUv);
    gl_FragColor = vec4(min(base.rgb * vDiffuse + vSpecular, vec3(1.0)), base.a * uAlpha);
}
)";

constexpr const char* kDepthVertexShader = R"(#version 100
attribute vec3 aPosition;
uniform mat4 uModelViewProjection;
void main()
{
    gl_Position = uModelViewProjection * vec4(aPosition, 1.0);
}
)";

constexpr const char* kDepthFragmentShader = R"(#version 100
precision mediump float;
void main()
{
    gl_FragColor = vec4(0.0);
}
)";

constexpr float kDegrees = 3.14159265358979f / 180.f;
// 256 triangles: llvmpipe's cost is per triangle, and the silhouette stays within 2 % of the
// head's radius (1 - cos 11.25 degrees).
constexpr int kProxySegments = 16;  // around the vertical axis
constexpr int kProxyRings = 8;      // pole to pole

// The head frame of vision/head_pose.hpp (y down, z into the head) from the model axes of the
// catalogue (y up, z towards the camera): a half turn about x.
const Eigen::Matrix3f kModelToHeadAxes = Eigen::Vector3f(1.f, -1.f, -1.f).asDiagonal();

Eigen::Vector3f toVector(const std::array<float, 3>& a)
{
    return {a[0], a[1], a[2]};
}

// The head proxy of unit semi-axes as a triangle list (positions only): a sphere whose
// horizontal sections are superellipses of exponent `n` (HeadModel::proxySquareness).
std::vector<float> unitProxy(float n)
{
    std::vector<float> out;
    auto superPower = [n](float c) { return std::copysign(std::pow(std::fabs(c), 2.f / n), c); };
    auto point = [&](int ring, int segment, std::vector<float>& to) {
        const float theta = static_cast<float>(ring) * 180.f / kProxyRings * kDegrees;
        const float phi = static_cast<float>(segment) * 360.f / kProxySegments * kDegrees;
        to.push_back(std::sin(theta) * superPower(std::cos(phi)));
        to.push_back(std::cos(theta));
        to.push_back(std::sin(theta) * superPower(std::sin(phi)));
    };
    for (int r = 0; r < kProxyRings; ++r)
        for (int s = 0; s < kProxySegments; ++s) {
            point(r, s, out);
            point(r + 1, s, out);
            point(r + 1, s + 1, out);
            point(r, s, out);
            point(r + 1, s + 1, out);
            point(r, s + 1, out);
        }
    return out;
}

struct Affine {
    Eigen::Matrix3f linear;
    Eigen::Vector3f translation;
};

// Model units -> head frame metres for one overlay (FORMAT.md: rotate x, y, z, add the offset,
// scale by scale * measure, put at the anchor).
Affine modelToHead(const Overlay& overlay, const HeadModel& head)
{
    const float w = head.faceWidthMetres;
    const float measure =
        overlay.measure == HeadMeasure::Interocular ? w * head.interocularPerFaceWidth : w;
    const float s = overlay.scale * measure;
    const Eigen::Matrix3f rotation =
        (Eigen::AngleAxisf(overlay.rotationDegrees[2] * kDegrees, Eigen::Vector3f::UnitZ()) *
         Eigen::AngleAxisf(overlay.rotationDegrees[1] * kDegrees, Eigen::Vector3f::UnitY()) *
         Eigen::AngleAxisf(overlay.rotationDegrees[0] * kDegrees, Eigen::Vector3f::UnitX()))
            .toRotationMatrix();
    const std::array<float, 3>* anchor = &head.eyeMidpoint;
    switch (overlay.anchor) {
        case OverlayAnchor::EyeMidpoint:
            anchor = &head.eyeMidpoint;
            break;
        case OverlayAnchor::NoseBridge:
            anchor = &head.noseBridge;
            break;
        case OverlayAnchor::ForeheadTop:
            anchor = &head.foreheadTop;
            break;
        case OverlayAnchor::HeadTop:
            anchor = &head.headTop;
            break;
    }
    return {s * kModelToHeadAxes * rotation,
            kModelToHeadAxes * (toVector(*anchor) * w + s * toVector(overlay.offset))};
}

}  // namespace

struct FaceOverlayLayer::Gl {
    struct Mesh {
        std::unique_ptr<detail::GlBuffer> vertices;
        std::unique_ptr<detail::GlBuffer> indices;
        GLsizei count = 0;  // indices
        OverlayMaterial material;
        std::unique_ptr<detail::GlTexture> texture;  // null: none
    };
    struct Part {           // an overlay: its meshes and placement
        Overlay placement;  // meshes left empty: only the placement fields are used
        std::vector<Mesh> meshes;
    };

    detail::GlProgram shade{
        "overlay", kShadeVertexShader, kShadeFragmentShader, {"aPosition", "aNormal", "aUv"}};
    GLint modelView = shade.uniform("uModelView");
    GLint projection = shade.uniform("uProjection");
    GLint normalMatrix = shade.uniform("uNormalMatrix");
    GLint color = shade.uniform("uColor");
    GLint textureUnit = shade.uniform("uTexture");
    GLint useTexture = shade.uniform("uUseTexture");
    GLint lightDirection = shade.uniform("uLightDirection");
    GLint light = shade.uniform("uLight");
    GLint shininess = shade.uniform("uShininess");
    GLint alpha = shade.uniform("uAlpha");

    detail::GlProgram depth{"head proxy", kDepthVertexShader, kDepthFragmentShader, {"aPosition"}};
    GLint modelViewProjection = depth.uniform("uModelViewProjection");
    detail::GlBuffer proxy;
    GLsizei proxyCount = 0;

    std::vector<Part> overlays;
};

FaceOverlayLayer::FaceOverlayLayer(const OverlayCatalogue& catalogue,
                                   const FaceOverlayOptions& options)
    : gl_(std::make_unique<Gl>()), options_(options)
{
    if (!(options.verticalFovDegrees > 1.f && options.verticalFovDegrees < 179.f) ||
        !(options.nearMetres > 0.f && options.farMetres > options.nearMetres))
        throw std::runtime_error(
            "FaceOverlayLayer: bad options (field of view 1..179 degrees, "
            "0 < near < far)");
    gl_->overlays.reserve(catalogue.overlays().size());
    for (const Overlay& overlay : catalogue.overlays()) {
        Gl::Part part;
        part.placement.name = overlay.name;
        part.placement.kind = overlay.kind;
        part.placement.anchor = overlay.anchor;
        part.placement.measure = overlay.measure;
        part.placement.scale = overlay.scale;
        part.placement.offset = overlay.offset;
        part.placement.rotationDegrees = overlay.rotationDegrees;
        for (const OverlayMesh& mesh : overlay.meshes) {
            Gl::Mesh m;
            m.vertices = std::make_unique<detail::GlBuffer>();
            m.indices = std::make_unique<detail::GlBuffer>();
            m.count = static_cast<GLsizei>(mesh.indices.size());
            m.material = mesh.material;
            glBindBuffer(GL_ARRAY_BUFFER, m.vertices->id());
            glBufferData(GL_ARRAY_BUFFER,
                         static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(OverlayVertex)),
                         mesh.vertices.data(), GL_STATIC_DRAW);
            glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.indices->id());
            glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                         static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint16_t)),
                         mesh.indices.data(), GL_STATIC_DRAW);
            if (!mesh.texture.empty()) {
                m.texture = std::make_unique<detail::GlTexture>();
                glBindTexture(GL_TEXTURE_2D, m.texture->id());
                glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
                glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, mesh.texture.width, mesh.texture.height, 0,
                             GL_RGBA, GL_UNSIGNED_BYTE, mesh.texture.rgba.data());
                // Any size (GLES2 allows no mipmaps or repeat for non-power-of-two pictures).
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
                glBindTexture(GL_TEXTURE_2D, 0);
            }
            part.meshes.push_back(std::move(m));
        }
        gl_->overlays.push_back(std::move(part));
    }
    if (!(options.head.proxySquareness >= 1.f && options.head.proxySquareness <= 10.f))
        throw std::runtime_error("FaceOverlayLayer: head proxy squareness must be in [1, 10]");
    const std::vector<float> sphere = unitProxy(options.head.proxySquareness);
    gl_->proxyCount = static_cast<GLsizei>(sphere.size() / 3);
    glBindBuffer(GL_ARRAY_BUFFER, gl_->proxy.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(sphere.size() * sizeof(float)),
                 sphere.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        char code[16];
        std::snprintf(code, sizeof(code), "0x%04x", error);
        throw std::runtime_error(std::string("FaceOverlayLayer: GL error ") + code +
                                 " while uploading the overlay meshes of " + catalogue.path());
    }
}

FaceOverlayLayer::~FaceOverlayLayer() = default;

int FaceOverlayLayer::overlayCount() const noexcept
{
    return static_cast<int>(gl_->overlays.size());
}

void FaceOverlayLayer::setFaces(std::span<const vision::TrackedFace> faces) noexcept
{
    faceCount_ = 0;
    for (const vision::TrackedFace& face : faces) {
        if (faceCount_ == kMaxFaces)
            break;
        Face& f = faces_[static_cast<std::size_t>(faceCount_++)];
        f.face = face;
        f.face.points = nullptr;  // not ours to keep
        f.face.pointCount = 0;
        f.hasPose = false;
    }
}

bool FaceOverlayLayer::setPose(int faceId, const vision::HeadPose& pose) noexcept
{
    for (int i = 0; i < faceCount_; ++i) {
        Face& f = faces_[static_cast<std::size_t>(i)];
        if (f.face.id == faceId) {
            f.pose = pose;
            f.hasPose = true;
            return true;
        }
    }
    return false;
}

bool FaceOverlayLayer::present(int faceId) const noexcept
{
    for (int i = 0; i < faceCount_; ++i)
        if (faces_[static_cast<std::size_t>(i)].face.id == faceId)
            return true;
    return false;
}

FaceOverlayLayer::Selection* FaceOverlayLayer::selection(int faceId) noexcept
{
    Selection* free = nullptr;
    for (Selection& s : selections_) {
        if (s.faceId == faceId)
            return &s;
        if (free == nullptr && s.faceId == 0)
            free = &s;
    }
    if (free == nullptr)  // full: reuse the slot of a face that is gone
        for (Selection& s : selections_)
            if (!present(s.faceId)) {
                free = &s;
                break;
            }
    if (free != nullptr)
        *free = Selection{faceId, -1, 1.f, 1.f};
    return free;
}

bool FaceOverlayLayer::setOverlay(int faceId, int overlayIndex, float alpha) noexcept
{
    if (faceId == 0 || overlayIndex < -1 || overlayIndex >= overlayCount())
        return false;
    Selection* s = selection(faceId);
    if (s == nullptr)
        return false;
    s->overlay = overlayIndex;
    s->alpha = alpha < 0.f ? 0.f : (alpha > 1.f ? 1.f : alpha);
    return true;
}

bool FaceOverlayLayer::setBrightness(int faceId, float brightness) noexcept
{
    if (faceId == 0)
        return false;
    Selection* s = selection(faceId);
    if (s == nullptr)
        return false;
    s->brightness = brightness > 0.f ? brightness : 0.f;
    return true;
}

void FaceOverlayLayer::clearSelection() noexcept
{
    selections_.fill(Selection{});
}

void FaceOverlayLayer::draw(const LayerContext& context) noexcept
{
    lastError_[0] = '\0';
    if (context.image.width <= 0 || context.image.height <= 0)
        return;

    // The faces to draw, with their poses, far first.
    struct Drawn {
        vision::HeadPose pose;
        const Selection* selection;
    };
    std::array<Drawn, kMaxFaces> drawn;
    int count = 0;
    const vision::CameraModel camera{context.image, options_.verticalFovDegrees};
    for (int i = 0; i < faceCount_; ++i) {
        const Face& f = faces_[static_cast<std::size_t>(i)];
        if (!f.face.shown())
            continue;
        const Selection* s = nullptr;
        for (const Selection& candidate : selections_)
            if (candidate.faceId == f.face.id)
                s = &candidate;
        if (s == nullptr || s->overlay < 0 || s->overlay >= overlayCount() || s->alpha <= 0.f)
            continue;
        const vision::HeadPose pose =
            f.hasPose ? f.pose
                      : vision::headPoseFromFace(f.face, camera, options_.head.faceWidthMetres);
        if (!(pose.translation.z() > options_.nearMetres))
            continue;  // behind the camera or too near: nothing sensible to draw
        int at = count++;
        while (at > 0 && drawn[static_cast<std::size_t>(at - 1)].pose.translation.z() <
                             pose.translation.z()) {
            drawn[static_cast<std::size_t>(at)] = drawn[static_cast<std::size_t>(at - 1)];
            --at;
        }
        drawn[static_cast<std::size_t>(at)] = {pose, s};
    }
    if (count == 0)
        return;

    GLint depthBits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depthBits);
    if (depthBits == 0)
        std::snprintf(lastError_, sizeof(lastError_),
                      "the framebuffer has no depth buffer: heads hide nothing");

    // Camera frame -> clip: the pinhole projection to camera pixels, then the layer context's
    // pixel -> NDC map (which mirrors and crops like the video); w = Z, depth from near to far.
    const float f = camera.focalPixels();
    const float cx = 0.5f * static_cast<float>(context.image.width) + 0.5f;  // +0.5: pixel edges
    const float cy = 0.5f * static_cast<float>(context.image.height) + 0.5f;
    const float* m = context.imageToNdc;
    const float n = options_.nearMetres;
    const float fa = options_.farMetres;
    Eigen::Matrix4f projection;
    projection << m[0] * f, 0.f, m[0] * cx + m[1], 0.f,           //
        0.f, m[2] * f, m[2] * cy + m[3], 0.f,                     //
        0.f, 0.f, (fa + n) / (fa - n), -2.f * fa * n / (fa - n),  //
        0.f, 0.f, 1.f, 0.f;

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    // Single-sided meshes are counter-clockwise seen from outside, so their front faces turn
    // counter-clockwise in the camera image as a viewer sees it. Image to NDC keeps that (y down
    // to y up is no flip: c < 0) unless it mirrors (a < 0): then they turn clockwise.
    glCullFace(GL_BACK);
    glFrontFace(m[0] * m[2] < 0.f ? GL_CCW : GL_CW);
    glClearDepthf(1.f);
    glClear(GL_DEPTH_BUFFER_BIT);

    const HeadModel& head = options_.head;
    const float w = head.faceWidthMetres;

    // 1. Head proxies, depth only.
    if (options_.headProxy) {
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glUseProgram(gl_->depth.id());
        glBindBuffer(GL_ARRAY_BUFFER, gl_->proxy.id());
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
        glEnableVertexAttribArray(0);
        const Eigen::Matrix3f axes =
            kModelToHeadAxes * (toVector(head.proxySemiAxes) * w).asDiagonal();
        const Eigen::Vector3f centre = kModelToHeadAxes * toVector(head.proxyCentre) * w;
        for (int i = 0; i < count; ++i) {
            const vision::HeadPose& pose = drawn[static_cast<std::size_t>(i)].pose;
            Eigen::Matrix4f modelView = Eigen::Matrix4f::Identity();
            modelView.topLeftCorner<3, 3>() = pose.rotation * axes;
            modelView.topRightCorner<3, 1>() = pose.rotation * centre + pose.translation;
            const Eigen::Matrix4f mvp = projection * modelView;
            glUniformMatrix4fv(gl_->modelViewProjection, 1, GL_FALSE, mvp.data());
            glDrawArrays(GL_TRIANGLES, 0, gl_->proxyCount);
        }
        glDisableVertexAttribArray(0);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }

    // 2 and 3. The overlays: opaque meshes, then transparent ones.
    glUseProgram(gl_->shade.id());
    glUniformMatrix4fv(gl_->projection, 1, GL_FALSE, projection.data());
    glUniform1i(gl_->textureUnit, 0);
    Eigen::Vector3f toLight = toVector(options_.lightDirection);
    toLight = toLight.norm() > 0.f ? toLight.normalized() : Eigen::Vector3f(0.f, 0.f, -1.f);
    glUniform3f(gl_->lightDirection, toLight.x(), toLight.y(), toLight.z());
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glEnableVertexAttribArray(2);
    glActiveTexture(GL_TEXTURE0);

    auto drawMeshes = [&](const Drawn& face, bool transparent) {
        const Gl::Part& part = gl_->overlays[static_cast<std::size_t>(face.selection->overlay)];
        const Affine model = modelToHead(part.placement, head);
        Eigen::Matrix4f modelView = Eigen::Matrix4f::Identity();
        modelView.topLeftCorner<3, 3>() = face.pose.rotation * model.linear;
        modelView.topRightCorner<3, 1>() =
            face.pose.rotation * model.translation + face.pose.translation;
        // Rotation part only: the scale is uniform and the shader normalises.
        const Eigen::Matrix3f normals = face.pose.rotation * model.linear;
        glUniformMatrix4fv(gl_->modelView, 1, GL_FALSE, modelView.data());
        glUniformMatrix3fv(gl_->normalMatrix, 1, GL_FALSE, normals.data());
        const float b = face.selection->brightness;
        glUniform3f(gl_->light, options_.ambient * b, options_.diffuse * b, options_.specular * b);
        glUniform1f(gl_->alpha, face.selection->alpha);
        for (const Gl::Mesh& mesh : part.meshes) {
            if (mesh.material.transparent() != transparent)
                continue;
            if (mesh.material.doubleSided)
                glDisable(GL_CULL_FACE);
            else
                glEnable(GL_CULL_FACE);
            const auto& c = mesh.material.color;
            glUniform4f(gl_->color, c[0], c[1], c[2], c[3]);
            glUniform1f(gl_->shininess, mesh.material.shininess);
            glUniform1f(gl_->useTexture, mesh.texture ? 1.f : 0.f);
            glBindTexture(GL_TEXTURE_2D, mesh.texture ? mesh.texture->id() : 0);
            glBindBuffer(GL_ARRAY_BUFFER, mesh.vertices->id());
            const auto stride = static_cast<GLsizei>(sizeof(OverlayVertex));
            glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
            glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                                  reinterpret_cast<const void*>(3 * sizeof(float)));
            glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride,
                                  reinterpret_cast<const void*>(6 * sizeof(float)));
            glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indices->id());
            glDrawElements(GL_TRIANGLES, mesh.count, GL_UNSIGNED_SHORT, nullptr);
        }
    };

    for (int i = 0; i < count; ++i) {
        const Drawn& face = drawn[static_cast<std::size_t>(i)];
        if (face.selection->alpha < 1.f) {
            // Fading: lay down its depth first so only its front surface is blended.
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            drawMeshes(face, false);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDepthMask(GL_FALSE);
            drawMeshes(face, false);
            glDepthMask(GL_TRUE);
        } else {
            drawMeshes(face, false);
        }
    }
    glDepthMask(GL_FALSE);
    for (int i = 0; i < count; ++i)
        drawMeshes(drawn[static_cast<std::size_t>(i)], true);

    // Back to the state the renderer promises the next layer.
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    glDisableVertexAttribArray(0);
    glDisableVertexAttribArray(1);
    glDisableVertexAttribArray(2);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    glUseProgram(0);
}

}  // namespace render
