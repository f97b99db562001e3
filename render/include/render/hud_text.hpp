#pragma once
// HudText: a few lines of diagnostics text (fps, tracking state) in the top-left corner of the
// viewport, white on a translucent dark box, in a built-in 5x8 bitmap font. The text is laid out
// in viewport pixels, never through the mirrored image mapping, so it always reads left to right.

#include <memory>

namespace render {

class HudText {
public:
    static constexpr int kMaxLines = 8;     ///< further lines are dropped
    static constexpr int kMaxColumns = 60;  ///< characters per line; the rest of a line is cut

    /// Where draw() puts the text, in viewport pixels (origin top-left, y down).
    struct Layout {
        int scale = 1;    ///< screen pixels per font pixel (integer, so glyphs stay crisp)
        int lines = 0;    ///< lines drawn (after truncation); 0 means nothing is drawn
        int columns = 0;  ///< characters in the longest drawn line
        int boxX = 0;     ///< the translucent box
        int boxY = 0;
        int boxWidth = 0;
        int boxHeight = 0;
        int textX = 0;  ///< top-left of the first character cell
        int textY = 0;
        int cellWidth = 0;   ///< advance from one character to the next
        int cellHeight = 0;  ///< advance from one line to the next
        int glyphWidth =
            0;  ///< lit area of a cell: glyphWidth x glyphHeight at the cell's top-left
        int glyphHeight = 0;
    };

    /// The layout of `text` (lines split at '\n'; a final '\n' adds no line) on a viewport of this
    /// height: one text line is about 2.5% of the height.
    static Layout layout(const char* text, int viewportHeight) noexcept;
    /// The layout of a message centred on the viewport, at twice the HUD's size (the "camera
    /// unavailable" screen).
    static Layout centredLayout(const char* text, int viewportWidth, int viewportHeight) noexcept;

    /// Creates the font atlas, shaders and buffers. Needs a current GLES2 context; throws
    /// std::runtime_error with one line on failure.
    HudText();
    ~HudText();  ///< needs the context still current
    HudText(const HudText&) = delete;
    HudText& operator=(const HudText&) = delete;

    /// Draws `text` into the bound framebuffer, whose viewport the caller has set to
    /// viewportWidth x viewportHeight. Sets the blending it needs. Non-printable characters show
    /// as '?'. Never allocates; GL errors are left for the caller's glGetError().
    void draw(const char* text, int viewportWidth, int viewportHeight) noexcept;
    /// Draws `text` as laid out by centredLayout().
    void drawCentred(const char* text, int viewportWidth, int viewportHeight) noexcept;

private:
    void drawLayout(const char* text, const Layout& layout, int viewportWidth,
                    int viewportHeight) noexcept;
    struct Gl;  // GL objects and the vertex array; defined in hud_text.cpp (no GL header here)
    std::unique_ptr<Gl> gl_;
};

}  // namespace render
