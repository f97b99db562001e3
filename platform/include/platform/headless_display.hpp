#pragma once
// HeadlessDisplay: renders off-screen with EGL (no window system) and writes PNG snapshots.

#include "platform/display.hpp"
#include "platform/png_writer.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace platform {

class EglContext;

/// \class HeadlessDisplay
/// A Display without a screen: an OpenGL ES 2 context on Mesa's surfaceless EGL platform (or the
/// first EGL device) drawing into a framebuffer object with an RGBA8 colour buffer and a depth
/// buffer (24-bit depth + 8-bit stencil with OES_packed_depth_stencil, else 16-bit depth only).
/// present() reads the frame back and writes DIR/snapshot-NNNNNN.png (NNNNNN = the number of
/// frames presented before it, counting from 0) every `snapshotEvery` frames and after
/// requestSnapshot(). Used by tests, benchmarks and demos, and on machines without a panel.
///
/// The constructor creates the output folder (with missing parents, but never a new folder at
/// the top of the file system: a typo must not litter /), proves it writable, and allocates the
/// context, framebuffer and every buffer; it throws std::runtime_error with one line
/// ("headless display: ...") on any failure. beginFrame() and present() never throw and never
/// allocate on the heap, including when they write a snapshot.
///
/// The renderer draws between beginFrame() and present() on the same thread; it may rely on a
/// current GLES2 context, the bound framebuffer and a viewport covering it, nothing else.
class HeadlessDisplay final : public Display {
public:
    /// `snapshotEvery` <= 0: snapshots only on request.
    HeadlessDisplay(const std::string& dir, int width, int height, int snapshotEvery);
    ~HeadlessDisplay() override;

    const char* description() const noexcept override { return description_.c_str(); }
    int width() const noexcept override { return width_; }
    int height() const noexcept override { return height_; }

    bool beginFrame() noexcept override;
    bool present() noexcept override;

    bool requestSnapshot() noexcept override;
    const char* lastSnapshot() const noexcept override { return lastSnapshot_; }
    const char* outputDir() const noexcept override { return dir_.c_str(); }
    const char* lastError() const noexcept override { return error_; }

    /// Frames presented so far (the number the next snapshot would carry).
    long framesPresented() const noexcept { return frames_; }
    /// Whether the framebuffer has a stencil buffer (OES_packed_depth_stencil).
    bool hasStencil() const noexcept { return hasStencil_; }
    /// The GL framebuffer object frames are drawn into (bound by beginFrame()).
    unsigned framebuffer() const noexcept { return framebuffer_; }

private:
    void createFramebuffer();
    void destroyFramebuffer() noexcept;
    bool writeSnapshot() noexcept;

    std::string dir_;
    int width_ = 0;
    int height_ = 0;
    int snapshotEvery_ = 0;
    std::string description_;
    std::unique_ptr<EglContext> egl_;
    unsigned framebuffer_ = 0;
    unsigned colorBuffer_ = 0;
    unsigned depthBuffer_ = 0;
    bool hasStencil_ = false;
    std::vector<std::uint8_t> pixels_;  ///< RGBA readback, bottom row first
    PngWriter png_;
    long frames_ = 0;
    bool inFrame_ = false;
    bool snapshotRequested_ = false;
    char snapshotPath_[4096] = {};
    char lastSnapshot_[4096] = {};
    char error_[512] = {};
};

}  // namespace platform
