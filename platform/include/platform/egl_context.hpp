#pragma once
// EglContext: an EGL display connection and an OpenGL ES 2 context, owned together (RAII).

// Keep X11's macros (None, Bool, Status...) out of every file that includes this header.
#ifndef EGL_NO_X11
#define EGL_NO_X11
#endif
#include <EGL/egl.h>

namespace platform {

/// \class EglContext
/// Opens an EGL display, initialises it, picks an RGBA8888 config that can render OpenGL ES 2 and
/// creates a GLES2 context on it. Construction throws std::runtime_error with one line starting
/// "EGL: " when any step fails.
///
/// The default constructor is for rendering without any window system: Mesa's surfaceless
/// platform (EGL_MESA_platform_surfaceless), else the first device of EGL_EXT_platform_device.
/// Such a context draws into framebuffer objects only. The other constructor takes a native
/// display of a window-system platform, e.g. (EGL_PLATFORM_GBM_KHR, gbm_device*) for DRM/KMS.
///
/// Several EglContext objects may share one EGLDisplay (EGL returns the same handle for the same
/// native display); the display is terminated when the last of them is destroyed.
class EglContext {
public:
    /// Headless: surfaceless platform, else the first EGL device.
    EglContext();
    /// On `nativeDisplay` of `platform` (an EGL_PLATFORM_* value). `surfaceType` is the
    /// EGL_SURFACE_TYPE the config must support (e.g. EGL_WINDOW_BIT); `nativeVisualId`, when not
    /// 0, selects the config whose EGL_NATIVE_VISUAL_ID matches (e.g. GBM_FORMAT_XRGB8888).
    EglContext(EGLenum platform, void* nativeDisplay, EGLint surfaceType,
               EGLint nativeVisualId = 0);
    /// Releases the context from this thread, destroys it and terminates the display if unused.
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    /// Makes the context current on the calling thread with `surface` as draw and read surface
    /// (EGL_NO_SURFACE: render to FBOs only). False on failure; eglGetError() says why.
    bool makeCurrent(EGLSurface surface = EGL_NO_SURFACE) noexcept;
    /// Releases the context from the calling thread.
    void releaseCurrent() noexcept;

    EGLDisplay display() const noexcept { return display_; }
    EGLConfig config() const noexcept { return config_; }
    EGLContext context() const noexcept { return context_; }
    /// "surfaceless", "device" or "platform 0x31D7": how the display was opened.
    const char* platformName() const noexcept { return platformName_; }

    /// Name of an EGL error code, e.g. "EGL_BAD_MATCH".
    static const char* errorName(EGLint error) noexcept;
    /// Whether the space-separated extension list (EGL or GL_EXTENSIONS) names `name` exactly.
    static bool hasExtension(const char* list, const char* name) noexcept;

private:
    void initialize(EGLint surfaceType, EGLint nativeVisualId);
    void destroy() noexcept;

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLConfig config_ = nullptr;
    EGLContext context_ = EGL_NO_CONTEXT;
    // A 1x1 pbuffer stands in for EGL_NO_SURFACE when EGL_KHR_surfaceless_context is missing.
    EGLSurface fallbackSurface_ = EGL_NO_SURFACE;
    const char* platformName_ = "";
    char platformBuffer_[32] = {};
};

}  // namespace platform
