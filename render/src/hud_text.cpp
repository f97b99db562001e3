#include "render/hud_text.hpp"

#include "gl_program.hpp"
#include "hud_font.hpp"

#include <GLES2/gl2.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace render {
namespace {

using detail::kGlyphCount;
using detail::kGlyphHeight;
using detail::kGlyphWidth;

// Layout in font pixels (times Layout::scale on screen).
constexpr int kCellWidth = kGlyphWidth + 1;    // one pixel between characters
constexpr int kCellHeight = kGlyphHeight + 1;  // one pixel between lines
constexpr int kMargin = 4;                     // viewport corner to box
constexpr int kPadding = 3;                    // box edge to text
// One text line (kCellHeight font pixels) is about 2.5% of the viewport height: h / 360.
constexpr int kViewportHeightPerScale = kCellHeight * 40;

// Font atlas: kAtlasColumns x kAtlasRows cells of 8x8 texels; glyph i sits at the top-left of
// cell i; the cell after the last glyph is solid, and the box samples it so box and text are
// one draw call.
constexpr int kAtlasCell = 8;
constexpr int kAtlasColumns = 16;
constexpr int kSolidCell = kGlyphCount;
constexpr int kAtlasRows = (kSolidCell + kAtlasColumns) / kAtlasColumns;
constexpr int kAtlasWidth = kAtlasColumns * kAtlasCell;
constexpr int kAtlasHeight = kAtlasRows * kAtlasCell;
static_assert(kGlyphWidth <= kAtlasCell && kGlyphHeight <= kAtlasCell);

constexpr int kMaxQuads = HudText::kMaxLines * HudText::kMaxColumns + 1;  // glyphs + the box
constexpr int kFloatsPerVertex = 8;                                       // x, y, s, t, r, g, b, a
constexpr std::size_t kVertexBytes = kFloatsPerVertex * sizeof(float);
static_assert(kMaxQuads * 4 <= 65536, "indices are GLushort");

constexpr float kBoxColor[4] = {0.f, 0.f, 0.f, 0.6f};
constexpr float kTextColor[4] = {1.f, 1.f, 1.f, 1.f};

constexpr const char* kVertexShader = R"(#version 100
attribute vec2 aPosition;  // viewport pixels, origin top-left, y down
attribute vec2 aTexCoord;
attribute vec4 aColor;
uniform vec2 uViewport;
varying vec2 vTexCoord;
varying vec4 vColor;
void main()
{
    vTexCoord = aTexCoord;
    vColor = aColor;
    vec2 ndc = aPosition / uViewport * 2.0 - 1.0;
    gl_Position = vec4(ndc.x, -ndc.y, 0.0, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 100
precision mediump float;
uniform sampler2D uFont;
varying vec2 vTexCoord;
varying vec4 vColor;
void main()
{
    gl_FragColor = vec4(vColor.rgb, vColor.a * texture2D(uFont, vTexCoord).r);
}
)";

struct Extent {
    int lines = 0;
    int columns = 0;
};

// Calls visit(line, column, c) for every character kept after truncation; '\n' ends a line
// (so "a\n\nb" has three lines, "a\n" one). The single place that decides what is drawn.
template <typename Visit>
Extent forEachCharacter(const char* text, Visit&& visit) noexcept
{
    Extent extent;
    int column = 0;
    for (const char* p = text; p != nullptr && *p != '\0'; ++p) {
        if (*p == '\n') {
            extent.columns = std::max(extent.columns, column);
            column = 0;
            if (++extent.lines == HudText::kMaxLines)
                return extent;
            continue;
        }
        if (column < HudText::kMaxColumns)
            visit(extent.lines, column++, *p);
    }
    if (column > 0) {
        extent.columns = std::max(extent.columns, column);
        ++extent.lines;
    }
    return extent;
}

int atlasIndex(char c) noexcept
{
    return (c >= detail::kFirstGlyph && c <= detail::kLastGlyph) ? c - detail::kFirstGlyph
                                                                 : '?' - detail::kFirstGlyph;
}

// Writes one quad as four vertices: top-left, top-right, bottom-left, bottom-right.
float* putQuad(float* v, float x0, float y0, float x1, float y1, float s0, float t0, float s1,
               float t1, const float (&color)[4]) noexcept
{
    const float corners[4][4] = {
        {x0, y0, s0, t0}, {x1, y0, s1, t0}, {x0, y1, s0, t1}, {x1, y1, s1, t1}};
    for (const auto& corner : corners) {
        for (float f : corner)
            *v++ = f;
        for (float f : color)
            *v++ = f;
    }
    return v;
}

}  // namespace

struct HudText::Gl {
    detail::GlProgram program{
        "HUD text", kVertexShader, kFragmentShader, {"aPosition", "aTexCoord", "aColor"}};
    GLint viewportUniform = program.uniform("uViewport");
    GLint fontUniform = program.uniform("uFont");
    detail::GlTexture font;
    detail::GlBuffer vertexBuffer;
    detail::GlBuffer indexBuffer;
    std::array<float, kMaxQuads * 4 * kFloatsPerVertex> vertices{};
};

HudText::Layout HudText::layout(const char* text, int viewportHeight) noexcept
{
    Layout l;
    l.scale = std::max(1, (viewportHeight + kViewportHeightPerScale / 2) / kViewportHeightPerScale);
    const Extent extent = forEachCharacter(text, [](int, int, char) {});
    l.lines = extent.lines;
    l.columns = extent.columns;
    l.cellWidth = kCellWidth * l.scale;
    l.cellHeight = kCellHeight * l.scale;
    l.glyphWidth = kGlyphWidth * l.scale;
    l.glyphHeight = kGlyphHeight * l.scale;
    l.boxX = kMargin * l.scale;
    l.boxY = kMargin * l.scale;
    l.textX = l.boxX + kPadding * l.scale;
    l.textY = l.boxY + kPadding * l.scale;
    if (l.lines > 0) {
        // The last cell's trailing gap pixel is not needed inside the box.
        l.boxWidth = std::max(0, l.columns * l.cellWidth - l.scale) + 2 * kPadding * l.scale;
        l.boxHeight = l.lines * l.cellHeight - l.scale + 2 * kPadding * l.scale;
    }
    return l;
}

HudText::Layout HudText::centredLayout(const char* text, int viewportWidth,
                                       int viewportHeight) noexcept
{
    Layout l = layout(text, viewportHeight * 2);
    const int dx = (viewportWidth - l.boxWidth) / 2 - l.boxX;
    const int dy = (viewportHeight - l.boxHeight) / 2 - l.boxY;
    l.boxX += dx;
    l.boxY += dy;
    l.textX += dx;
    l.textY += dy;
    return l;
}

HudText::HudText()
{
    if (glGetString(GL_VERSION) == nullptr)
        throw std::runtime_error("HUD text: no current GLES2 context");
    gl_ = std::make_unique<Gl>();
    if (gl_->font.id() == 0 || gl_->vertexBuffer.id() == 0 || gl_->indexBuffer.id() == 0)
        throw std::runtime_error("HUD text: cannot create GL texture or buffers");

    std::vector<std::uint8_t> atlas(static_cast<std::size_t>(kAtlasWidth) * kAtlasHeight, 0);
    const auto texel = [&](int x, int y) -> std::uint8_t& {
        return atlas[static_cast<std::size_t>(y) * kAtlasWidth + static_cast<std::size_t>(x)];
    };
    for (int g = 0; g < kGlyphCount; ++g) {
        const std::uint8_t* rows = detail::glyphRows(static_cast<char>(detail::kFirstGlyph + g));
        const int cx = (g % kAtlasColumns) * kAtlasCell;
        const int cy = (g / kAtlasColumns) * kAtlasCell;
        for (int y = 0; y < kGlyphHeight; ++y)
            for (int x = 0; x < kGlyphWidth; ++x)
                if (rows[y] & (1u << (kGlyphWidth - 1 - x)))
                    texel(cx + x, cy + y) = 255;
    }
    for (int y = 0; y < kAtlasCell; ++y)
        for (int x = 0; x < kAtlasCell; ++x)
            texel((kSolidCell % kAtlasColumns) * kAtlasCell + x,
                  (kSolidCell / kAtlasColumns) * kAtlasCell + y) = 255;

    glBindTexture(GL_TEXTURE_2D, gl_->font.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE, kAtlasWidth, kAtlasHeight, 0, GL_LUMINANCE,
                 GL_UNSIGNED_BYTE, atlas.data());
    // NEAREST: glyphs are drawn at integer scales on whole pixels, so texels map exactly.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);

    std::vector<GLushort> indices(static_cast<std::size_t>(kMaxQuads) * 6);
    for (int q = 0; q < kMaxQuads; ++q) {
        const auto base = static_cast<GLushort>(q * 4);
        const GLushort quad[6] = {base,
                                  static_cast<GLushort>(base + 1),
                                  static_cast<GLushort>(base + 2),
                                  static_cast<GLushort>(base + 2),
                                  static_cast<GLushort>(base + 1),
                                  static_cast<GLushort>(base + 3)};
        std::copy(std::begin(quad), std::end(quad), indices.begin() + q * 6);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gl_->indexBuffer.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(indices.size() * sizeof(GLushort)), indices.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);

    glBindBuffer(GL_ARRAY_BUFFER, gl_->vertexBuffer.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(sizeof(gl_->vertices)), nullptr,
                 GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        char message[64];
        std::snprintf(message, sizeof(message), "HUD text: GL error 0x%04x while setting up",
                      error);
        throw std::runtime_error(message);
    }
}

HudText::~HudText() = default;

void HudText::draw(const char* text, int viewportWidth, int viewportHeight) noexcept
{
    drawLayout(text, layout(text, viewportHeight), viewportWidth, viewportHeight);
}

void HudText::drawCentred(const char* text, int viewportWidth, int viewportHeight) noexcept
{
    drawLayout(text, centredLayout(text, viewportWidth, viewportHeight), viewportWidth,
               viewportHeight);
}

void HudText::drawLayout(const char* text, const Layout& l, int viewportWidth,
                         int viewportHeight) noexcept
{
    if (l.lines == 0 || viewportWidth <= 0 || viewportHeight <= 0)
        return;

    constexpr float kSolidS = ((kSolidCell % kAtlasColumns) * kAtlasCell + kAtlasCell / 2) /
                              static_cast<float>(kAtlasWidth);
    constexpr float kSolidT = ((kSolidCell / kAtlasColumns) * kAtlasCell + kAtlasCell / 2) /
                              static_cast<float>(kAtlasHeight);
    float* v = gl_->vertices.data();
    v = putQuad(v, static_cast<float>(l.boxX), static_cast<float>(l.boxY),
                static_cast<float>(l.boxX + l.boxWidth), static_cast<float>(l.boxY + l.boxHeight),
                kSolidS, kSolidT, kSolidS, kSolidT, kBoxColor);
    int quads = 1;
    forEachCharacter(text, [&](int line, int column, char c) {
        if (c == ' ')
            return;
        const int index = atlasIndex(c);
        const float s0 = static_cast<float>((index % kAtlasColumns) * kAtlasCell) / kAtlasWidth;
        const float t0 = static_cast<float>((index / kAtlasColumns) * kAtlasCell) / kAtlasHeight;
        const float x0 = static_cast<float>(l.textX + column * l.cellWidth);
        const float y0 = static_cast<float>(l.textY + line * l.cellHeight);
        v = putQuad(v, x0, y0, x0 + static_cast<float>(l.glyphWidth),
                    y0 + static_cast<float>(l.glyphHeight), s0, t0,
                    s0 + static_cast<float>(kGlyphWidth) / kAtlasWidth,
                    t0 + static_cast<float>(kGlyphHeight) / kAtlasHeight, kTextColor);
        ++quads;
    });

    glUseProgram(gl_->program.id());
    glUniform2f(gl_->viewportUniform, static_cast<float>(viewportWidth),
                static_cast<float>(viewportHeight));
    glUniform1i(gl_->fontUniform, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, gl_->font.id());
    glBindBuffer(GL_ARRAY_BUFFER, gl_->vertexBuffer.id());
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(quads * 4 * kVertexBytes),
                    gl_->vertices.data());
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gl_->indexBuffer.id());
    const auto stride = static_cast<GLsizei>(kVertexBytes);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(0));
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(2 * sizeof(float)));
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(4 * sizeof(float)));
    for (GLuint a = 0; a < 3; ++a)
        glEnableVertexAttribArray(a);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDrawElements(GL_TRIANGLES, quads * 6, GL_UNSIGNED_SHORT, nullptr);
    for (GLuint a = 0; a < 3; ++a)
        glDisableVertexAttribArray(a);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace render
