#include "platform/headless_display.hpp"

#include "platform/egl_context.hpp"

#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace platform {

namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& what)
{
    throw std::runtime_error("headless display: " + what);
}

/// Creates `dir` like mkdir -p, except a new folder directly under / (a typo there must not litter
/// the appliance's root, and as root permissions would not stop it), then proves it writable.
void prepareOutputDir(const std::string& dir)
{
    if (dir.empty())
        fail("empty output folder name");
    std::error_code ec;
    const fs::path absolute = fs::absolute(dir, ec).lexically_normal();
    if (ec)
        fail("cannot resolve output folder " + dir + ": " + ec.message());

    const fs::path relative = absolute.relative_path();
    if (!relative.empty()) {
        const fs::path top = absolute.root_path() / *relative.begin();
        const bool topExists = fs::exists(top, ec);
        if (ec)
            fail("cannot use output folder " + dir + ": " + top.string() + ": " + ec.message());
        if (!topExists) {
            std::string message =
                top.string() +
                " does not exist and will not be created at the top of the file system";
            if (fs::path(dir).lexically_normal() != top)
                message += " (output folder " + dir + ")";
            fail(message);
        }
    }

    const fs::file_status status = fs::status(absolute, ec);
    if (fs::exists(status) && !fs::is_directory(status))
        fail("output folder " + dir + " exists and is not a directory");
    if (!fs::exists(status)) {
        fs::create_directories(absolute, ec);
        if (ec)
            fail("cannot create output folder " + dir + ": " + ec.message());
    }

    // A read-only mount, a full disk or a pseudo file system fails here, not at the first snapshot.
    const std::string probe = (absolute / (".write-probe-" + std::to_string(::getpid()))).string();
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
        fail("output folder " + dir + " is not writable: " + std::strerror(errno));
    ::close(fd);
    ::unlink(probe.c_str());
}

std::string withoutTrailingSlashes(std::string dir)
{
    while (dir.size() > 1 && dir.back() == '/')
        dir.pop_back();
    return dir;
}

const char* glString(GLenum name)
{
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s != nullptr ? s : "";
}

}  // namespace

HeadlessDisplay::HeadlessDisplay(const std::string& dir, int width, int height, int snapshotEvery)
    : dir_(withoutTrailingSlashes(dir)),
      width_(width),
      height_(height),
      snapshotEvery_(snapshotEvery > 0 ? snapshotEvery : 0)
{
    if (width <= 0 || height <= 0)
        fail("invalid size " + std::to_string(width) + "x" + std::to_string(height));
    // Room for "/snapshot-<any long>.png.tmp" in the fixed path buffers.
    if (dir_.size() + 40 > sizeof snapshotPath_)
        fail("output folder name too long: " + dir_);
    prepareOutputDir(dir_);

    try {
        egl_ = std::make_unique<EglContext>();
    } catch (const std::runtime_error& e) {
        fail(e.what());
    }
    createFramebuffer();
    pixels_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4, 0);

    description_ = "headless:" + dir_ + " (" + std::to_string(width_) + "x" +
                   std::to_string(height_) + ", " + glString(GL_RENDERER) + ")";
}

HeadlessDisplay::~HeadlessDisplay()
{
    // GL objects go while their context is current; then the context, then the EGL display.
    if (egl_ && egl_->makeCurrent())
        destroyFramebuffer();
    egl_.reset();
}

void HeadlessDisplay::createFramebuffer()
{
    const char* extensions = glString(GL_EXTENSIONS);
    if (!EglContext::hasExtension(extensions, "GL_OES_rgb8_rgba8"))
        fail(std::string("GL: no GL_OES_rgb8_rgba8 (RGBA8 renderbuffers) on ") +
             glString(GL_RENDERER));
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    if (width_ > maxSize || height_ > maxSize)
        fail("GL: " + std::to_string(width_) + "x" + std::to_string(height_) +
             " exceeds the largest renderbuffer (" + std::to_string(maxSize) + ")");
    hasStencil_ = EglContext::hasExtension(extensions, "GL_OES_packed_depth_stencil");

    glGenFramebuffers(1, &framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glGenRenderbuffers(1, &colorBuffer_);
    glBindRenderbuffer(GL_RENDERBUFFER, colorBuffer_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8_OES, width_, height_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colorBuffer_);

    glGenRenderbuffers(1, &depthBuffer_);
    glBindRenderbuffer(GL_RENDERBUFFER, depthBuffer_);
    glRenderbufferStorage(GL_RENDERBUFFER,
                          hasStencil_ ? GL_DEPTH24_STENCIL8_OES : GL_DEPTH_COMPONENT16, width_,
                          height_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer_);
    if (hasStencil_)
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                  depthBuffer_);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);

    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    const GLenum error = glGetError();
    if (status != GL_FRAMEBUFFER_COMPLETE || error != GL_NO_ERROR) {
        char detail[96];
        std::snprintf(detail, sizeof detail, "framebuffer status 0x%04X, GL error 0x%04X", status,
                      error);
        destroyFramebuffer();
        fail("GL: cannot create a " + std::to_string(width_) + "x" + std::to_string(height_) +
             " framebuffer (" + detail + ")");
    }
    // Defined content even if the first frame draws nothing.
    glViewport(0, 0, width_, height_);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | (hasStencil_ ? GL_STENCIL_BUFFER_BIT : 0));
}

void HeadlessDisplay::destroyFramebuffer() noexcept
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (depthBuffer_ != 0)
        glDeleteRenderbuffers(1, &depthBuffer_);
    if (colorBuffer_ != 0)
        glDeleteRenderbuffers(1, &colorBuffer_);
    if (framebuffer_ != 0)
        glDeleteFramebuffers(1, &framebuffer_);
    depthBuffer_ = colorBuffer_ = framebuffer_ = 0;
}

bool HeadlessDisplay::beginFrame() noexcept
{
    inFrame_ = false;
    if (!egl_->makeCurrent()) {
        std::snprintf(error_, sizeof error_, "eglMakeCurrent failed (%s)",
                      EglContext::errorName(eglGetError()));
        return false;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glViewport(0, 0, width_, height_);
    inFrame_ = true;
    return true;
}

bool HeadlessDisplay::present() noexcept
{
    if (!inFrame_) {
        std::snprintf(error_, sizeof error_, "present() without a successful beginFrame()");
        return false;
    }
    inFrame_ = false;
    const long frame = frames_++;
    const bool due = snapshotRequested_ || (snapshotEvery_ > 0 && frame % snapshotEvery_ == 0);
    if (!due) {
        glFinish();  // the frame is complete when present() returns, as after a real flip
        return true;
    }
    snapshotRequested_ = false;
    std::snprintf(snapshotPath_, sizeof snapshotPath_, "%s/snapshot-%06ld.png", dir_.c_str(),
                  frame);
    return writeSnapshot();
}

bool HeadlessDisplay::writeSnapshot() noexcept
{
    // Errors left by the renderer are its business; only the read-back's own error counts here.
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels_.data());
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        std::snprintf(error_, sizeof error_, "glReadPixels failed (GL error 0x%04X)", error);
        return false;
    }
    if (!png_.write(snapshotPath_, pixels_.data(), width_, height_,
                    static_cast<std::size_t>(width_) * 4, PngInputLayout::Rgbx,
                    PngRowOrder::BottomUp)) {
        std::snprintf(error_, sizeof error_, "snapshot: %.490s", png_.lastError());
        return false;
    }
    std::memcpy(lastSnapshot_, snapshotPath_, sizeof lastSnapshot_);
    return true;
}

bool HeadlessDisplay::requestSnapshot() noexcept
{
    snapshotRequested_ = true;
    return true;
}

}  // namespace platform
