#pragma once
// WindowDisplay: a window on an X11 desktop (EGL + GLES2), for development, with key events.

#include "platform/display.hpp"

#include <memory>
#include <string>

namespace platform {

/// \class WindowDisplay
/// A fixed-size X11 window with an EGL window surface (EGL_PLATFORM_X11_KHR) and a GLES2 context
/// (EglContext), swapped with vsync. Works on an X server and on XWayland. The constructor throws
/// std::runtime_error with one line ("window: ...") when there is no display ($DISPLAY unset or
/// the server refuses), no EGL on it, or no matching visual.
///
/// Events are read without blocking in beginFrame(): key presses go into a ring of 32 (the oldest
/// are dropped when nobody reads them), and closing the window sets closeRequested(). The firmware
/// maps key names to its actions. Like HeadlessDisplay, the renderer draws between beginFrame()
/// and present() on the same thread into the bound framebuffer (0, the window) with the viewport
/// set. Xlib may allocate while it reads events; our code does not.
class WindowDisplay final : public Display {
public:
    WindowDisplay(int width, int height, const std::string& title = "mirror");
    ~WindowDisplay() override;

    /// E.g. "window:1280x720 on :0 (llvmpipe)".
    const char* description() const noexcept override;
    int width() const noexcept override;
    int height() const noexcept override;
    bool beginFrame() noexcept override;
    bool present() noexcept override;
    const char* lastError() const noexcept override;

    /// Takes the oldest unread key press; false when there is none.
    bool nextKey(KeyEvent& out) noexcept override;
    /// The user closed the window (the window manager's close button).
    bool closeRequested() const noexcept override;
    /// The X window id (tests send it key events).
    unsigned long windowId() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// True when $DISPLAY names an X server that accepts a connection.
bool windowDisplayAvailable() noexcept;

}  // namespace platform
