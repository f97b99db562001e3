#include "render/card_picture_layer.hpp"

#include "gl_program.hpp"

#include <GLES2/gl2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace render {
namespace {

constexpr const char* kPictureVertexShader = R"(#version 100
attribute vec2 aCamera;     // camera pixel, vision convention (pixel centres at integers)
uniform vec4 uImageToNdc;   // LayerContext::imageToNdc
varying vec2 vCamera;
void main()
{
    vCamera = aCamera;
    vec2 image = aCamera + 0.5;  // LayerContext puts the image's edges at 0 and width
    gl_Position = vec4(uImageToNdc.x * image.x + uImageToNdc.y,
                       uImageToNdc.z * image.y + uImageToNdc.w, 0.0, 1.0);
}
)";

// highp where available: camera coordinates up to ~2000 through a projective map need it.
constexpr const char* kPictureFragmentShader = R"(#version 100
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif
uniform sampler2D uPicture;
uniform sampler2D uMask;
uniform mat3 uCameraToPicture;  // inverse homography: camera pixel -> homogeneous picture uv
uniform vec2 uMaskScale;        // 1 / camera size
uniform vec3 uEdges[4];         // quad edges: a x + b y + c = camera pixels inside the edge
uniform float uScreenPerCamera; // screen pixels per camera pixel
varying vec2 vCamera;
void main()
{
    // Edge coverage of this screen pixel: a half-pixel ramp across each quad edge, so the
    // picture's border is smooth at any scale.
    vec3 p = vec3(vCamera, 1.0);
    float inside = min(min(dot(uEdges[0], p), dot(uEdges[1], p)),
                       min(dot(uEdges[2], p), dot(uEdges[3], p)));
    float coverage = clamp(inside * uScreenPerCamera + 0.5, 0.0, 1.0);
    // The card-colour mask, linearly filtered: 0 where a hand covers the card, a ramp at edges.
    float alpha = coverage * texture2D(uMask, (vCamera + 0.5) * uMaskScale).r;
    if (alpha < 0.5 / 255.0)
        discard;
    vec3 q = uCameraToPicture * p;
    vec2 uv = clamp(q.xy / q.z, 0.0, 1.0);
    gl_FragColor = vec4(texture2D(uPicture, uv).rgb, alpha);
}
)";

constexpr const char* kOutlineVertexShader = R"(#version 100
attribute vec2 aPosition;  // NDC
void main()
{
    gl_Position = vec4(aPosition, 0.0, 1.0);
}
)";

constexpr const char* kOutlineFragmentShader = R"(#version 100
precision mediump float;
uniform vec4 uColor;
void main()
{
    gl_FragColor = uColor;
}
)";

// Outline colour: saturated yellow, rare on a card and readable over skin and room.
constexpr float kOutlineColor[4] = {1.0f, 0.85f, 0.0f, 0.9f};
// Picture textures are resampled to a power of two (GLES2 mipmaps need one) no larger than
// this: more than a card ever covers on a mirror-sized screen.
constexpr int kMaxPictureSide = 1024;
// Screen-aligned box around the quad, grown so the edge pixels are all rasterised; the shader
// decides which fragments are inside.
constexpr float kBoxMargin = 1.0f;
constexpr int kOutlineVertices = 4 * 6;  // two triangles per edge

std::string sizeText(int width, int height)
{
    return std::to_string(width) + "x" + std::to_string(height);
}

int nearestPowerOfTwo(int n, int limit)
{
    int p = 1;
    while (p < limit && p * 2 <= n)
        p *= 2;
    // Round up when n is nearer the next power (1000 -> 1024, not 512).
    if (p < limit && n - p > p * 2 - n)
        p *= 2;
    return p;
}

// One axis of a resampling filter: for each output sample, the input samples and weights.
// Downscaling averages the source footprint (box filter with fractional ends), upscaling
// interpolates linearly. Start-up only.
struct Taps {
    std::vector<int> first;           // first input index per output
    std::vector<int> count;           // inputs per output
    std::vector<float> weights;       // count[i] weights per output, concatenated
    std::vector<std::size_t> offset;  // where output i's weights start
};

Taps makeTaps(int in, int out)
{
    Taps t;
    const double scale = static_cast<double>(in) / out;
    for (int o = 0; o < out; ++o) {
        t.offset.push_back(t.weights.size());
        if (scale > 1.0) {
            const double begin = o * scale;
            const double end = begin + scale;
            const int first = static_cast<int>(std::floor(begin));
            const int last = std::min(in - 1, static_cast<int>(std::ceil(end)) - 1);
            t.first.push_back(first);
            t.count.push_back(last - first + 1);
            for (int i = first; i <= last; ++i) {
                const double cover = std::min(end, i + 1.0) - std::max(begin, double(i));
                t.weights.push_back(static_cast<float>(cover / scale));
            }
        } else {
            const double centre = std::clamp((o + 0.5) * scale - 0.5, 0.0, in - 1.0);
            const int first = std::min(static_cast<int>(centre), std::max(0, in - 2));
            const double frac = centre - first;
            t.first.push_back(first);
            t.count.push_back(in > 1 ? 2 : 1);
            t.weights.push_back(static_cast<float>(in > 1 ? 1.0 - frac : 1.0));
            if (in > 1)
                t.weights.push_back(static_cast<float>(frac));
        }
    }
    return t;
}

// Resamples an RGB24 view to a tight width x height RGB buffer. Row by row, so a large photo
// needs only two rows of floats besides the result.
std::vector<std::uint8_t> resample(const vision::ConstImageView& in, int width, int height)
{
    const Taps tx = makeTaps(in.width, width);
    const Taps ty = makeTaps(in.height, height);
    const auto rowFloats = static_cast<std::size_t>(width) * 3;
    std::vector<float> horizontal(rowFloats);
    std::vector<float> sum(rowFloats);
    std::vector<std::uint8_t> out(rowFloats * static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y) {
        std::fill(sum.begin(), sum.end(), 0.f);
        for (int k = 0; k < ty.count[y]; ++k) {
            const std::uint8_t* src = in.row(ty.first[y] + k);
            for (int x = 0; x < width; ++x) {
                float acc[3] = {0.f, 0.f, 0.f};
                for (int j = 0; j < tx.count[x]; ++j) {
                    const float w = tx.weights[tx.offset[x] + j];
                    const std::uint8_t* s = src + (tx.first[x] + j) * 3;
                    acc[0] += w * s[0];
                    acc[1] += w * s[1];
                    acc[2] += w * s[2];
                }
                std::copy(acc, acc + 3, horizontal.begin() + x * 3);
            }
            const float w = ty.weights[ty.offset[y] + k];
            for (std::size_t i = 0; i < rowFloats; ++i)
                sum[i] += w * horizontal[i];
        }
        std::uint8_t* dst = out.data() + rowFloats * static_cast<std::size_t>(y);
        for (std::size_t i = 0; i < rowFloats; ++i)
            dst[i] = static_cast<std::uint8_t>(std::clamp(std::lround(sum[i]), 0L, 255L));
    }
    return out;
}

void checkGl(const std::string& what, const char* step)
{
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        char code[16];
        std::snprintf(code, sizeof(code), "0x%04x", error);
        throw std::runtime_error(what + ": GL error " + code + " while " + step);
    }
}

bool convex(const vision::Quad& q) noexcept
{
    int sign = 0;
    for (int i = 0; i < 4; ++i) {
        const vision::Point2f a = q[static_cast<std::size_t>(i)];
        const vision::Point2f b = q[static_cast<std::size_t>((i + 1) % 4)];
        const vision::Point2f c = q[static_cast<std::size_t>((i + 2) % 4)];
        const double cross = (static_cast<double>(b.x) - a.x) * (static_cast<double>(c.y) - b.y) -
                             (static_cast<double>(b.y) - a.y) * (static_cast<double>(c.x) - b.x);
        if (!std::isfinite(cross) || cross == 0.0)
            return false;
        const int s = cross > 0.0 ? 1 : -1;
        if (sign != 0 && s != sign)
            return false;
        sign = s;
    }
    return true;
}

}  // namespace

struct CardPictureLayer::Gl {
    explicit Gl(bool outline)
        : program(outline ? detail::GlProgram("card outline", kOutlineVertexShader,
                                              kOutlineFragmentShader, {"aPosition"})
                          : detail::GlProgram("card picture", kPictureVertexShader,
                                              kPictureFragmentShader, {"aCamera"}))
    {
    }

    detail::GlProgram program;
    detail::GlTexture picture;
    detail::GlTexture mask;
    detail::GlBuffer vertices;
    // Uniform locations (-1 where the mode's program has no such uniform).
    GLint pictureUniform = -1;
    GLint maskUniform = -1;
    GLint cameraToPictureUniform = -1;
    GLint maskScaleUniform = -1;
    GLint imageToNdcUniform = -1;
    GLint edgesUniform = -1;
    GLint screenPerCameraUniform = -1;
    GLint colorUniform = -1;
    // The mask of the last update(), tight rows (GLES2 has no GL_UNPACK_ROW_LENGTH).
    std::unique_ptr<std::uint8_t[]> maskStaging;
    // Per-frame vertex data: picture box (4 x camera xy) or outline (24 x NDC xy).
    float vertexData[kOutlineVertices * 2] = {};
};

CardPictureLayer::CardPictureLayer(const vision::ConstImageView& picture, vision::Size cameraSize)
    : camera_(cameraSize), outline_(picture.empty())
{
    const std::string what = "card picture layer";
    if (cameraSize.width <= 0 || cameraSize.height <= 0)
        throw std::runtime_error(what + ": empty camera size " +
                                 sizeText(cameraSize.width, cameraSize.height));
    if (!outline_ && picture.format != vision::PixelFormat::RGB24)
        throw std::runtime_error(what + ": picture is " + vision::pixelFormatName(picture.format) +
                                 ", need RGB24");
    if (glGetString(GL_VERSION) == nullptr)
        throw std::runtime_error(what + ": no current GLES2 context");
    GLint maxTexture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    if (cameraSize.width > maxTexture || cameraSize.height > maxTexture)
        throw std::runtime_error(what + ": camera " +
                                 sizeText(cameraSize.width, cameraSize.height) +
                                 " larger than GL_MAX_TEXTURE_SIZE " + std::to_string(maxTexture));

    try {
        gl_ = std::make_unique<Gl>(outline_);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(what + ": " + e.what());
    }
    if (gl_->picture.id() == 0 || gl_->mask.id() == 0 || gl_->vertices.id() == 0)
        throw std::runtime_error(what + ": cannot create GL textures or buffer");

    glBindBuffer(GL_ARRAY_BUFFER, gl_->vertices.id());
    glBufferData(GL_ARRAY_BUFFER, sizeof(gl_->vertexData), nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    if (outline_) {
        gl_->colorUniform = gl_->program.uniform("uColor");
        checkGl(what, "creating the outline buffer");
        return;
    }

    gl_->pictureUniform = gl_->program.uniform("uPicture");
    gl_->maskUniform = gl_->program.uniform("uMask");
    gl_->cameraToPictureUniform = gl_->program.uniform("uCameraToPicture");
    gl_->maskScaleUniform = gl_->program.uniform("uMaskScale");
    gl_->imageToNdcUniform = gl_->program.uniform("uImageToNdc");
    gl_->edgesUniform = gl_->program.uniform("uEdges");
    gl_->screenPerCameraUniform = gl_->program.uniform("uScreenPerCamera");

    // The picture: resampled once to a power-of-two size so it can be mipmapped; a photo
    // shrunk onto a small card would otherwise shimmer as the card moves.
    const int textureWidth =
        nearestPowerOfTwo(picture.width, std::min(kMaxPictureSide, static_cast<int>(maxTexture)));
    const int textureHeight =
        nearestPowerOfTwo(picture.height, std::min(kMaxPictureSide, static_cast<int>(maxTexture)));
    const std::vector<std::uint8_t> pixels = resample(picture, textureWidth, textureHeight);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, gl_->picture.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, textureWidth, textureHeight, 0, GL_RGB, GL_UNSIGNED_BYTE,
                 pixels.data());
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    checkGl(what, "uploading the picture");

    // The mask: created once at the camera size, replaced per frame. Linear filtering turns its
    // 0/255 steps into a ramp: soft edges where the mask is the picture's alpha.
    const std::size_t maskBytes =
        static_cast<std::size_t>(cameraSize.width) * static_cast<std::size_t>(cameraSize.height);
    gl_->maskStaging = std::make_unique<std::uint8_t[]>(maskBytes);
    std::memset(gl_->maskStaging.get(), 0xFF, maskBytes);
    glBindTexture(GL_TEXTURE_2D, gl_->mask.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE, cameraSize.width, cameraSize.height, 0,
                 GL_LUMINANCE, GL_UNSIGNED_BYTE, gl_->maskStaging.get());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    checkGl(what, "creating the mask texture");
}

CardPictureLayer::~CardPictureLayer() = default;

bool CardPictureLayer::unitSquareToQuadInverse(const vision::Quad& quad, float inverse[9]) noexcept
{
    // Heckbert's square-to-quad projective map (1989): x = (a u + b v + c) / (g u + h v + 1),
    // y = (d u + e v + f) / (g u + h v + 1), with (0,0), (1,0), (1,1), (0,1) -> corners 0..3.
    const double x0 = quad[0].x, y0 = quad[0].y, x1 = quad[1].x, y1 = quad[1].y;
    const double x2 = quad[2].x, y2 = quad[2].y, x3 = quad[3].x, y3 = quad[3].y;
    const double sx = x0 - x1 + x2 - x3;
    const double sy = y0 - y1 + y2 - y3;
    const double dx1 = x1 - x2, dx2 = x3 - x2, dy1 = y1 - y2, dy2 = y3 - y2;
    const double den = dx1 * dy2 - dx2 * dy1;
    if (!std::isfinite(den) || den == 0.0)
        return false;
    const double g = (sx * dy2 - dx2 * sy) / den;
    const double h = (dx1 * sy - sx * dy1) / den;
    const double m[3][3] = {{x1 - x0 + g * x1, x3 - x0 + h * x3, x0},
                            {y1 - y0 + g * y1, y3 - y0 + h * y3, y0},
                            {g, h, 1.0}};
    // The inverse up to scale is the adjugate (homogeneous: the scale does not matter).
    double adj[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            // adj[r][c] = cofactor of m[c][r]
            const int r0 = (c + 1) % 3, r1 = (c + 2) % 3, c0 = (r + 1) % 3, c1 = (r + 2) % 3;
            adj[r][c] = m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
        }
    const double det = m[0][0] * adj[0][0] + m[0][1] * adj[1][0] + m[0][2] * adj[2][0];
    double largest = 0.0;
    for (const auto& row : adj)
        for (double v : row)
            largest = std::max(largest, std::fabs(v));
    if (!std::isfinite(det) || det == 0.0 || !std::isfinite(largest) || largest == 0.0)
        return false;
    // Normalised so float keeps the precision, with the sign making w > 0 inside the quad.
    const double scale = (det > 0.0 ? 1.0 : -1.0) / largest;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            inverse[r * 3 + c] = static_cast<float>(adj[r][c] * scale);
    return true;
}

void CardPictureLayer::update(const vision::CardObservation* card) noexcept
{
    lastError_[0] = '\0';
    visible_ = card != nullptr && card->hasQuad && card->state == vision::CardState::Tracking &&
               convex(card->quad) && unitSquareToQuadInverse(card->quad, inverseHomography_);
    if (!visible_)
        return;
    quad_ = card->quad;
    // Edge lines with unit normals pointing inwards (either winding), for the shader's coverage.
    float cx = 0.f, cy = 0.f;
    for (const vision::Point2f& p : quad_) {
        cx += 0.25f * p.x;
        cy += 0.25f * p.y;
    }
    for (std::size_t i = 0; i < 4; ++i) {
        const vision::Point2f a = quad_[i];
        const vision::Point2f b = quad_[(i + 1) % 4];
        float nx = a.y - b.y;
        float ny = b.x - a.x;
        const float length = std::sqrt(nx * nx + ny * ny);  // > 0: convex() saw no repeated corner
        nx /= length;
        ny /= length;
        float c = -(nx * a.x + ny * a.y);
        if (nx * cx + ny * cy + c < 0.f) {
            nx = -nx;
            ny = -ny;
            c = -c;
        }
        edges_[i * 3] = nx;
        edges_[i * 3 + 1] = ny;
        edges_[i * 3 + 2] = c;
    }
    if (outline_)
        return;

    const vision::ConstImageView& mask = card->mask;
    std::uint8_t* staging = gl_->maskStaging.get();
    const auto width = static_cast<std::size_t>(camera_.width);
    if (mask.empty() || mask.format != vision::PixelFormat::Gray8 || mask.size() != camera_ ||
        static_cast<std::size_t>(mask.stride) < width) {
        if (!mask.empty())
            std::snprintf(lastError_, sizeof(lastError_),
                          "mask %dx%d %s does not match the camera %dx%d GRAY8; not used",
                          mask.width, mask.height, vision::pixelFormatName(mask.format),
                          camera_.width, camera_.height);
        else
            std::snprintf(lastError_, sizeof(lastError_), "no mask; picture not occluded");
        std::memset(staging, 0xFF, width * static_cast<std::size_t>(camera_.height));
    } else {
        for (int y = 0; y < camera_.height; ++y)
            std::memcpy(staging + width * static_cast<std::size_t>(y), mask.row(y), width);
    }
    maskDirty_ = true;
}

void CardPictureLayer::draw(const LayerContext& context) noexcept
{
    if (!visible_)
        return;
    float* v = gl_->vertexData;
    const auto stride = static_cast<GLsizei>(2 * sizeof(float));
    glUseProgram(gl_->program.id());
    glBindBuffer(GL_ARRAY_BUFFER, gl_->vertices.id());

    if (outline_) {
        // Each edge as a band of constant screen width: corners to viewport pixels, offset
        // along the edge normal (and past the ends, so the corners close), back to NDC.
        const float halfWidth =
            0.5f * static_cast<float>(std::max(2, context.viewportHeight / 200));
        const float sx = 0.5f * static_cast<float>(context.viewportWidth);
        const float sy = 0.5f * static_cast<float>(context.viewportHeight);
        float px[4];
        float py[4];
        for (std::size_t i = 0; i < 4; ++i) {
            px[i] = (context.imageToNdc[0] * (quad_[i].x + 0.5f) + context.imageToNdc[1]) * sx;
            py[i] = (context.imageToNdc[2] * (quad_[i].y + 0.5f) + context.imageToNdc[3]) * sy;
        }
        for (std::size_t i = 0; i < 4; ++i) {
            const std::size_t j = (i + 1) % 4;
            float dx = px[j] - px[i];
            float dy = py[j] - py[i];
            const float length = std::sqrt(dx * dx + dy * dy);
            if (length > 0.f) {
                dx = dx / length * halfWidth;
                dy = dy / length * halfWidth;
            }
            // (dx, dy) along the edge, (-dy, dx) across it, both halfWidth long.
            const float ax = px[i] - dx, ay = py[i] - dy, bx = px[j] + dx, by = py[j] + dy;
            const float corners[4][2] = {
                {ax - dy, ay + dx}, {ax + dy, ay - dx}, {bx - dy, by + dx}, {bx + dy, by - dx}};
            const int order[6] = {0, 1, 2, 2, 1, 3};
            for (int k : order) {
                *v++ = corners[k][0] / sx;
                *v++ = corners[k][1] / sy;
            }
        }
        glUniform4fv(gl_->colorUniform, 1, kOutlineColor);
        glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof(gl_->vertexData), gl_->vertexData);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, nullptr);
        glEnableVertexAttribArray(0);
        glDrawArrays(GL_TRIANGLES, 0, kOutlineVertices);
        glDisableVertexAttribArray(0);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        return;
    }

    // The screen-aligned bounding box of the quad in camera coordinates (mirroring keeps it
    // screen-aligned); the fragment shader cuts out the quad itself.
    float minX = quad_[0].x, maxX = quad_[0].x, minY = quad_[0].y, maxY = quad_[0].y;
    for (const vision::Point2f& p : quad_) {
        minX = std::min(minX, p.x);
        maxX = std::max(maxX, p.x);
        minY = std::min(minY, p.y);
        maxY = std::max(maxY, p.y);
    }
    minX -= kBoxMargin;
    minY -= kBoxMargin;
    maxX += kBoxMargin;
    maxY += kBoxMargin;
    const float box[4][2] = {{minX, minY}, {maxX, minY}, {minX, maxY}, {maxX, maxY}};
    for (const auto& corner : box) {
        *v++ = corner[0];
        *v++ = corner[1];
    }

    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, gl_->mask.id());
    if (maskDirty_) {
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, camera_.width, camera_.height, GL_LUMINANCE,
                        GL_UNSIGNED_BYTE, gl_->maskStaging.get());
        maskDirty_ = false;
    }
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, gl_->picture.id());

    // In a mirror the card's picture must still read the right way round to the person holding
    // it (text on it is not reversed), so when the video is mirrored the picture's u is flipped:
    // rows of F * H^-1 with F = [[-1 0 1] [0 1 0] [0 0 1]], i.e. u' = w - u in homogeneous terms.
    float m[9];
    for (int i = 0; i < 9; ++i)
        m[i] = inverseHomography_[i];
    if (context.mirrored)
        for (int c = 0; c < 3; ++c)
            m[c] = m[6 + c] - m[c];
    // GLES2 takes matrices column-major only (transpose must be GL_FALSE).
    float columnMajor[9];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            columnMajor[c * 3 + r] = m[r * 3 + c];
    glUniform1i(gl_->pictureUniform, 0);
    glUniform1i(gl_->maskUniform, 1);
    glUniformMatrix3fv(gl_->cameraToPictureUniform, 1, GL_FALSE, columnMajor);
    glUniform2f(gl_->maskScaleUniform, 1.0f / static_cast<float>(camera_.width),
                1.0f / static_cast<float>(camera_.height));
    glUniform4fv(gl_->imageToNdcUniform, 1, context.imageToNdc);
    glUniform3fv(gl_->edgesUniform, 4, edges_);
    glUniform1f(gl_->screenPerCameraUniform, std::fabs(context.imageToNdc[0]) * 0.5f *
                                                 static_cast<float>(context.viewportWidth));
    glBufferSubData(GL_ARRAY_BUFFER, 0, 4 * 2 * sizeof(float), gl_->vertexData);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(0);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace render
