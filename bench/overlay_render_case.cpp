#include "overlay_render_case.hpp"

// Compiled once mirror-bench links render (render/cmake/overlays.cmake does it); until then the
// glob that picks up every bench/*.cpp must not break the build of the other benchmarks.
#if __has_include("render/face_overlay_layer.hpp")

#include "platform/egl_context.hpp"
#include "render/face_overlay_layer.hpp"
#include "render/overlay_catalogue.hpp"
#include "render/renderer.hpp"
#include "vision/face_tracker.hpp"
#include "vision/image.hpp"

#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>
#include <time.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace bench {

namespace {

/// llvmpipe reads LP_NUM_THREADS when its screen is created (eglInitialize): 0 = no rasteriser
/// threads, everything on the thread that flushes, so the thread CPU clock sees all of it.
bool rasteriseOnCallingThread()
{
    return setenv("LP_NUM_THREADS", "0", 1) == 0;
}

double threadCpuMs()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

}  // namespace

struct OverlayRenderCase::Impl {
    platform::EglContext egl;
    GLuint framebuffer = 0;
    GLuint color = 0;
    GLuint depth = 0;
    int width = 0;
    int height = 0;
    render::OverlayCatalogue catalogue;
    vision::ImageBuffer video;
    std::unique_ptr<render::Renderer> renderer;
    std::unique_ptr<render::FaceOverlayLayer> layer;
    render::FaceDrawing faces[kFaces];
    int triangles = 0;
    std::string names;

    ~Impl()
    {
        layer.reset();
        renderer.reset();
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteRenderbuffers(1, &color);
        glDeleteRenderbuffers(1, &depth);
        egl.releaseCurrent();
    }
};

OverlayRenderCase::OverlayRenderCase(const std::string& catalogueToml, int width, int height)
    : impl_((rasteriseOnCallingThread(), std::make_unique<Impl>()))
{
    Impl& s = *impl_;
    if (!s.egl.makeCurrent())
        throw std::runtime_error("overlay render case: eglMakeCurrent without a surface failed");
    s.width = width;
    s.height = height;
    glGenFramebuffers(1, &s.framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, s.framebuffer);
    glGenRenderbuffers(1, &s.color);
    glBindRenderbuffer(GL_RENDERBUFFER, s.color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8_OES, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s.color);
    glGenRenderbuffers(1, &s.depth);
    glBindRenderbuffer(GL_RENDERBUFFER, s.depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s.depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("overlay render case: framebuffer incomplete");

    // A frame with some texture (the cost does not depend on it, but a flat frame could be
    // special-cased by a driver).
    s.video = vision::ImageBuffer(width, height, vision::PixelFormat::RGB24);
    for (int y = 0; y < height; ++y) {
        std::uint8_t* row = s.video.view().row(y);
        for (int x = 0; x < width * 3; ++x)
            row[x] = static_cast<std::uint8_t>((x * 7 + y * 3) & 0xff);
    }

    s.catalogue = render::OverlayCatalogue::load(catalogueToml);
    s.renderer =
        std::make_unique<render::Renderer>(vision::Size{width, height}, vision::PixelFormat::RGB24,
                                           render::RendererOptions{true, {}, false});
    s.layer = std::make_unique<render::FaceOverlayLayer>(s.catalogue);
    s.renderer->addLayer(s.layer.get());

    // Three faces of a group at 1-2 m, wearing the three heaviest overlays (most triangles).
    std::vector<int> order(static_cast<std::size_t>(s.catalogue.size()));
    std::iota(order.begin(), order.end(), 0);
    auto triangles = [&](int i) {
        std::size_t n = 0;
        for (const render::OverlayMesh& mesh : s.catalogue[i].meshes)
            n += mesh.indices.size();
        return n;
    };
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return triangles(a) > triangles(b); });
    const float sizes[kFaces] = {0.2f, 0.16f, 0.13f};
    for (int i = 0; i < kFaces; ++i) {
        vision::TrackedFace& f = s.faces[i].face;
        f.id = i + 1;
        f.size = sizes[i] * static_cast<float>(height);
        f.centre = {static_cast<float>(width) * (0.25f + 0.25f * static_cast<float>(i)),
                    static_cast<float>(height) * 0.55f};
        f.rollDegrees = static_cast<float>(i * 8 - 8);
        f.state = vision::FaceState::Confirmed;
        if (order.empty())
            continue;
        const int overlay = order[static_cast<std::size_t>(i) % order.size()];
        s.faces[i].overlay = overlay;
        s.triangles += static_cast<int>(triangles(overlay) / 3);
        s.names += (i ? "," : "") + s.catalogue[overlay].name;
    }
}

OverlayRenderCase::~OverlayRenderCase() = default;

bool OverlayRenderCase::frame(bool overlays)
{
    Impl& s = *impl_;
    s.layer->setFaces(overlays ? std::span<const render::FaceDrawing>(s.faces)
                               : std::span<const render::FaceDrawing>());
    const bool ok = s.renderer->draw(s.video.view(), s.width, s.height, nullptr);
    glFinish();
    return ok;
}

OverlayRenderCase::Timing OverlayRenderCase::measure(int frames)
{
    for (int i = 0; i < 5; ++i) {  // warm-up: llvmpipe compiles shader variants on first use
        frame(true);
        frame(false);
    }
    std::vector<double> with;
    std::vector<double> without;
    for (int i = 0; i < frames; ++i)
        for (int overlays = 0; overlays < 2; ++overlays) {
            const double t0 = threadCpuMs();
            frame(overlays == 1);
            (overlays ? with : without).push_back(threadCpuMs() - t0);
        }
    auto median = [](std::vector<double>& v) {
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    return {median(with), median(without), impl_->triangles};
}

std::string OverlayRenderCase::overlayNames() const
{
    return impl_->names;
}

const char* OverlayRenderCase::lastError() const
{
    return impl_->renderer->lastError();
}

}  // namespace bench

#endif  // __has_include("render/face_overlay_layer.hpp")
