#include "rotated_target.hpp"

#include <GLES2/gl2ext.h>

#include <cstring>
#include <stdexcept>

namespace render::detail {

namespace {

constexpr const char* kVertexShader = R"(#version 100
attribute vec2 aPosition;
attribute vec2 aTexCoord;
varying vec2 vTexCoord;
void main()
{
    vTexCoord = aTexCoord;
    gl_Position = vec4(aPosition, 0.0, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 100
precision mediump float;
uniform sampler2D uPicture;
varying vec2 vTexCoord;
void main()
{
    gl_FragColor = texture2D(uPicture, vTexCoord);
}
)";

bool hasExtension(const char* name) noexcept
{
    const auto* all = reinterpret_cast<const char*>(glGetString(GL_EXTENSIONS));
    return all != nullptr && std::strstr(all, name) != nullptr;
}

}  // namespace

void rotatedTexCoord(int degrees, float x, float y, float& u, float& v) noexcept
{
    // Turning the picture clockwise by 90 puts its top edge on the display's right edge and its
    // left edge on the display's top edge, so the display point (x, y) shows picture point
    // (1 - y, x); 180 and 270 follow the same way.
    switch (degrees) {
        case 90:
            u = 1.f - y;
            v = x;
            return;
        case 180:
            u = 1.f - x;
            v = 1.f - y;
            return;
        case 270:
            u = y;
            v = 1.f - x;
            return;
        default:
            u = x;
            v = y;
            return;
    }
}

RotatedTarget::RotatedTarget()
    : program_("rotation", kVertexShader, kFragmentShader, {"aPosition", "aTexCoord"}),
      pictureUniform_(program_.uniform("uPicture"))
{
    glGenFramebuffers(1, &framebuffer_);
    glGenRenderbuffers(1, &depth_);
    if (framebuffer_ == 0 || depth_ == 0 || colour_.id() == 0 || quad_.id() == 0)
        throw std::runtime_error("display rotation: cannot create the off-screen framebuffer");
    glBindBuffer(GL_ARRAY_BUFFER, quad_.id());
    glBufferData(GL_ARRAY_BUFFER, 16 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

RotatedTarget::~RotatedTarget()
{
    glDeleteRenderbuffers(1, &depth_);
    glDeleteFramebuffers(1, &framebuffer_);
}

bool RotatedTarget::allocate(int width, int height) noexcept
{
    glBindTexture(GL_TEXTURE_2D, colour_.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    // Depth and stencil as the display's own framebuffer has them: the overlays' 3D meshes and
    // the head occluder use both.
    const bool packed = hasExtension("GL_OES_packed_depth_stencil");
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, packed ? GL_DEPTH24_STENCIL8_OES : GL_DEPTH_COMPONENT16,
                          width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_.id(), 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    if (packed)
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return false;
    width_ = width;
    height_ = height;
    return true;
}

bool RotatedTarget::begin(int degrees, int displayWidth, int displayHeight, int& drawWidth,
                          int& drawHeight) noexcept
{
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &displayFramebuffer_);
    degrees_ = degrees;
    displayWidth_ = displayWidth;
    displayHeight_ = displayHeight;
    const bool sideways = degrees == 90 || degrees == 270;
    drawWidth = sideways ? displayHeight : displayWidth;
    drawHeight = sideways ? displayWidth : displayHeight;
    if (drawWidth != width_ || drawHeight != height_) {
        if (!allocate(drawWidth, drawHeight)) {
            glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(displayFramebuffer_));
            return false;
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    return true;
}

void RotatedTarget::finish() noexcept
{
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(displayFramebuffer_));
    glViewport(0, 0, displayWidth_, displayHeight_);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    float vertices[16];
    const float corners[4][2] = {{0.f, 0.f}, {1.f, 0.f}, {0.f, 1.f}, {1.f, 1.f}};
    float* p = vertices;
    for (const auto& c : corners) {
        *p++ = 2.f * c[0] - 1.f;
        *p++ = 2.f * c[1] - 1.f;
        rotatedTexCoord(degrees_, c[0], c[1], p[0], p[1]);
        p += 2;
    }
    glUseProgram(program_.id());
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, colour_.id());
    glUniform1i(pictureUniform_, 0);
    drawTexturedStrip(quad_, vertices);
    glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace render::detail
