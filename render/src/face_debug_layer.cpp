#include "render/face_debug_layer.hpp"

#include "gl_program.hpp"
#include "vision/geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace render {

namespace {

constexpr const char* kVertexShader = R"(#version 100
attribute vec2 aPosition;
void main()
{
    gl_Position = vec4(aPosition, 0.0, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 100
precision mediump float;
uniform vec4 uColor;
void main()
{
    gl_FragColor = uColor;
}
)";

constexpr float kShown[4] = {0.2f, 1.0f, 0.3f, 0.9f};
constexpr float kTentative[4] = {1.0f, 0.9f, 0.1f, 0.8f};
constexpr float kMissing[4] = {1.0f, 0.5f, 0.1f, 0.8f};
constexpr float kAxis[4] = {1.0f, 0.2f, 0.9f, 0.9f};
constexpr float kPoint[4] = {0.2f, 0.9f, 1.0f, 0.9f};
constexpr float kMeshFitted[4] = {1.0f, 1.0f, 1.0f, 0.7f};
constexpr float kMeshFailed[4] = {1.0f, 0.2f, 0.2f, 0.7f};

/// Each face: 4 box edges, the axis, and its points, 6 vertices (two triangles) each.
constexpr int kSegmentsPerFace = 5 + FaceDebugLayer::kMaxPointsPerFace;
constexpr int kVerticesPerFace = kSegmentsPerFace * 6;

struct Face {
    vision::TrackedFace face;
    std::array<vision::Point2f, FaceDebugLayer::kMaxPointsPerFace> points{};
};

}  // namespace

struct FaceDebugLayer::Gl {
    Gl() : program("face debug", kVertexShader, kFragmentShader, {"aPosition"})
    {
        color = program.uniform("uColor");
    }
    detail::GlProgram program;
    GLint color = -1;
    std::array<Face, kMaxFaces> faces{};
    int count = 0;
    std::array<float, kVerticesPerFace * 2> vertices{};
    std::vector<std::pair<int, int>> meshEdges;  ///< each edge of the fitted mesh once
    std::vector<float> meshVertices;             ///< 6 vertices per edge
    std::array<vision::FaceFit, kMaxFaces> fits{};
    int fitCount = 0;
};

FaceDebugLayer::FaceDebugLayer() : gl_(std::make_unique<Gl>()) {}
FaceDebugLayer::~FaceDebugLayer() = default;

void FaceDebugLayer::update(std::span<const vision::TrackedFace> faces) noexcept
{
    gl_->count = static_cast<int>(std::min<std::size_t>(faces.size(), kMaxFaces));
    for (int i = 0; i < gl_->count; ++i) {
        Face& f = gl_->faces[static_cast<std::size_t>(i)];
        f.face = faces[static_cast<std::size_t>(i)];
        const int n = std::clamp(f.face.pointCount, 0, kMaxPointsPerFace);
        for (int p = 0; p < n; ++p)
            f.points[static_cast<std::size_t>(p)] = f.face.points[p];
        f.face.points = f.points.data();
        f.face.pointCount = n;
    }
}

void FaceDebugLayer::setMeshTriangles(std::span<const std::array<int, 3>> triangles)
{
    std::vector<std::pair<int, int>>& edges = gl_->meshEdges;
    edges.clear();
    for (const std::array<int, 3>& t : triangles)
        for (int k = 0; k < 3; ++k)
            edges.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    gl_->meshVertices.assign(edges.size() * 6 * 2, 0.f);
}

void FaceDebugLayer::updateFits(std::span<const vision::FaceFit> fits) noexcept
{
    gl_->fitCount = static_cast<int>(std::min<std::size_t>(fits.size(), kMaxFaces));
    std::copy_n(fits.begin(), gl_->fitCount, gl_->fits.begin());
}

void FaceDebugLayer::draw(const LayerContext& context) noexcept
{
    if (!visible_ || (gl_->count == 0 && gl_->fitCount == 0))
        return;
    const float sx = 0.5f * static_cast<float>(context.viewportWidth);
    const float sy = 0.5f * static_cast<float>(context.viewportHeight);
    const float half = 0.5f * static_cast<float>(std::max(2, context.viewportHeight / 300));
    // Camera pixel (centre at integers) -> viewport pixels, relative to the viewport centre.
    auto toScreen = [&](vision::Point2f p, float& x, float& y) {
        x = (context.imageToNdc[0] * (p.x + 0.5f) + context.imageToNdc[1]) * sx;
        y = (context.imageToNdc[2] * (p.y + 0.5f) + context.imageToNdc[3]) * sy;
    };
    float* out = gl_->vertices.data();
    int vertices = 0;
    // A segment as a band of constant screen width (GLES2 line widths are not portable).
    auto segment = [&](vision::Point2f a, vision::Point2f b, float w) {
        float ax, ay, bx, by;
        toScreen(a, ax, ay);
        toScreen(b, bx, by);
        float dx = bx - ax, dy = by - ay;
        const float length = std::sqrt(dx * dx + dy * dy);
        if (length > 0.f) {
            dx = dx / length * w;
            dy = dy / length * w;
        } else {
            dx = w;
            dy = 0.f;
        }
        ax -= dx;
        ay -= dy;
        bx += dx;
        by += dy;
        const float corners[4][2] = {
            {ax - dy, ay + dx}, {ax + dy, ay - dx}, {bx - dy, by + dx}, {bx + dy, by - dx}};
        for (int k : {0, 1, 2, 2, 1, 3}) {
            *out++ = corners[k][0] / sx;
            *out++ = corners[k][1] / sy;
        }
        vertices += 6;
    };
    float* buffer = gl_->vertices.data();
    auto flush = [&](const float* color) {
        if (vertices == 0)
            return;
        glUniform4fv(gl_->color, 1, color);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, buffer);
        glDrawArrays(GL_TRIANGLES, 0, vertices);
        out = buffer;
        vertices = 0;
    };

    glUseProgram(gl_->program.id());
    glBindBuffer(GL_ARRAY_BUFFER, 0);  // client-side vertices
    glEnableVertexAttribArray(0);
    for (int i = 0; i < gl_->count; ++i) {
        const vision::TrackedFace& f = gl_->faces[static_cast<std::size_t>(i)].face;
        // §4: the box and the axis turned by the roll (clockwise on screen for positive).
        const float r = vision::toRadians(f.rollDegrees);
        const float c = std::cos(r), s = std::sin(r), h = 0.5f * f.size;
        auto at = [&](float u, float v) {
            return vision::Point2f{f.centre.x + c * u - s * v, f.centre.y + s * u + c * v};
        };
        const vision::Point2f box[4] = {at(-h, -h), at(h, -h), at(h, h), at(-h, h)};
        for (int k = 0; k < 4; ++k)
            segment(box[k], box[(k + 1) % 4], half);
        flush(f.state == vision::FaceState::Confirmed ? kShown
              : f.state == vision::FaceState::Missing ? kMissing
                                                      : kTentative);
        segment(at(0.f, -1.5f * h), at(0.f, 1.5f * h), half);
        flush(kAxis);
        for (int p = 0; p < f.pointCount; ++p)
            segment(f.points[p], f.points[p], 1.5f * half);
        flush(kPoint);
    }
    // §5.3: the fitted meshes, thin, over the faces.
    if (!gl_->meshEdges.empty()) {
        buffer = out = gl_->meshVertices.data();
        for (int i = 0; i < gl_->fitCount; ++i) {
            const vision::FaceFit& fit = gl_->fits[static_cast<std::size_t>(i)];
            if (!fit.fitted)
                continue;
            for (const auto& [a, b] : gl_->meshEdges)
                if (a < fit.vertexCount && b < fit.vertexCount)
                    segment(fit.vertices[static_cast<std::size_t>(a)],
                            fit.vertices[static_cast<std::size_t>(b)], 0.5f * half);
            flush(fit.ok() ? kMeshFitted : kMeshFailed);
        }
    }
    glDisableVertexAttribArray(0);
}

}  // namespace render
