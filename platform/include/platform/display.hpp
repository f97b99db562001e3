#pragma once
// Display: where rendered frames go (headless EGL now; later DRM/KMS and a desktop window).
// A display owns the GL context and the target framebuffer; it never draws content itself.

namespace platform {

/// One key pressed on a display that has a keyboard (the desktop window), named by its X keysym
/// ("q", "space", "Escape", "F1", "plus").
struct KeyEvent {
    char name[32] = {};
};

class Display {
public:
    virtual ~Display() = default;
    Display() = default;
    Display(const Display&) = delete;
    Display& operator=(const Display&) = delete;

    /// What this display is, e.g. "headless:out/demo (1280x720, llvmpipe)".
    virtual const char* description() const noexcept = 0;
    virtual int width() const noexcept = 0;
    virtual int height() const noexcept = 0;

    /// Makes the GL context current and binds the framebuffer to draw into. False when the display
    /// cannot take a frame now (lastError() says why); the caller skips drawing this frame.
    virtual bool beginFrame() noexcept = 0;
    /// Finishes the frame: flip, or read back. Writes a snapshot if one is due. False on failure.
    virtual bool present() noexcept = 0;

    /// Asks for a PNG snapshot of the next presented frame. False when this display cannot.
    virtual bool requestSnapshot() noexcept { return false; }
    /// Path of the last snapshot written, or "" when none.
    virtual const char* lastSnapshot() const noexcept { return ""; }
    /// Folder where this display writes its output (snapshots, summaries), or "" when none.
    virtual const char* outputDir() const noexcept { return ""; }
    virtual const char* lastError() const noexcept { return ""; }

    /// Takes the oldest unread key press on this display's own keyboard; false when there is none
    /// (always, for a display without one). The firmware maps key names to its actions.
    virtual bool nextKey(KeyEvent& /*out*/) noexcept { return false; }
    /// The user asked to close this display (a window manager's close button).
    virtual bool closeRequested() const noexcept { return false; }
};

}  // namespace platform
