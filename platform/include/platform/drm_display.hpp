#pragma once
// DrmDisplay: full-screen output on a panel through DRM/KMS, GBM and EGL (no window system).

#include "platform/display.hpp"

#include <cstdint>
#include <memory>
#include <string>

namespace platform {

struct DrmOptions {
    std::string card;            ///< "/dev/dri/cardN", or "" for the first with a connected display
    std::string mode;            ///< "", "preferred", "WxH" or "WxH@Hz" (parseDisplayMode)
    std::string snapshotDir;     ///< an existing, writable folder for requestSnapshot(); "" = none
    int flipTimeoutMs = 1000;    ///< present() waits this long for the last flip, else it is stuck
    int retryIntervalMs = 1000;  ///< after a failed mode set or flip, beginFrame() declines frames
};

/// \class DrmDisplay
/// The kmscube path, kept honest for drivers such as vkms: the card is found by its connected
/// connector (no driver name is assumed), the mode comes from the config or is the connector's
/// preferred one, a GBM surface (XRGB8888, scanout) carries an EGL window surface with a GLES2
/// context (EglContext on EGL_PLATFORM_GBM_KHR). Each GBM buffer gets its framebuffer from
/// drmModeAddFB (legacy: no format modifiers, which some drivers reject) once, cached in a fixed
/// table through the buffer's user data and removed by its destroy callback. The first frame sets
/// the mode (drmModeSetCrtc); every later one is a page flip with a vblank event, which the next
/// present() waits for (poll + drmHandleEvent, with a timeout), so rendering overlaps the wait and
/// the loop runs at the panel's rate. The CRTC's previous configuration (the console) is restored
/// on destruction.
///
/// The constructor throws std::runtime_error with one line ("drm: ...") naming the card and the
/// reason: no /dev/dri/card*, no connected connector, no such mode, no CRTC, GBM or EGL failures.
///
/// At run time a failed mode set or flip (display unplugged, another program holding DRM master,
/// a flip that never completes) makes present() return false with lastError() set; the display
/// then declines frames (beginFrame() false) for retryIntervalMs and sets the mode again on the
/// next frame, until it works. modeSetFailures() counts these. beginFrame() and present() never
/// throw and never allocate (libdrm/Mesa internals aside).
///
/// Like HeadlessDisplay, the renderer draws between beginFrame() and present() on the same thread
/// and may rely on a current GLES2 context, the bound framebuffer (here the window surface, 0) and
/// a viewport covering it, nothing else.
class DrmDisplay final : public Display {
public:
    explicit DrmDisplay(const DrmOptions& options);
    ~DrmDisplay() override;

    /// E.g. "drm:/dev/dri/card0 Virtual-1 1024x768@60.00 (vkms, llvmpipe)".
    const char* description() const noexcept override;
    int width() const noexcept override;
    int height() const noexcept override;

    bool beginFrame() noexcept override;
    bool present() noexcept override;

    bool requestSnapshot() noexcept override;
    const char* lastSnapshot() const noexcept override;
    const char* outputDir() const noexcept override;
    const char* lastError() const noexcept override;

    /// The card in use, e.g. "/dev/dri/card0".
    const char* cardPath() const noexcept;
    /// Whether the mode is set and flips are running.
    bool modeSet() const noexcept;
    /// Frames shown (mode set or flip completed).
    long framesPresented() const noexcept;
    /// Failed mode sets and flips since construction.
    long modeSetFailures() const noexcept;
    double refreshHz() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// True when some /dev/dri/card* has a connected connector with at least one mode (what DrmDisplay
/// with an empty card needs). Opens the cards briefly; never sets a mode.
bool drmDisplayAvailable() noexcept;

}  // namespace platform
