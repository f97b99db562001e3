#include "render/face_overlay_layer.hpp"

#include "face_overlay_shaders.hpp"
#include "gl_program.hpp"
#include "overlay_placement.hpp"
#include "window_bounds.hpp"

#include <GLES2/gl2.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace render {

using detail::Affine;
using detail::PixelRect;
using detail::toVector;

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
        std::vector<Eigen::Vector3f> points;  // every distinct vertex position, model units
    };
    struct Shade {  // one of the two overlay programs and its uniforms
        explicit Shade(bool textured)
            : program(textured ? "textured overlay" : "overlay",
                      detail::shaderSource(textured, detail::kShadeVertexShader).c_str(),
                      detail::shaderSource(textured, detail::kShadeFragmentShader).c_str(),
                      {"aPosition", "aNormal", "aUv"}),
              textureUnit(textured ? program.uniform("uTexture") : -1)
        {
        }
        detail::GlProgram program;
        GLint modelView = program.uniform("uModelView");
        GLint projection = program.uniform("uProjection");
        GLint normalMatrix = program.uniform("uNormalMatrix");
        GLint color = program.uniform("uColor");
        GLint lightDirection = program.uniform("uLightDirection");
        GLint light = program.uniform("uLight");
        GLint shininess = program.uniform("uShininess");
        GLint textureUnit;
        int faceUniformsOf = -1;  // the draw pass whose face uniforms it has (-1: none yet)
    };

    Shade lit{false};
    Shade textured{true};

    detail::GlProgram depth{
        "head proxy", detail::kDepthVertexShader, detail::kDepthFragmentShader, {"aPosition"}};
    GLint modelViewProjection = depth.uniform("uModelViewProjection");
    detail::GlBuffer proxy;
    detail::GlBuffer proxyIndices;
    GLsizei proxyCount = 0;                    // indices
    std::vector<Eigen::Vector3f> proxyPoints;  // distinct, unit semi-axes

    std::vector<Part> overlays;
    bool variantsPrepared = false;

    // llvmpipe compiles a shader variant (heap, LLVM, milliseconds) the first time a program is
    // drawn in a new GL state, and Mesa makes its scissored clear's shaders on first use. This
    // makes all of them on the first frame with overlays (with the framebuffer they are drawn
    // into, and rasterising nothing), so that no later frame does: not when a fade ends, lenses
    // first appear or a face comes near.
    void prepareShaderVariants(const PixelRect& viewport) noexcept
    {
        if (variantsPrepared)
            return;
        variantsPrepared = true;
        glEnable(GL_SCISSOR_TEST);
        glScissor(viewport.x0, viewport.y0, 1, 1);
        glClear(GL_DEPTH_BUFFER_BIT);  // a corner's depth, cleared again before it is used
        glScissor(viewport.x0 - 2, viewport.y0 - 2, 1, 1);  // outside: nothing is drawn

        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // the head proxies' state
        glUseProgram(depth.id());
        glBindBuffer(GL_ARRAY_BUFFER, proxy.id());
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, proxyIndices.id());
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
        glEnableVertexAttribArray(0);
        glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_SHORT, nullptr);

        glEnableVertexAttribArray(1);
        for (const bool withTexture : {false, true}) {
            const Mesh* mesh = nullptr;
            for (const Part& part : overlays)
                for (const Mesh& m : part.meshes)
                    if (mesh == nullptr && (m.texture != nullptr) == withTexture && m.count >= 3)
                        mesh = &m;
            if (mesh == nullptr)
                continue;
            glUseProgram((withTexture ? textured : lit).program.id());
            bindMesh(*mesh);
            // Opaque; a fading face's depth pass; its colour pass and lenses.
            glDisable(GL_BLEND);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_SHORT, nullptr);
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_SHORT, nullptr);
            glEnable(GL_BLEND);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDepthMask(GL_FALSE);
            glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_SHORT, nullptr);
            glDepthMask(GL_TRUE);
        }
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDisableVertexAttribArray(1);
        glDisableVertexAttribArray(2);
        glDisable(GL_SCISSOR_TEST);
    }

    // Binds a mesh's buffers, attributes (the texture coordinates only for a textured mesh)
    // and texture.
    static void bindMesh(const Mesh& mesh) noexcept
    {
        glBindBuffer(GL_ARRAY_BUFFER, mesh.vertices->id());
        const auto stride = static_cast<GLsizei>(sizeof(OverlayVertex));
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                              reinterpret_cast<const void*>(3 * sizeof(float)));
        if (mesh.texture) {
            glEnableVertexAttribArray(2);
            glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride,
                                  reinterpret_cast<const void*>(6 * sizeof(float)));
            glBindTexture(GL_TEXTURE_2D, mesh.texture->id());
        }
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indices->id());
    }
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
        part.placement.follows = overlay.follows;
        std::vector<std::array<float, 3>> positions;
        for (const OverlayMesh& mesh : overlay.meshes)
            for (const OverlayVertex& v : mesh.vertices)
                positions.push_back({v.position[0], v.position[1], v.position[2]});
        part.points = detail::distinctPoints(std::move(positions));
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
    const HeadProxyMesh proxy = unitHeadProxy(options.head.proxySquareness);
    const std::vector<std::array<float, 3>>& distinct = proxy.points;
    const std::vector<std::uint16_t>& indices = proxy.indices;
    gl_->proxyCount = static_cast<GLsizei>(indices.size());
    for (const auto& p : distinct)
        gl_->proxyPoints.emplace_back(p[0], p[1], p[2]);
    glBindBuffer(GL_ARRAY_BUFFER, gl_->proxy.id());
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(distinct.size() * sizeof(std::array<float, 3>)),
                 distinct.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gl_->proxyIndices.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint16_t)), indices.data(),
                 GL_STATIC_DRAW);
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

bool FaceOverlayLayer::setFaces(std::span<const FaceDrawing> faces) noexcept
{
    bool known = true;
    faceCount_ = 0;
    for (const FaceDrawing& face : faces) {
        if (faceCount_ == kMaxFaces)
            break;
        FaceDrawing& f = faces_[static_cast<std::size_t>(faceCount_++)];
        f = face;
        f.face.points = nullptr;  // not ours to keep
        f.face.pointCount = 0;
        f.alpha = std::clamp(f.alpha, 0.f, 1.f);
        f.brightness = std::max(f.brightness, 0.f);
        if (f.overlay < -1 || f.overlay >= overlayCount()) {
            f.overlay = -1;
            known = false;
        }
    }
    return known;
}

void FaceOverlayLayer::draw(const LayerContext& context) noexcept
{
    lastError_[0] = '\0';
    if (context.image.width <= 0 || context.image.height <= 0)
        return;

    // The faces to draw, with their poses, far first.
    struct Drawn {
        vision::HeadPose pose;
        const FaceDrawing* drawing;
        Eigen::Matrix4f modelView;       // the overlay's model -> camera frame
        Eigen::Matrix4f proxyModelView;  // the unit head proxy's
        PixelRect overlayPixels;         // what the overlay can cover
        PixelRect proxyPixels;           // what its head proxy has to cover
    };
    std::array<Drawn, kMaxFaces> drawn{};
    int count = 0;
    const vision::CameraModel camera{context.image, options_.verticalFovDegrees};
    for (int i = 0; i < faceCount_; ++i) {
        const FaceDrawing& f = faces_[static_cast<std::size_t>(i)];
        if (!f.face.shown() || f.overlay < 0 || f.alpha <= 0.f)
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
        drawn[static_cast<std::size_t>(at)].pose = pose;
        drawn[static_cast<std::size_t>(at)].drawing = &f;
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

    // Where each face's overlay and head proxy go, in window pixels.
    const HeadModel& head = options_.head;
    const float w = head.faceWidthMetres;
    const Eigen::Matrix3f proxyAxes =
        modelToHeadAxes() * (toVector(head.proxySemiAxes) * w).asDiagonal();
    const Eigen::Vector3f proxyCentre = modelToHeadAxes() * toVector(head.proxyCentre) * w;
    GLint v[4] = {0, 0, 0, 0};  // what window pixels the NDC map to (the renderer's glViewport)
    glGetIntegerv(GL_VIEWPORT, v);
    const PixelRect viewport{v[0], v[1], v[0] + v[2], v[1] + v[3]};
    long overlayArea = 0;
    for (int i = 0; i < count; ++i) {
        Drawn& face = drawn[static_cast<std::size_t>(i)];
        const Gl::Part& part = gl_->overlays[static_cast<std::size_t>(face.drawing->overlay)];
        const Affine model = detail::modelToHead(
            part.placement, head, face.drawing->hasPose ? &face.drawing->animation : nullptr);
        face.modelView.setIdentity();
        face.modelView.topLeftCorner<3, 3>() = face.pose.rotation * model.linear;
        face.modelView.topRightCorner<3, 1>() =
            face.pose.rotation * model.translation + face.pose.translation;
        face.proxyModelView.setIdentity();
        face.proxyModelView.topLeftCorner<3, 3>() = face.pose.rotation * proxyAxes;
        face.proxyModelView.topRightCorner<3, 1>() =
            face.pose.rotation * proxyCentre + face.pose.translation;
        face.overlayPixels =
            detail::windowBounds(projection * face.modelView, part.points, viewport);
        face.proxyPixels =
            detail::windowBounds(projection * face.proxyModelView, gl_->proxyPoints, viewport);
        overlayArea += face.overlayPixels.area();
    }

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
    gl_->prepareShaderVariants(viewport);  // the first time only
    // Only the depth under the overlays matters: nothing else is depth-tested. llvmpipe clears a
    // scissored rectangle by drawing it, ~6 times its whole-buffer clear's cost per pixel (and
    // that alone is ~0.35 ms at 720p), so the rectangles are cleared while they are small and
    // the whole buffer otherwise.
    if (overlayArea * 6 < viewport.area()) {
        glEnable(GL_SCISSOR_TEST);
        for (int i = 0; i < count; ++i) {
            drawn[static_cast<std::size_t>(i)].overlayPixels.scissor();
            glClear(GL_DEPTH_BUFFER_BIT);
        }
    } else {
        glDisable(GL_SCISSOR_TEST);
        glClear(GL_DEPTH_BUFFER_BIT);
    }

    // 1. Head proxies, depth only, each where overlays can be (outside, the depth is stale and
    //    no fragment is tested against it).
    if (options_.headProxy) {
        glEnable(GL_SCISSOR_TEST);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_CULL_FACE);
        glUseProgram(gl_->depth.id());
        glBindBuffer(GL_ARRAY_BUFFER, gl_->proxy.id());
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gl_->proxyIndices.id());
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
        glEnableVertexAttribArray(0);
        for (int i = 0; i < count; ++i) {
            const Drawn& face = drawn[static_cast<std::size_t>(i)];
            // Where overlays (its own and the others') can be behind it.
            PixelRect where;
            bool any = false;
            for (int j = 0; j < count; ++j) {
                const PixelRect& overlay = drawn[static_cast<std::size_t>(j)].overlayPixels;
                if (!overlay.intersects(face.proxyPixels))
                    continue;
                const PixelRect part = overlay.intersection(face.proxyPixels);
                where = any ? where.hull(part) : part;
                any = true;
            }
            if (!any)
                continue;
            where.scissor();
            const Eigen::Matrix4f mvp = projection * face.proxyModelView;
            glUniformMatrix4fv(gl_->modelViewProjection, 1, GL_FALSE, mvp.data());
            glDrawElements(GL_TRIANGLES, gl_->proxyCount, GL_UNSIGNED_SHORT, nullptr);
        }
        glDisableVertexAttribArray(0);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }
    glDisable(GL_SCISSOR_TEST);

    // 2 and 3. The overlays: opaque meshes, then transparent ones.
    Eigen::Vector3f toLight = toVector(options_.lightDirection);
    toLight = toLight.norm() > 0.f ? toLight.normalized() : Eigen::Vector3f(0.f, 0.f, -1.f);
    for (Gl::Shade* shade : {&gl_->textured, &gl_->lit}) {  // ends with the usual one in use
        glUseProgram(shade->program.id());
        glUniformMatrix4fv(shade->projection, 1, GL_FALSE, projection.data());
        glUniform3f(shade->lightDirection, toLight.x(), toLight.y(), toLight.z());
        if (shade->textureUnit >= 0)
            glUniform1i(shade->textureUnit, 0);
        shade->faceUniformsOf = -1;
    }
    const Gl::Shade* inUse = &gl_->lit;
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glActiveTexture(GL_TEXTURE0);

    // One pass draws the opaque or the transparent meshes of one face.
    int pass = 0;
    auto drawMeshes = [&](const Drawn& face, bool transparent) {
        const Gl::Part& part = gl_->overlays[static_cast<std::size_t>(face.drawing->overlay)];
        ++pass;
        const float b = face.drawing->brightness;
        const float fade = face.drawing->alpha;
        for (const Gl::Mesh& mesh : part.meshes) {
            if (mesh.material.transparent() != transparent)
                continue;
            Gl::Shade& shade = mesh.texture ? gl_->textured : gl_->lit;
            if (&shade != inUse) {
                glUseProgram(shade.program.id());
                if (!mesh.texture)
                    glDisableVertexAttribArray(2);
                inUse = &shade;
            }
            if (shade.faceUniformsOf != pass) {
                // Rotation part only: the scale is uniform and the shader normalises.
                const Eigen::Matrix3f normals = face.modelView.topLeftCorner<3, 3>();
                glUniformMatrix4fv(shade.modelView, 1, GL_FALSE, face.modelView.data());
                glUniformMatrix3fv(shade.normalMatrix, 1, GL_FALSE, normals.data());
                glUniform3f(shade.light, options_.ambient * b, options_.diffuse * b,
                            options_.specular * b);
                shade.faceUniformsOf = pass;
            }
            if (mesh.material.doubleSided)
                glDisable(GL_CULL_FACE);
            else
                glEnable(GL_CULL_FACE);
            const auto& c = mesh.material.color;
            glUniform4f(shade.color, c[0], c[1], c[2], c[3] * fade);
            glUniform1f(shade.shininess, mesh.material.shininess);
            Gl::bindMesh(mesh);
            glDrawElements(GL_TRIANGLES, mesh.count, GL_UNSIGNED_SHORT, nullptr);
        }
    };

    // Opaque surfaces replace the pixels: no blending (it reads every pixel), except in the
    // colour pass of a face fading in or out. (The states are Gl::prepareShaderVariants'.)
    glDisable(GL_BLEND);
    for (int i = 0; i < count; ++i) {
        const Drawn& face = drawn[static_cast<std::size_t>(i)];
        if (face.drawing->alpha < 1.f) {
            // Fading: lay down its depth first so only its front surface is blended.
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            drawMeshes(face, false);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glEnable(GL_BLEND);
            glDepthMask(GL_FALSE);
            drawMeshes(face, false);
            glDepthMask(GL_TRUE);
            glDisable(GL_BLEND);
        } else {
            drawMeshes(face, false);
        }
    }
    glEnable(GL_BLEND);
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
