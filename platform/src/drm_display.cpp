// GCC 12 at -O3 reports a false -Wrestrict inside libstdc++'s char_traits for `"literal" +
// std::string` (GCC bug 105329); the message building below is start-up code, not a hot path.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif
#include "platform/drm_display.hpp"

#include "drm_output_choice.hpp"
#include "platform/display_mode.hpp"
#include "platform/egl_context.hpp"
#include "platform/png_writer.hpp"

#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <gbm.h>
#include <poll.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <string>
#include <vector>

namespace platform {

namespace {

std::int64_t monotonicMs() noexcept
{
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1000 + ts.tv_nsec / 1'000'000;
}

/// Framebuffer ids of GBM buffers, in a fixed table: a GBM surface has only a few buffers.
struct FramebufferSlot {
    int fd = -1;
    std::uint32_t id = 0;
    bool used = false;
};
constexpr int kFramebufferSlots = 8;

void destroyFramebuffer(gbm_bo*, void* data)
{
    auto* slot = static_cast<FramebufferSlot*>(data);
    if (slot->id != 0)
        drmModeRmFB(slot->fd, slot->id);
    *slot = {};
}

}  // namespace

struct DrmDisplay::Impl {
    DrmOptions options;
    std::string cardPath;
    int fd = -1;
    std::uint32_t connectorId = 0;
    std::uint32_t crtcId = 0;
    drmModeModeInfo mode{};
    double refreshHz = 0.0;
    drmModeCrtc* savedCrtc = nullptr;
    gbm_device* gbm = nullptr;
    gbm_surface* surface = nullptr;
    std::unique_ptr<EglContext> egl;
    EGLSurface eglSurface = EGL_NO_SURFACE;
    std::array<FramebufferSlot, kFramebufferSlots> slots{};

    gbm_bo* shown = nullptr;    ///< on screen
    gbm_bo* pending = nullptr;  ///< flip requested, not yet completed
    bool flipDone = false;
    bool modeIsSet = false;
    bool inFrame = false;
    std::int64_t retryAtMs = 0;
    long frames = 0;
    long failures = 0;

    std::unique_ptr<PngWriter> png;
    std::vector<std::uint8_t> pixels;
    bool snapshotRequested = false;
    long snapshotNumber = 0;
    char snapshotPath[4096] = {};
    char lastSnapshot[4096] = {};
    std::string description;
    char error[512] = {};

    [[noreturn]] void fail(const std::string& what) const { throwDrmError(cardPath, what); }

    void open();
    void createSurface();
    void close() noexcept;
    std::uint32_t framebufferFor(gbm_bo* bo) noexcept;
    bool waitForFlip(int timeoutMs) noexcept;
    bool failFrame(const char* what, int err) noexcept;
    bool writeSnapshot() noexcept;
    bool present() noexcept;
};

void DrmDisplay::Impl::open()
{
    const DrmOutput output = chooseDrmOutput(options.card, options.mode);
    fd = output.fd;
    cardPath = output.cardPath;
    connectorId = output.connectorId;
    crtcId = output.crtcId;
    mode = output.mode;
    refreshHz = displayModeCandidateOf(mode).refreshHz;
    savedCrtc = drmModeGetCrtc(fd, crtcId);

    createSurface();

    if (!options.snapshotDir.empty()) {
        if (options.snapshotDir.size() + 40 > sizeof snapshotPath)
            fail("snapshot folder name too long");
        if (access(options.snapshotDir.c_str(), W_OK) != 0)
            fail("snapshot folder " + options.snapshotDir +
                 " is not writable: " + std::strerror(errno));
        png = std::make_unique<PngWriter>();
        pixels.assign(static_cast<std::size_t>(mode.hdisplay) * mode.vdisplay * 4, 0);
    }

    drmVersion* version = drmGetVersion(fd);
    const std::string driver = version != nullptr && version->name != nullptr ? version->name : "?";
    if (version != nullptr)
        drmFreeVersion(version);
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    description = "drm:" + cardPath + " " + output.connectorName + " " +
                  displayModeName(displayModeCandidateOf(mode)) + " (" + driver + ", " +
                  (renderer != nullptr ? renderer : "?") + ")";
}

void DrmDisplay::Impl::createSurface()
{
    gbm = gbm_create_device(fd);
    if (gbm == nullptr)
        fail("cannot create a GBM device");
    surface = gbm_surface_create(gbm, mode.hdisplay, mode.vdisplay, GBM_FORMAT_XRGB8888,
                                 GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    if (surface == nullptr)
        fail("cannot create a " + std::to_string(mode.hdisplay) + "x" +
             std::to_string(mode.vdisplay) + " XRGB8888 GBM surface");
    try {
        egl = std::make_unique<EglContext>(EGL_PLATFORM_GBM_KHR, gbm, EGL_WINDOW_BIT,
                                           static_cast<EGLint>(GBM_FORMAT_XRGB8888));
    } catch (const std::runtime_error& e) {
        fail(e.what());
    }
    auto createWindowSurface = reinterpret_cast<PFNEGLCREATEPLATFORMWINDOWSURFACEEXTPROC>(
        eglGetProcAddress("eglCreatePlatformWindowSurfaceEXT"));
    if (createWindowSurface == nullptr)
        fail("EGL: no eglCreatePlatformWindowSurfaceEXT");
    eglSurface = createWindowSurface(egl->display(), egl->config(), surface, nullptr);
    if (eglSurface == EGL_NO_SURFACE)
        fail(std::string("EGL: cannot create a window surface on GBM (") +
             EglContext::errorName(eglGetError()) + ")");
    if (!egl->makeCurrent(eglSurface))
        fail(std::string("EGL: cannot make the context current (") +
             EglContext::errorName(eglGetError()) + ")");
}

void DrmDisplay::Impl::close() noexcept
{
    if (pending != nullptr && fd >= 0)
        waitForFlip(options.flipTimeoutMs);
    if (savedCrtc != nullptr) {
        // Give the panel back to the console as it was.
        if (modeIsSet)
            drmModeSetCrtc(fd, savedCrtc->crtc_id, savedCrtc->buffer_id, savedCrtc->x, savedCrtc->y,
                           &connectorId, 1, &savedCrtc->mode);
        drmModeFreeCrtc(savedCrtc);
        savedCrtc = nullptr;
    }
    if (egl) {
        egl->releaseCurrent();
        if (eglSurface != EGL_NO_SURFACE)
            eglDestroySurface(egl->display(), eglSurface);
    }
    eglSurface = EGL_NO_SURFACE;
    if (surface != nullptr) {
        if (pending != nullptr)
            gbm_surface_release_buffer(surface, pending);
        if (shown != nullptr)
            gbm_surface_release_buffer(surface, shown);
    }
    pending = shown = nullptr;
    egl.reset();
    // Destroying the surface destroys its buffers; their callbacks remove the framebuffers.
    if (surface != nullptr)
        gbm_surface_destroy(surface);
    surface = nullptr;
    if (gbm != nullptr)
        gbm_device_destroy(gbm);
    gbm = nullptr;
    if (fd >= 0)
        ::close(fd);
    fd = -1;
}

std::uint32_t DrmDisplay::Impl::framebufferFor(gbm_bo* bo) noexcept
{
    if (auto* slot = static_cast<FramebufferSlot*>(gbm_bo_get_user_data(bo)))
        return slot->id;
    for (FramebufferSlot& slot : slots) {
        if (slot.used)
            continue;
        std::uint32_t id = 0;
        // Legacy AddFB: no modifiers (vkms and others reject the ones GBM would pass).
        if (drmModeAddFB(fd, gbm_bo_get_width(bo), gbm_bo_get_height(bo), 24, 32,
                         gbm_bo_get_stride(bo), gbm_bo_get_handle(bo).u32, &id) != 0) {
            std::snprintf(error, sizeof error, "drm: %s: cannot add a framebuffer: %s",
                          cardPath.c_str(), std::strerror(errno));
            return 0;
        }
        slot = {fd, id, true};
        gbm_bo_set_user_data(bo, &slot, destroyFramebuffer);
        return id;
    }
    std::snprintf(error, sizeof error, "drm: %s: more GBM buffers than framebuffer slots",
                  cardPath.c_str());
    return 0;
}

bool DrmDisplay::Impl::waitForFlip(int timeoutMs) noexcept
{
    drmEventContext events{};
    events.version = 2;
    events.page_flip_handler = [](int, unsigned, unsigned, unsigned, void* data) {
        *static_cast<bool*>(data) = true;
    };
    const std::int64_t deadline = monotonicMs() + timeoutMs;
    while (!flipDone) {
        const std::int64_t left = deadline - monotonicMs();
        if (left <= 0)
            return false;
        pollfd pfd{fd, POLLIN, 0};
        const int ready = poll(&pfd, 1, static_cast<int>(left));
        if (ready < 0 && errno != EINTR)
            return false;
        if (ready > 0 && drmHandleEvent(fd, &events) != 0)
            return false;
    }
    if (shown != nullptr)
        gbm_surface_release_buffer(surface, shown);
    shown = pending;
    pending = nullptr;
    ++frames;
    return true;
}

bool DrmDisplay::Impl::failFrame(const char* what, int err) noexcept
{
    ++failures;
    modeIsSet = false;  // the next attempt sets the mode again
    retryAtMs = monotonicMs() + options.retryIntervalMs;
    const char* hint = err == EACCES || err == EPERM
                           ? " (not DRM master: another program holds the display)"
                           : (err == ENODEV ? " (display or card gone)" : "");
    if (err != 0)
        std::snprintf(error, sizeof error, "drm: %s: %s: %s%s; retrying", cardPath.c_str(), what,
                      std::strerror(err), hint);
    else
        std::snprintf(error, sizeof error, "drm: %s: %s; retrying", cardPath.c_str(), what);
    return false;
}

bool DrmDisplay::Impl::writeSnapshot() noexcept
{
    snapshotRequested = false;
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {
    }
    const int w = mode.hdisplay;
    const int h = mode.vdisplay;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        std::snprintf(error, sizeof error, "snapshot: glReadPixels failed (GL error 0x%04X)", e);
        return false;
    }
    std::snprintf(snapshotPath, sizeof snapshotPath, "%s/snapshot-%06ld.png",
                  options.snapshotDir.c_str(), snapshotNumber);
    if (!png->write(snapshotPath, pixels.data(), w, h, static_cast<std::size_t>(w) * 4,
                    PngInputLayout::Rgbx, PngRowOrder::BottomUp)) {
        std::snprintf(error, sizeof error, "snapshot: %.490s", png->lastError());
        return false;
    }
    std::memcpy(lastSnapshot, snapshotPath, sizeof lastSnapshot);
    return true;
}

bool DrmDisplay::Impl::present() noexcept
{
    if (!inFrame) {
        std::snprintf(error, sizeof error, "present() without a successful beginFrame()");
        return false;
    }
    inFrame = false;
    bool snapshotOk = true;
    // A snapshot reads the frame back before the swap and flip, from the buffer just drawn.
    if (snapshotRequested) {
        snapshotNumber = frames;
        snapshotOk = writeSnapshot();
    }

    // The previous flip must complete before its buffer's predecessor can be reused.
    if (pending != nullptr && !waitForFlip(options.flipTimeoutMs)) {
        // Count the buffer as shown so the surface does not run out of buffers; the retry sets
        // the mode afresh.
        if (shown != nullptr)
            gbm_surface_release_buffer(surface, shown);
        shown = pending;
        pending = nullptr;
        return failFrame("page flip did not complete", 0);
    }

    if (!eglSwapBuffers(egl->display(), eglSurface)) {
        ++failures;
        std::snprintf(error, sizeof error, "drm: %s: eglSwapBuffers failed (%s)", cardPath.c_str(),
                      EglContext::errorName(eglGetError()));
        return false;
    }
    gbm_bo* next = gbm_surface_lock_front_buffer(surface);
    if (next == nullptr)
        return failFrame("no front buffer after eglSwapBuffers", 0);
    const std::uint32_t fb = framebufferFor(next);
    if (fb == 0) {
        gbm_surface_release_buffer(surface, next);
        ++failures;
        return false;
    }

    if (!modeIsSet) {
        // Another program may have held the display and let it go since: take it back (works
        // when nobody is master now, for a privileged process or the card's first opener).
        if (failures > 0)
            drmSetMaster(fd);
        if (drmModeSetCrtc(fd, crtcId, fb, 0, 0, &connectorId, 1, &mode) != 0) {
            const int err = errno;
            gbm_surface_release_buffer(surface, next);
            return failFrame("mode set failed", err);
        }
        modeIsSet = true;
        if (shown != nullptr)
            gbm_surface_release_buffer(surface, shown);
        shown = next;
        ++frames;
        return snapshotOk;
    }
    flipDone = false;
    if (drmModePageFlip(fd, crtcId, fb, DRM_MODE_PAGE_FLIP_EVENT, &flipDone) != 0) {
        const int err = errno;
        gbm_surface_release_buffer(surface, next);
        return failFrame("page flip failed", err);
    }
    pending = next;
    return snapshotOk;
}

DrmDisplay::DrmDisplay(const DrmOptions& options) : impl_(std::make_unique<Impl>())
{
    impl_->options = options;
    if (impl_->options.flipTimeoutMs <= 0)
        impl_->options.flipTimeoutMs = 1000;
    if (impl_->options.retryIntervalMs < 0)
        impl_->options.retryIntervalMs = 0;
    try {
        impl_->open();
    } catch (...) {
        impl_->close();
        throw;
    }
}

DrmDisplay::~DrmDisplay()
{
    impl_->close();
}

const char* DrmDisplay::description() const noexcept
{
    return impl_->description.c_str();
}

int DrmDisplay::width() const noexcept
{
    return impl_->mode.hdisplay;
}

int DrmDisplay::height() const noexcept
{
    return impl_->mode.vdisplay;
}

bool DrmDisplay::beginFrame() noexcept
{
    Impl& d = *impl_;
    d.inFrame = false;
    if (!d.modeIsSet && d.failures > 0 && monotonicMs() < d.retryAtMs)
        return false;  // lastError() still says why
    if (!d.egl->makeCurrent(d.eglSurface)) {
        std::snprintf(d.error, sizeof d.error, "eglMakeCurrent failed (%s)",
                      EglContext::errorName(eglGetError()));
        return false;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, d.mode.hdisplay, d.mode.vdisplay);
    d.inFrame = true;
    return true;
}

bool DrmDisplay::present() noexcept
{
    return impl_->present();
}

bool DrmDisplay::requestSnapshot() noexcept
{
    if (!impl_->png)
        return false;
    impl_->snapshotRequested = true;
    return true;
}

const char* DrmDisplay::lastSnapshot() const noexcept
{
    return impl_->lastSnapshot;
}

const char* DrmDisplay::outputDir() const noexcept
{
    return impl_->options.snapshotDir.c_str();
}

const char* DrmDisplay::lastError() const noexcept
{
    return impl_->error;
}

const char* DrmDisplay::cardPath() const noexcept
{
    return impl_->cardPath.c_str();
}

bool DrmDisplay::modeSet() const noexcept
{
    return impl_->modeIsSet;
}

long DrmDisplay::framesPresented() const noexcept
{
    return impl_->frames;
}

long DrmDisplay::modeSetFailures() const noexcept
{
    return impl_->failures;
}

double DrmDisplay::refreshHz() const noexcept
{
    return impl_->refreshHz;
}

}  // namespace platform
