#include "platform/egl_context.hpp"

#include <EGL/eglext.h>
#include <dlfcn.h>
#include <link.h>

#include <cstdio>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace platform {

namespace {

std::string lastEglError()
{
    return EglContext::errorName(eglGetError());
}

// EGL hands out one EGLDisplay per native display and eglTerminate() ends it for every user, so
// contexts sharing a display count references and only the last one terminates it.
struct DisplayUsers {
    std::mutex mutex;
    std::vector<std::pair<EGLDisplay, int>> counts;
};

DisplayUsers& displayUsers()
{
    static DisplayUsers users;
    return users;
}

void retainDisplay(EGLDisplay display)
{
    DisplayUsers& users = displayUsers();
    std::lock_guard lock(users.mutex);
    for (auto& [d, n] : users.counts) {
        if (d == display) {
            ++n;
            return;
        }
    }
    users.counts.emplace_back(display, 1);
}

/// True when the caller held the last reference.
bool releaseDisplay(EGLDisplay display) noexcept
{
    DisplayUsers& users = displayUsers();
    std::lock_guard lock(users.mutex);
    for (auto it = users.counts.begin(); it != users.counts.end(); ++it) {
        if (it->first == display) {
            if (--it->second > 0)
                return false;
            users.counts.erase(it);
            return true;
        }
    }
    return true;
}

/// Keeps the GL driver that eglInitialize loaded (Mesa's *_dri.so or libgallium) in memory for the
/// life of the process. Without this, eglTerminate unloads it and every pipeline restart loads and
/// JIT-initialises it again; it also keeps the driver's symbols available to leak reports.
void pinLoadedGlDrivers() noexcept
{
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void*) -> int {
            const char* name = info->dlpi_name;
            if (name && *name && (std::strstr(name, "_dri.so") || std::strstr(name, "libgallium")))
                dlopen(name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
            return 0;
        },
        nullptr);
}

/// Initialises `display`; on failure returns the reason and leaves it unusable.
std::string initializeDisplay(EGLDisplay display)
{
    if (display == EGL_NO_DISPLAY)
        return "no display (" + lastEglError() + ")";
    EGLint major = 0;
    EGLint minor = 0;
    if (!eglInitialize(display, &major, &minor))
        return "eglInitialize failed (" + lastEglError() + ")";
    pinLoadedGlDrivers();
    return {};
}

}  // namespace

EglContext::EglContext()
{
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!hasExtension(clientExtensions, "EGL_EXT_platform_base") || getPlatformDisplay == nullptr)
        throw std::runtime_error(
            "EGL: no EGL_EXT_platform_base, so no surfaceless platform (install libegl-mesa0)");

    const bool haveSurfaceless = hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless");
    std::string surfacelessProblem;
    if (haveSurfaceless) {
        EGLDisplay d =
            getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        surfacelessProblem = initializeDisplay(d);
        if (surfacelessProblem.empty()) {
            display_ = d;
            platformName_ = "surfaceless";
        }
    }

    std::string deviceProblem = "no EGL_EXT_platform_device";
    if (display_ == EGL_NO_DISPLAY && hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
        auto queryDevices =
            reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        EGLDeviceEXT device = nullptr;
        EGLint count = 0;
        if (queryDevices == nullptr || !queryDevices(1, &device, &count) || count < 1) {
            deviceProblem = "no EGL device";
        } else {
            EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
            deviceProblem = initializeDisplay(d);
            if (deviceProblem.empty()) {
                display_ = d;
                platformName_ = "device";
            }
        }
    }

    if (display_ == EGL_NO_DISPLAY) {
        if (!haveSurfaceless)
            throw std::runtime_error("EGL: no surfaceless platform (install libegl-mesa0); " +
                                     deviceProblem);
        throw std::runtime_error("EGL: surfaceless platform: " + surfacelessProblem +
                                 "; device platform: " + deviceProblem);
    }
    retainDisplay(display_);
    try {
        initialize(EGL_PBUFFER_BIT, 0);
    } catch (...) {
        destroy();
        throw;
    }
}

EglContext::EglContext(EGLenum platform, void* nativeDisplay, EGLint surfaceType,
                       EGLint nativeVisualId)
{
    std::snprintf(platformBuffer_, sizeof platformBuffer_, "platform 0x%04X", platform);
    platformName_ = platformBuffer_;
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!hasExtension(clientExtensions, "EGL_EXT_platform_base") || getPlatformDisplay == nullptr)
        throw std::runtime_error("EGL: no EGL_EXT_platform_base (install libegl-mesa0)");
    EGLDisplay d = getPlatformDisplay(platform, nativeDisplay, nullptr);
    const std::string problem = initializeDisplay(d);
    if (!problem.empty())
        throw std::runtime_error(std::string("EGL: ") + platformName_ + ": " + problem);
    display_ = d;
    retainDisplay(display_);
    try {
        initialize(surfaceType, nativeVisualId);
    } catch (...) {
        destroy();
        throw;
    }
}

EglContext::~EglContext()
{
    destroy();
}

void EglContext::initialize(EGLint surfaceType, EGLint nativeVisualId)
{
    if (!eglBindAPI(EGL_OPENGL_ES_API))
        throw std::runtime_error("EGL: OpenGL ES is not supported (" + lastEglError() + ")");

    // FBO-only rendering needs no depth or stencil in the config; a window surface does (overlays
    // use both).
    const bool window = (surfaceType & EGL_WINDOW_BIT) != 0;
    const EGLint attributes[] = {EGL_SURFACE_TYPE,
                                 surfaceType,
                                 EGL_RENDERABLE_TYPE,
                                 EGL_OPENGL_ES2_BIT,
                                 EGL_RED_SIZE,
                                 8,
                                 EGL_GREEN_SIZE,
                                 8,
                                 EGL_BLUE_SIZE,
                                 8,
                                 EGL_DEPTH_SIZE,
                                 window ? 16 : 0,
                                 EGL_STENCIL_SIZE,
                                 window ? 8 : 0,
                                 EGL_NONE};
    EGLConfig configs[64];
    EGLint count = 0;
    if (!eglChooseConfig(display_, attributes, configs, 64, &count) || count < 1) {
        char type[16];
        std::snprintf(type, sizeof type, "0x%X", static_cast<unsigned>(surfaceType));
        throw std::runtime_error(
            std::string("EGL: no RGB888 OpenGL ES 2 config for surface type ") + type + " (" +
            lastEglError() + ")");
    }
    config_ = nullptr;
    for (EGLint i = 0; i < count && config_ == nullptr; ++i) {
        EGLint visual = 0;
        if (nativeVisualId == 0 ||
            (eglGetConfigAttrib(display_, configs[i], EGL_NATIVE_VISUAL_ID, &visual) &&
             visual == nativeVisualId))
            config_ = configs[i];
    }
    if (config_ == nullptr)
        throw std::runtime_error("EGL: no OpenGL ES 2 config with native visual " +
                                 std::to_string(nativeVisualId));

    const EGLint contextAttributes[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    context_ = eglCreateContext(display_, config_, EGL_NO_CONTEXT, contextAttributes);
    if (context_ == EGL_NO_CONTEXT)
        throw std::runtime_error("EGL: cannot create an OpenGL ES 2 context (" + lastEglError() +
                                 ")");

    const char* extensions = eglQueryString(display_, EGL_EXTENSIONS);
    if (!hasExtension(extensions, "EGL_KHR_surfaceless_context") &&
        (surfaceType & EGL_PBUFFER_BIT) != 0) {
        const EGLint pbufferAttributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        fallbackSurface_ = eglCreatePbufferSurface(display_, config_, pbufferAttributes);
        if (fallbackSurface_ == EGL_NO_SURFACE)
            throw std::runtime_error("EGL: no surfaceless contexts and no pbuffer (" +
                                     lastEglError() + ")");
    }
    if (!makeCurrent())
        throw std::runtime_error("EGL: cannot make the context current (" + lastEglError() + ")");
}

bool EglContext::makeCurrent(EGLSurface surface) noexcept
{
    if (surface == EGL_NO_SURFACE)
        surface = fallbackSurface_;
    return eglMakeCurrent(display_, surface, surface, context_) == EGL_TRUE;
}

void EglContext::releaseCurrent() noexcept
{
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

void EglContext::destroy() noexcept
{
    if (display_ == EGL_NO_DISPLAY)
        return;
    if (context_ != EGL_NO_CONTEXT && eglGetCurrentContext() == context_)
        releaseCurrent();
    if (context_ != EGL_NO_CONTEXT)
        eglDestroyContext(display_, context_);
    if (fallbackSurface_ != EGL_NO_SURFACE)
        eglDestroySurface(display_, fallbackSurface_);
    context_ = EGL_NO_CONTEXT;
    fallbackSurface_ = EGL_NO_SURFACE;
    if (releaseDisplay(display_))
        eglTerminate(display_);
    display_ = EGL_NO_DISPLAY;
}

bool EglContext::hasExtension(const char* list, const char* name) noexcept
{
    if (list == nullptr)
        return false;
    const std::size_t length = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length) {
        const bool startsToken = p == list || p[-1] == ' ';
        const bool endsToken = p[length] == ' ' || p[length] == '\0';
        if (startsToken && endsToken)
            return true;
    }
    return false;
}

const char* EglContext::errorName(EGLint error) noexcept
{
    switch (error) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CURRENT_SURFACE:
            return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_SURFACE:
            return "EGL_BAD_SURFACE";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        case EGL_BAD_NATIVE_PIXMAP:
            return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW:
            return "EGL_BAD_NATIVE_WINDOW";
        case EGL_CONTEXT_LOST:
            return "EGL_CONTEXT_LOST";
        default:
            return "unknown EGL error";
    }
}

}  // namespace platform
