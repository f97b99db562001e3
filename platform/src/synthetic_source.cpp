#include "platform/synthetic_source.hpp"

#include "noise_hash.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>

namespace platform {

namespace {

struct Rgb {
    int r, g, b;
};

inline std::uint8_t clampByte(double v) noexcept
{
    return static_cast<std::uint8_t>(std::clamp(v + 0.5, 0.0, 255.0));
}

inline double smoothstep(double e0, double e1, double x) noexcept
{
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

inline double mix(double a, double b, double t) noexcept
{
    return a + (b - a) * t;
}

/// Coverage (0..1) of a soft-edged axis-aligned rectangle in normalised coordinates.
inline double softRect(double u, double v, double u0, double v0, double u1, double v1,
                       double soft) noexcept
{
    return smoothstep(u0 - soft, u0 + soft, u) * (1.0 - smoothstep(u1 - soft, u1 + soft, u)) *
           smoothstep(v0 - soft, v0 + soft, v) * (1.0 - smoothstep(v1 - soft, v1 + soft, v));
}

/// Draws an anti-aliased filled ellipse (centre cx, cy; semi-axes a, b in pixels) blended with
/// `opacity`. Only the bounding box is visited; the edge coverage comes from the first-order
/// signed distance to the ellipse, which is exact enough for a one-pixel ramp. The surface is
/// darkened towards the rim by `shade` (a rounded look) and carries a +-3 texture that moves with
/// the shape, so objects are not flat either.
void fillEllipse(vision::ImageView img, double cx, double cy, double a, double b, Rgb c,
                 double opacity = 1.0, double shade = 0.18) noexcept
{
    a = std::max(a, 0.5);
    b = std::max(b, 0.5);
    const int x0 = std::max(0, static_cast<int>(std::floor(cx - a - 1.0)));
    const int x1 = std::min(img.width - 1, static_cast<int>(std::ceil(cx + a + 1.0)));
    const int y0 = std::max(0, static_cast<int>(std::floor(cy - b - 1.0)));
    const int y1 = std::min(img.height - 1, static_cast<int>(std::ceil(cy + b + 1.0)));
    const double ia = 1.0 / a;
    const double ib = 1.0 / b;
    const double ia2 = ia * ia;
    const double ib2 = ib * ib;
    // q = u^2 + v^2 below `inner` is fully covered, above `outer` not at all.
    const double m = 1.0 / std::min(a, b);
    const double inner = (1.0 - m) > 0.0 ? (1.0 - m) * (1.0 - m) : 0.0;
    const double outer = (1.0 + m) * (1.0 + m);
    const int full = static_cast<int>(std::lround(opacity * 256.0));
    const long ox = std::lround(cx);
    const long oy = std::lround(cy);
    for (int y = y0; y <= y1; ++y) {
        std::uint8_t* p = img.row(y) + 3 * x0;
        const double v = (y - cy) * ib;
        for (int x = x0; x <= x1; ++x, p += 3) {
            const double u = (x - cx) * ia;
            const double q = u * u + v * v;
            if (q >= outer)
                continue;
            int alpha = full;
            if (q > inner) {
                const double d = std::sqrt(q);
                const double grad = std::sqrt(u * u * ia2 + v * v * ib2);
                const double sd = (d - 1.0) * d / std::max(grad, 1e-12);
                const double cov = std::clamp(0.5 - sd, 0.0, 1.0);
                alpha = static_cast<int>(cov * full + 0.5);
                if (alpha == 0)
                    continue;
            }
            const int light = 256 - static_cast<int>(shade * std::min(q, 1.0) * 256.0);
            const int tex = static_cast<int>(noiseHash(static_cast<std::uint32_t>(x - ox),
                                                       static_cast<std::uint32_t>(y - oy)) %
                                             7u) -
                            3;
            const int r = std::clamp(((c.r * light) >> 8) + tex, 0, 255);
            const int g = std::clamp(((c.g * light) >> 8) + tex, 0, 255);
            const int bl = std::clamp(((c.b * light) >> 8) + tex, 0, 255);
            p[0] = static_cast<std::uint8_t>(p[0] + (((r - p[0]) * alpha) >> 8));
            p[1] = static_cast<std::uint8_t>(p[1] + (((g - p[1]) * alpha) >> 8));
            p[2] = static_cast<std::uint8_t>(p[2] + (((bl - p[2]) * alpha) >> 8));
        }
    }
}

constexpr double kTwoPi = 2.0 * std::numbers::pi;

}  // namespace

SyntheticSource::SyntheticSource(int width, int height, double fps, PacerClock& clock)
    : width_(width), height_(height), pacer_(fps, clock)
{
    if (width < 16 || height < 16 || width > 16384 || height > 16384)
        throw std::runtime_error("synthetic: size " + std::to_string(width) + "x" +
                                 std::to_string(height) + " out of range (16..16384)");
    if (!std::isfinite(fps) || fps < 0.0)
        throw std::runtime_error("synthetic: fps " + std::to_string(fps) +
                                 " invalid (0 = as fast as possible, or > 0)");
    background_ = vision::ImageBuffer(width, height, vision::PixelFormat::RGB24);
    frame_ = vision::ImageBuffer(width, height, vision::PixelFormat::RGB24);
    renderBackground();
    if (fps > 0.0)
        std::snprintf(description_, sizeof description_, "synthetic (%dx%d RGB24, %g fps)", width,
                      height, fps);
    else
        std::snprintf(description_, sizeof description_, "synthetic (%dx%d RGB24, max rate)", width,
                      height);
}

void SyntheticSource::renderBackground() noexcept
{
    const vision::ImageView img = background_.view();
    const double w = width_;
    const double h = height_;
    const double soft = 6.0 / h;  // edges of the static shapes blur over ~12 pixels
    for (int y = 0; y < height_; ++y) {
        std::uint8_t* p = img.row(y);
        const double v = y / h;
        for (int x = 0; x < width_; ++x, p += 3) {
            const double u = x / w;
            // Warm wall, darker towards the floor, with a faint woven wallpaper texture.
            const double weave = 7.0 * std::sin(kTwoPi * (u * 9.0 + v * 3.0)) *
                                 std::sin(kTwoPi * (v * 11.0 - u * 2.0));
            double r = 160.0 - 45.0 * v + 25.0 * u + weave;
            double g = 148.0 - 40.0 * v + 10.0 * u + weave;
            double b = 128.0 - 25.0 * v - 15.0 * u + 0.6 * weave;
            // Lamp glow near the ceiling.
            const double du = (u - 0.58) * w / h;
            const double dv = v - 0.08;
            const double glow = 60.0 * std::exp(-(du * du + dv * dv) / 0.02);
            r += glow;
            g += glow * 0.95;
            b += glow * 0.75;
            // Window on the left: bright sky, brighter at the top.
            const double win = softRect(u, v, 0.05, 0.08, 0.30, 0.46, soft);
            r = mix(r, 190.0 + 30.0 * (0.46 - v), win);
            g = mix(g, 210.0 + 25.0 * (0.46 - v), win);
            b = mix(b, 235.0 + 15.0 * (0.46 - v), win);
            // Dark wooden cupboard on the right, with vertical grain.
            const double cup = softRect(u, v, 0.76, 0.18, 0.96, 1.10, soft);
            const double grain = 6.0 * std::sin(kTwoPi * u * 60.0 + 3.0 * std::sin(kTwoPi * v * 4));
            r = mix(r, 92.0 + grain, cup);
            g = mix(g, 64.0 + grain * 0.8, cup);
            b = mix(b, 46.0 + grain * 0.6, cup);
            // Floor below the skirting line.
            const double floor = smoothstep(0.82 - soft, 0.82 + soft, v);
            r = mix(r, 120.0 - 30.0 * (v - 0.82), floor);
            g = mix(g, 100.0 - 30.0 * (v - 0.82), floor);
            b = mix(b, 82.0 - 25.0 * (v - 0.82), floor);
            // Fine sensor-like noise, +-4.
            const double n =
                static_cast<double>(
                    noiseHash(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)) % 9u) -
                4.0;
            p[0] = clampByte(r + n);
            p[1] = clampByte(g + n);
            p[2] = clampByte(b + n);
        }
    }
}

bool SyntheticSource::renderFrame(std::uint64_t index, vision::ImageView out) const noexcept
{
    if (out.data == nullptr || out.width != width_ || out.height != height_ ||
        out.format != vision::PixelFormat::RGB24)
        return false;
    const vision::ConstImageView bg = background_.view();
    const std::size_t rowBytes = static_cast<std::size_t>(width_) * 3;
    for (int y = 0; y < height_; ++y)
        std::memcpy(out.row(y), bg.row(y), rowBytes);

    const double t = sceneTime(index);
    const double w = width_;
    const double h = height_;

    // Two discs on Lissajous paths (incommensurate periods, so the pattern rarely repeats).
    fillEllipse(out, w * (0.5 + 0.38 * std::sin(kTwoPi * t / 5.0)),
                h * (0.5 + 0.32 * std::sin(kTwoPi * t / 3.7 + 0.6)), 0.06 * h, 0.06 * h,
                {232, 118, 28});
    fillEllipse(out, w * (0.5 + 0.42 * std::sin(kTwoPi * t / 4.3 + 1.3)),
                h * (0.55 + 0.28 * std::sin(kTwoPi * t / 6.1 + 2.0)), 0.045 * h, 0.045 * h,
                {38, 92, 205});

    // A face-like figure swaying slowly in front of the discs.
    const double cx = w * (0.5 + 0.14 * std::sin(kTwoPi * t / 8.0));
    const double cy = h * (0.42 + 0.04 * std::sin(kTwoPi * t / 5.5));
    const double a = 0.10 * h;   // half width of the face
    const double b = 0.135 * h;  // half height of the face
    const Rgb skin{226, 176, 146};
    fillEllipse(out, cx, cy + 1.75 * b, 2.3 * a, 0.75 * b, {58, 78, 118});   // shoulders
    fillEllipse(out, cx, cy + 0.9 * b, 0.45 * a, 0.5 * b, {205, 156, 128});  // neck
    fillEllipse(out, cx, cy - 0.22 * b, 1.1 * a, 0.85 * b, {62, 42, 30});    // hair
    fillEllipse(out, cx, cy, a, b, skin);
    for (const double side : {-1.0, 1.0}) {
        fillEllipse(out, cx + side * 0.38 * a, cy - 0.33 * b, 0.22 * a, 0.045 * b, {80, 56, 42});
        fillEllipse(out, cx + side * 0.38 * a, cy - 0.12 * b, 0.17 * a, 0.085 * b, {44, 34, 34});
    }
    fillEllipse(out, cx, cy + 0.16 * b, 0.09 * a, 0.14 * b, {196, 146, 118}, 0.6);  // nose shadow
    fillEllipse(out, cx, cy + 0.5 * b, 0.32 * a, 0.07 * b, {152, 62, 62});          // mouth
    return true;
}

SourceStatus SyntheticSource::next(vision::Frame& frame) noexcept
{
    const std::int64_t timestamp = pacer_.wait();
    renderFrame(sequence_, frame_.view());
    frame.image = frame_.view();
    frame.sequence = sequence_;
    frame.timestampNs = timestamp;
    ++sequence_;
    return SourceStatus::Ok;
}

}  // namespace platform
