#pragma once
// GlTestContext: a surfaceless EGL GLES2 context (Mesa llvmpipe headless) with a bound RGBA8
// framebuffer object, and read-back of its pixels, for render tests only.

#include "platform/egl_context.hpp"

#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace testing_support {

struct Rgba {
    int r = 0;
    int g = 0;
    int b = 0;
    int a = 0;
};

class GlTestContext {
public:
    /// Creates the context, makes it current and binds a width x height framebuffer.
    GlTestContext(int width, int height)
    {
        // The same surfaceless context the headless display uses (platform/egl_context.hpp).
        if (!egl_.makeCurrent())
            fail("eglMakeCurrent without a surface");
        glGenFramebuffers(1, &framebuffer_);
        glGenRenderbuffers(1, &renderbuffer_);
        resize(width, height);
    }

    ~GlTestContext()
    {
        glDeleteFramebuffers(1, &framebuffer_);
        glDeleteRenderbuffers(1, &renderbuffer_);
        egl_.releaseCurrent();
    }

    GlTestContext(const GlTestContext&) = delete;
    GlTestContext& operator=(const GlTestContext&) = delete;

    /// Reallocates the framebuffer at a new size (contents undefined) and keeps it bound.
    void resize(int width, int height)
    {
        width_ = width;
        height_ = height;
        glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer_);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8_OES, width, height);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  renderbuffer_);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            fail("framebuffer incomplete");
        pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 0);
    }

    int width() const { return width_; }
    int height() const { return height_; }

    /// Reads the framebuffer back (call after drawing, before pixel()).
    void read()
    {
        glFinish();
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels_.data());
    }

    /// Pixel of the last read(), y counted from the TOP like image rows (glReadPixels starts at
    /// the bottom row; NDC y = +1 is the top).
    Rgba pixel(int x, int y) const
    {
        const std::size_t i =
            (static_cast<std::size_t>(height_ - 1 - y) * static_cast<std::size_t>(width_) +
             static_cast<std::size_t>(x)) *
            4;
        return {pixels_[i], pixels_[i + 1], pixels_[i + 2], pixels_[i + 3]};
    }

private:
    [[noreturn]] static void fail(const char* what)
    {
        throw std::runtime_error(std::string("GL test context: ") + what + " (EGL error 0x" +
                                 hex(eglGetError()) + ")");
    }
    static std::string hex(EGLint value)
    {
        char text[16];
        std::snprintf(text, sizeof(text), "%04x", static_cast<unsigned>(value));
        return text;
    }

    platform::EglContext egl_;
    GLuint framebuffer_ = 0;
    GLuint renderbuffer_ = 0;
    int width_ = 0;
    int height_ = 0;
    std::vector<std::uint8_t> pixels_;
};

}  // namespace testing_support
