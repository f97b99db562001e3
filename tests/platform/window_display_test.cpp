// WindowDisplay on a real X server: draws, swaps and delivers key presses. Skips where there is
// no X display; run it under Xvfb with `xvfb-run -a bin/window_display_test`.

#include "platform/window_display.hpp"

#include <GLES2/gl2.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

// Xlib last: its macros (None, Bool, Status) break gtest's headers.
#include <X11/Xlib.h>
#include <X11/keysym.h>

namespace {

TEST(WindowDisplay, NoDisplayIsOneClearLine)
{
    const char* saved = std::getenv("DISPLAY");
    const std::string keep = saved ? saved : "";
    unsetenv("DISPLAY");
    try {
        platform::WindowDisplay display(320, 240);
        ADD_FAILURE() << "opened a window without $DISPLAY";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "window: no X display ($DISPLAY is not set)");
    }
    EXPECT_FALSE(platform::windowDisplayAvailable());
    if (saved)
        setenv("DISPLAY", keep.c_str(), 1);
}

TEST(WindowDisplay, DrawsAndDeliversKeys)
{
    if (!platform::windowDisplayAvailable())
        GTEST_SKIP() << "no X display (run under xvfb-run)";
    platform::WindowDisplay display(320, 240, "mirror test");
    EXPECT_EQ(display.width(), 320);
    EXPECT_NE(std::string(display.description()).find("window:320x240 on "), std::string::npos)
        << display.description();

    ASSERT_TRUE(display.beginFrame()) << display.lastError();
    glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    std::vector<unsigned char> pixel(4);
    glReadPixels(160, 120, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel.data());
    EXPECT_EQ(pixel[0], 0);
    EXPECT_EQ(pixel[1], 255);
    ASSERT_TRUE(display.present()) << display.lastError();

    // Two key presses sent to the window as the X server would deliver them.
    ::Display* x = XOpenDisplay(nullptr);
    ASSERT_NE(x, nullptr);
    for (const KeySym sym : {XK_q, XK_space}) {
        XEvent event{};
        event.xkey.type = KeyPress;
        event.xkey.display = x;
        event.xkey.window = display.windowId();
        event.xkey.root = DefaultRootWindow(x);
        event.xkey.keycode = XKeysymToKeycode(x, sym);
        event.xkey.same_screen = True;
        XSendEvent(x, display.windowId(), True, KeyPressMask, &event);
    }
    XSync(x, False);
    XCloseDisplay(x);

    std::vector<std::string> names;
    for (int frame = 0; frame < 50 && names.size() < 2; ++frame) {
        ASSERT_TRUE(display.beginFrame()) << display.lastError();
        glClear(GL_COLOR_BUFFER_BIT);
        ASSERT_TRUE(display.present()) << display.lastError();
        platform::KeyEvent key;
        while (display.nextKey(key))
            names.emplace_back(key.name);
    }
    EXPECT_EQ(names, (std::vector<std::string>{"q", "space"}));
    EXPECT_FALSE(display.closeRequested());
}

}  // namespace
