#pragma once
// RotatedTarget: the renderer's picture turned for a panel mounted on its side or upside down.
// The whole picture (camera image, overlays, card picture, HUD, the calm screen) is drawn upright
// into an off-screen framebuffer of the turned size, then copied onto the display's framebuffer
// rotated: every layer follows without knowing about the rotation.

#include "gl_program.hpp"

namespace render::detail {

class RotatedTarget {
public:
    /// Needs a current GLES2 context; throws std::runtime_error with one line on failure.
    RotatedTarget();
    ~RotatedTarget();
    RotatedTarget(const RotatedTarget&) = delete;
    RotatedTarget& operator=(const RotatedTarget&) = delete;

    /// Remembers the bound framebuffer (the display's), binds the off-screen one sized for a
    /// `displayWidth` x `displayHeight` display turned by `degrees` (90, 180 or 270 clockwise) and
    /// gives the size to draw at. Storage is made on the first call and when the size changes.
    /// False on a GL error.
    bool begin(int degrees, int displayWidth, int displayHeight, int& drawWidth,
               int& drawHeight) noexcept;
    /// Copies the off-screen picture, turned, onto the display's framebuffer (bound again).
    void finish() noexcept;

private:
    bool allocate(int width, int height) noexcept;

    GlProgram program_;
    GLint pictureUniform_;
    GlTexture colour_;
    GlBuffer quad_;
    GLuint framebuffer_ = 0;
    GLuint depth_ = 0;
    int width_ = 0;
    int height_ = 0;
    int degrees_ = 0;
    int displayWidth_ = 0;
    int displayHeight_ = 0;
    GLint displayFramebuffer_ = 0;
};

/// Texture coordinates (u, v), GL's convention (v up), of the picture at display corner (x, y)
/// (0..1, y up) when the picture is turned `degrees` clockwise on the display.
void rotatedTexCoord(int degrees, float x, float y, float& u, float& v) noexcept;

}  // namespace render::detail
