#include "render/renderer.hpp"

#include "gl_program.hpp"
#include "render/hud_text.hpp"
#include "rotated_target.hpp"

#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

namespace render {
namespace {

constexpr const char* kVideoVertexShader = R"(#version 100
attribute vec2 aPosition;  // NDC
attribute vec2 aTexCoord;  // (0,0) = the image's top-left
varying vec2 vTexCoord;
void main()
{
    vTexCoord = aTexCoord;
    gl_Position = vec4(aPosition, 0.0, 1.0);
}
)";

// %s is the swizzle from texel to RGB. highp where available: mediump texture coordinates are
// too coarse to address single texels of a 1920-wide frame.
constexpr const char* kVideoFragmentShader = R"(#version 100
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif
uniform sampler2D uFrame;
varying vec2 vTexCoord;
void main()
{
    gl_FragColor = vec4(texture2D(uFrame, vTexCoord).%s, 1.0);
}
)";

struct TextureFormat {
    GLenum format;        // upload format (GLES2: also the internal format)
    const char* swizzle;  // texel components holding R, G, B
};

// Byte order in memory decides the swizzle: GL reads bytes as R,G,B(,A) in that order.
bool textureFormat(vision::PixelFormat f, TextureFormat& out) noexcept
{
    switch (f) {
        case vision::PixelFormat::RGB24:
            out = {GL_RGB, "rgb"};
            return true;
        case vision::PixelFormat::BGR24:
            out = {GL_RGB, "bgr"};
            return true;
        case vision::PixelFormat::XRGB8888:
            out = {GL_RGBA, "bgr"};  // bytes B,G,R,X
            return true;
        case vision::PixelFormat::Gray8:
            out = {GL_LUMINANCE, "rgb"};
            return true;
        default:
            return false;
    }
}

std::string videoFragmentSource(const char* swizzle)
{
    char source[512];
    std::snprintf(source, sizeof(source), kVideoFragmentShader, swizzle);
    return source;
}

constexpr int kVideoFloatsPerVertex = 4;  // x, y, s, t

}  // namespace

struct Renderer::Gl {
    Gl(vision::Size size, const TextureFormat& format)
        : program("video", kVideoVertexShader, videoFragmentSource(format.swizzle).c_str(),
                  {"aPosition", "aTexCoord"}),
          frameUniform(program.uniform("uFrame")),
          textureFormat(format.format),
          rowBytes(static_cast<std::size_t>(size.width) *
                   static_cast<std::size_t>(format.format == GL_RGBA  ? 4
                                            : format.format == GL_RGB ? 3
                                                                      : 1)),
          // Zeroed: the first upload of the (black) texture, then the repacking buffer for
          // frames whose stride is not tight (GLES2 has no GL_UNPACK_ROW_LENGTH).
          staging(
              std::make_unique<std::uint8_t[]>(rowBytes * static_cast<std::size_t>(size.height)))
    {
    }

    detail::GlProgram program;
    GLint frameUniform;
    GLenum textureFormat;
    std::size_t rowBytes;  // tight row of the texture
    std::unique_ptr<std::uint8_t[]> staging;
    detail::GlTexture frame;
    detail::GlBuffer quad;
    HudText hud;
    float quadVertices[4 * kVideoFloatsPerVertex] = {};
};

Renderer::Renderer(vision::Size videoSize, vision::PixelFormat videoFormat,
                   const RendererOptions& options)
    : videoSize_(videoSize), videoFormat_(videoFormat), options_(options)
{
    const std::string what = std::string("Renderer ") + std::to_string(videoSize.width) + "x" +
                             std::to_string(videoSize.height) + " " +
                             vision::pixelFormatName(videoFormat);
    TextureFormat format{};
    if (!textureFormat(videoFormat, format))
        throw std::runtime_error(
            what + ": unsupported video format (need RGB24, BGR24, XRGB8888 or GRAY8)");
    if (videoSize.width <= 0 || videoSize.height <= 0)
        throw std::runtime_error(what + ": empty video size");
    if (glGetString(GL_VERSION) == nullptr)
        throw std::runtime_error(what + ": no current GLES2 context");
    GLint maxTexture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    if (videoSize.width > maxTexture || videoSize.height > maxTexture)
        throw std::runtime_error(what + ": larger than GL_MAX_TEXTURE_SIZE " +
                                 std::to_string(maxTexture));

    try {
        gl_ = std::make_unique<Gl>(videoSize, format);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(what + ": " + e.what());
    }
    if (gl_->frame.id() == 0 || gl_->quad.id() == 0)
        throw std::runtime_error(what + ": cannot create GL texture or buffer");

    // Created once at the frame size; draw() only replaces its pixels.
    glBindTexture(GL_TEXTURE_2D, gl_->frame.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(format.format), videoSize.width,
                 videoSize.height, 0, format.format, GL_UNSIGNED_BYTE, gl_->staging.get());
    // Non-power-of-two sizes in GLES2 require CLAMP_TO_EDGE and no mipmaps.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);

    glBindBuffer(GL_ARRAY_BUFFER, gl_->quad.id());
    glBufferData(GL_ARRAY_BUFFER, sizeof(gl_->quadVertices), nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        char code[16];
        std::snprintf(code, sizeof(code), "0x%04x", error);
        throw std::runtime_error(what + ": GL error " + code + " while creating the video texture");
    }
    context_.image = videoSize;
    context_.mirrored = options.mirror;
    if (options.rotation != 0 && options.rotation != 90 && options.rotation != 180 &&
        options.rotation != 270)
        throw std::runtime_error(what + ": rotation " + std::to_string(options.rotation) +
                                 " (allowed: 0, 90, 180, 270)");
    if (options.rotation != 0)
        rotated_ = std::make_unique<detail::RotatedTarget>();
}

Renderer::~Renderer() = default;

/// Runs `draw(width, height)` upright into the rotation's off-screen framebuffer, then turns
/// the picture onto the display's; without a rotation straight into the display's.
template <typename Draw>
bool Renderer::drawTurned(int viewportWidth, int viewportHeight, Draw&& draw) noexcept
{
    if (!rotated_)
        return draw(viewportWidth, viewportHeight);
    int width = 0;
    int height = 0;
    if (!rotated_->begin(options_.rotation, viewportWidth, viewportHeight, width, height)) {
        std::snprintf(lastError_, sizeof(lastError_),
                      "display rotation: off-screen framebuffer %dx%d incomplete", viewportHeight,
                      viewportWidth);
        return false;
    }
    const bool drawn = draw(width, height);
    rotated_->finish();
    return drawn;
}

bool Renderer::draw(const vision::ConstImageView& frame, int viewportWidth, int viewportHeight,
                    const char* hudText) noexcept
{
    return drawTurned(viewportWidth, viewportHeight, [&](int width, int height) noexcept {
        return drawUpright(frame, width, height, hudText);
    });
}

bool Renderer::drawMessage(const char* message, int viewportWidth, int viewportHeight) noexcept
{
    return drawTurned(viewportWidth, viewportHeight, [&](int width, int height) noexcept {
        return drawMessageUpright(message, width, height);
    });
}

void Renderer::addLayer(OverlayLayer* layer)
{
    if (layer == nullptr)
        throw std::runtime_error("Renderer: addLayer(nullptr)");
    if (layerCount_ == kMaxLayers)
        throw std::runtime_error(std::string("Renderer: cannot add layer ") + layer->name() +
                                 ", already " + std::to_string(kMaxLayers) + " layers");
    layers_[layerCount_++] = layer;
}

bool Renderer::drawUpright(const vision::ConstImageView& frame, int viewportWidth,
                           int viewportHeight, const char* hudText) noexcept
{
    if (viewportWidth <= 0 || viewportHeight <= 0) {
        std::snprintf(lastError_, sizeof(lastError_), "empty viewport %dx%d", viewportWidth,
                      viewportHeight);
        return false;
    }
    // An empty frame redraws the last one (e.g. the HUD changed but no new frame came).
    const bool upload = !frame.empty();
    if (upload && (frame.size() != videoSize_ || frame.format != videoFormat_ ||
                   static_cast<std::size_t>(frame.stride) < gl_->rowBytes)) {
        std::snprintf(lastError_, sizeof(lastError_),
                      "frame %dx%d %s stride %d does not fit the renderer's %dx%d %s", frame.width,
                      frame.height, vision::pixelFormatName(frame.format), frame.stride,
                      videoSize_.width, videoSize_.height, vision::pixelFormatName(videoFormat_));
        return false;
    }

    // Fit: the image's half-extent in NDC. Cover overflows [-1, 1] on one axis (clipped away,
    // centred so the crop is symmetric); Contain stays inside it (cleared black around).
    const double imageAspect = static_cast<double>(videoSize_.width) / videoSize_.height;
    const double viewAspect = static_cast<double>(viewportWidth) / viewportHeight;
    double halfWidth = 1.0;
    double halfHeight = 1.0;
    if ((options_.fit == Fit::Cover) == (imageAspect > viewAspect))
        halfWidth = imageAspect / viewAspect;
    else
        halfHeight = viewAspect / imageAspect;
    const double flip = options_.mirror ? -1.0 : 1.0;
    context_.imageToNdc[0] = static_cast<float>(flip * 2.0 * halfWidth / videoSize_.width);
    context_.imageToNdc[1] = static_cast<float>(-flip * halfWidth);
    context_.imageToNdc[2] = static_cast<float>(-2.0 * halfHeight / videoSize_.height);
    context_.imageToNdc[3] = static_cast<float>(halfHeight);
    context_.image = videoSize_;
    context_.viewportWidth = viewportWidth;
    context_.viewportHeight = viewportHeight;
    context_.mirrored = options_.mirror;

    // The image corners through the same mapping the layers get, so video and layers agree.
    float* v = gl_->quadVertices;
    const float corners[4][2] = {{0.f, 0.f}, {1.f, 0.f}, {0.f, 1.f}, {1.f, 1.f}};
    for (const auto& c : corners) {
        *v++ = context_.imageToNdc[0] * c[0] * static_cast<float>(videoSize_.width) +
               context_.imageToNdc[1];
        *v++ = context_.imageToNdc[2] * c[1] * static_cast<float>(videoSize_.height) +
               context_.imageToNdc[3];
        *v++ = c[0];
        *v++ = c[1];
    }

    glViewport(0, 0, viewportWidth, viewportHeight);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(0.f, 0.f, 0.f, 1.f);
    glClear(GL_COLOR_BUFFER_BIT);

    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, gl_->frame.id());
    if (upload) {
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        const std::uint8_t* pixels = frame.data;
        if (static_cast<std::size_t>(frame.stride) != gl_->rowBytes) {
            std::uint8_t* packed = gl_->staging.get();
            for (int y = 0; y < frame.height; ++y)
                std::memcpy(packed + gl_->rowBytes * static_cast<std::size_t>(y), frame.row(y),
                            gl_->rowBytes);
            pixels = packed;
        }
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, videoSize_.width, videoSize_.height,
                        gl_->textureFormat, GL_UNSIGNED_BYTE, pixels);
    }
    glUseProgram(gl_->program.id());
    glUniform1i(gl_->frameUniform, 0);
    drawTexturedStrip(gl_->quad, gl_->quadVertices);
    glBindTexture(GL_TEXTURE_2D, 0);

    // Layers blend with standard (non-premultiplied) alpha; destination alpha stays opaque.
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    for (std::size_t i = 0; i < layerCount_; ++i)
        layers_[i]->draw(context_);

    if (options_.hud && hudText != nullptr && hudText[0] != '\0') {
        // Layers may have changed the viewport; the HUD is laid out in viewport pixels.
        glViewport(0, 0, viewportWidth, viewportHeight);
        gl_->hud.draw(hudText, viewportWidth, viewportHeight);
    }

    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        std::snprintf(lastError_, sizeof(lastError_), "GL error 0x%04x after draw", error);
        // GL may hold several error flags; clear them so the next frame reports its own.
        for (int i = 0; i < 8 && glGetError() != GL_NO_ERROR; ++i) {
        }
        return false;
    }
    return true;
}

bool Renderer::drawMessageUpright(const char* message, int viewportWidth,
                                  int viewportHeight) noexcept
{
    glViewport(0, 0, viewportWidth, viewportHeight);
    glDisable(GL_DEPTH_TEST);
    // A dark slate, not black: the mirror is on and says so.
    glClearColor(0.09f, 0.11f, 0.14f, 1.f);
    glClear(GL_COLOR_BUFFER_BIT);
    gl_->hud.drawCentred(message, viewportWidth, viewportHeight);
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        std::snprintf(lastError_, sizeof(lastError_), "GL error 0x%04x after drawMessage", error);
        for (int i = 0; i < 8 && glGetError() != GL_NO_ERROR; ++i) {
        }
        return false;
    }
    return true;
}

}  // namespace render
