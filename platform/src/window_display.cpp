#include "platform/window_display.hpp"

#include "platform/egl_context.hpp"

#include <EGL/eglext.h>
#include <GLES2/gl2.h>
// Xlib last: its macros (None, Bool, Status) must not reach the other headers.
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace platform {

struct WindowDisplay::Impl {
    ::Display* x = nullptr;
    Window window = 0;
    Colormap colormap = 0;
    Atom deleteWindow = 0;
    std::unique_ptr<EglContext> egl;
    EGLSurface surface = EGL_NO_SURFACE;
    int width = 0;
    int height = 0;
    bool closed = false;
    bool inFrame = false;
    std::array<KeyEvent, 32> keys{};
    std::size_t keyHead = 0;
    std::size_t keyCount = 0;
    std::string description;
    char error[256] = {};

    [[noreturn]] static void fail(const std::string& what)
    {
        throw std::runtime_error("window: " + what);
    }

    void open(const std::string& title);
    void close() noexcept;
    void pollEvents() noexcept;
};

void WindowDisplay::Impl::open(const std::string& title)
{
    const char* name = std::getenv("DISPLAY");
    if (name == nullptr || *name == '\0')
        fail("no X display ($DISPLAY is not set)");
    x = XOpenDisplay(name);
    if (x == nullptr)
        fail(std::string("cannot connect to X display ") + name);

    try {
        egl = std::make_unique<EglContext>(EGL_PLATFORM_X11_KHR, x, EGL_WINDOW_BIT);
    } catch (const std::runtime_error& e) {
        fail(e.what());
    }
    EGLint visualId = 0;
    eglGetConfigAttrib(egl->display(), egl->config(), EGL_NATIVE_VISUAL_ID, &visualId);
    XVisualInfo wanted{};
    wanted.visualid = static_cast<VisualID>(visualId);
    int count = 0;
    XVisualInfo* visual = XGetVisualInfo(x, VisualIDMask, &wanted, &count);
    if (visual == nullptr || count < 1)
        fail("no X visual for the EGL config (visual id " + std::to_string(visualId) + ")");

    const Window root = RootWindow(x, visual->screen);
    colormap = XCreateColormap(x, root, visual->visual, AllocNone);
    XSetWindowAttributes attributes{};
    attributes.colormap = colormap;
    attributes.background_pixel = 0;
    attributes.border_pixel = 0;
    attributes.event_mask = KeyPressMask | StructureNotifyMask | ExposureMask;
    window =
        XCreateWindow(x, root, 0, 0, static_cast<unsigned>(width), static_cast<unsigned>(height), 0,
                      visual->depth, InputOutput, visual->visual,
                      CWColormap | CWBackPixel | CWBorderPixel | CWEventMask, &attributes);
    XFree(visual);
    // The renderer is built for one size: ask the window manager to keep it.
    XSizeHints hints{};
    hints.flags = PMinSize | PMaxSize;
    hints.min_width = hints.max_width = width;
    hints.min_height = hints.max_height = height;
    XSetWMNormalHints(x, window, &hints);
    XStoreName(x, window, title.c_str());
    deleteWindow = XInternAtom(x, "WM_DELETE_WINDOW", False);
    XSetWMProtocols(x, window, &deleteWindow, 1);
    XMapWindow(x, window);
    XFlush(x);
    // Draw only once the window is on screen: before that its contents are undefined.
    XEvent event;
    for (int i = 0; i < 400 && !XCheckTypedWindowEvent(x, window, MapNotify, &event); ++i)
        usleep(5000);

    auto createWindowSurface = reinterpret_cast<PFNEGLCREATEPLATFORMWINDOWSURFACEEXTPROC>(
        eglGetProcAddress("eglCreatePlatformWindowSurfaceEXT"));
    if (createWindowSurface == nullptr)
        fail("EGL: no eglCreatePlatformWindowSurfaceEXT");
    // For the X11 platform the native window is a pointer to the Window id.
    surface = createWindowSurface(egl->display(), egl->config(), &window, nullptr);
    if (surface == EGL_NO_SURFACE)
        fail(std::string("EGL: cannot create a window surface (") +
             EglContext::errorName(eglGetError()) + ")");
    if (!egl->makeCurrent(surface))
        fail(std::string("EGL: cannot make the context current (") +
             EglContext::errorName(eglGetError()) + ")");
    eglSwapInterval(egl->display(), 1);

    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    description = "window:" + std::to_string(width) + "x" + std::to_string(height) + " on " + name +
                  " (" + (renderer != nullptr ? renderer : "?") + ")";
}

void WindowDisplay::Impl::close() noexcept
{
    if (egl) {
        egl->releaseCurrent();
        if (surface != EGL_NO_SURFACE)
            eglDestroySurface(egl->display(), surface);
    }
    surface = EGL_NO_SURFACE;
    egl.reset();  // before the X connection it was opened on
    if (x != nullptr) {
        if (window != 0)
            XDestroyWindow(x, window);
        if (colormap != 0)
            XFreeColormap(x, colormap);
        XCloseDisplay(x);
    }
    x = nullptr;
    window = 0;
    colormap = 0;
}

void WindowDisplay::Impl::pollEvents() noexcept
{
    // Bounded, so a flood of events cannot stall the frame.
    for (int i = 0; i < 64 && XPending(x) > 0; ++i) {
        XEvent event;
        XNextEvent(x, &event);
        if (event.type == ClientMessage &&
            static_cast<Atom>(event.xclient.data.l[0]) == deleteWindow) {
            closed = true;
        } else if (event.type == KeyPress) {
            const KeySym sym = XLookupKeysym(&event.xkey, 0);
            const char* keyName = sym != NoSymbol ? XKeysymToString(sym) : nullptr;
            if (keyName == nullptr)
                continue;
            if (keyCount == keys.size()) {  // drop the oldest
                keyHead = (keyHead + 1) % keys.size();
                --keyCount;
            }
            KeyEvent& slot = keys[(keyHead + keyCount) % keys.size()];
            std::snprintf(slot.name, sizeof slot.name, "%s", keyName);
            ++keyCount;
        }
    }
}

WindowDisplay::WindowDisplay(int width, int height, const std::string& title)
    : impl_(std::make_unique<Impl>())
{
    if (width < 16 || height < 16 || width > 16384 || height > 16384)
        Impl::fail("invalid size " + std::to_string(width) + "x" + std::to_string(height));
    impl_->width = width;
    impl_->height = height;
    try {
        impl_->open(title);
    } catch (...) {
        impl_->close();
        throw;
    }
}

WindowDisplay::~WindowDisplay()
{
    impl_->close();
}

const char* WindowDisplay::description() const noexcept
{
    return impl_->description.c_str();
}

int WindowDisplay::width() const noexcept
{
    return impl_->width;
}

int WindowDisplay::height() const noexcept
{
    return impl_->height;
}

bool WindowDisplay::beginFrame() noexcept
{
    Impl& d = *impl_;
    d.inFrame = false;
    d.pollEvents();
    if (!d.egl->makeCurrent(d.surface)) {
        std::snprintf(d.error, sizeof d.error, "eglMakeCurrent failed (%s)",
                      EglContext::errorName(eglGetError()));
        return false;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, d.width, d.height);
    d.inFrame = true;
    return true;
}

bool WindowDisplay::present() noexcept
{
    Impl& d = *impl_;
    if (!d.inFrame) {
        std::snprintf(d.error, sizeof d.error, "present() without a successful beginFrame()");
        return false;
    }
    d.inFrame = false;
    if (!eglSwapBuffers(d.egl->display(), d.surface)) {
        std::snprintf(d.error, sizeof d.error, "eglSwapBuffers failed (%s)",
                      EglContext::errorName(eglGetError()));
        return false;
    }
    return true;
}

const char* WindowDisplay::lastError() const noexcept
{
    return impl_->error;
}

bool WindowDisplay::nextKey(KeyEvent& out) noexcept
{
    Impl& d = *impl_;
    if (d.keyCount == 0)
        return false;
    out = d.keys[d.keyHead];
    d.keyHead = (d.keyHead + 1) % d.keys.size();
    --d.keyCount;
    return true;
}

bool WindowDisplay::closeRequested() const noexcept
{
    return impl_->closed;
}

unsigned long WindowDisplay::windowId() const noexcept
{
    return impl_->window;
}

bool windowDisplayAvailable() noexcept
{
    const char* name = std::getenv("DISPLAY");
    if (name == nullptr || *name == '\0')
        return false;
    ::Display* x = XOpenDisplay(name);
    if (x == nullptr)
        return false;
    XCloseDisplay(x);
    return true;
}

}  // namespace platform
