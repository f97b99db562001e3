// The piecewise affine warp of the image into the mean shape's frame (§5, 5.3.2), as 5.3.4 made it
// fast: closed-form triangle maps, the frame walked run by run (a row's pixels in one triangle)
// with the map stepped in q16 fixed point, nearest-neighbour sampling. A run whose two ends are
// inside the image has all its pixels inside (the map is linear along it), so only runs crossing
// the border pay for clamping.
#include "aam_warp.hpp"

#include <algorithm>
#include <cmath>

namespace vision::aam {

namespace {

constexpr float kQ16 = 65536.f;

struct Stepper {
    std::int32_t x, y, dx, dy;  // q16
};

/// Run `r`'s first place and step, when both of its ends lie at least `margin` pixels inside
/// the image's last pixel; false otherwise.
bool insideStepper(const WarpRun& r, const TriangleAffine& a, int width, int height, float margin,
                   Stepper& s) noexcept
{
    const Eigen::Vector2f first = a.linear * Eigen::Vector2f(r.x0, r.y) + a.offset;
    const Eigen::Vector2f last = first + a.linear.col(0) * static_cast<float>(r.count - 1);
    const float maxX = static_cast<float>(width - 1) - margin;
    const float maxY = static_cast<float>(height - 1) - margin;
    if (!(first.x() >= 0.f && first.y() >= 0.f && last.x() >= 0.f && last.y() >= 0.f &&
          first.x() <= maxX && last.x() <= maxX && first.y() <= maxY && last.y() <= maxY))
        return false;
    s = {static_cast<std::int32_t>(std::lround(first.x() * kQ16)),
         static_cast<std::int32_t>(std::lround(first.y() * kQ16)),
         static_cast<std::int32_t>(std::lround(a.linear(0, 0) * kQ16)),
         static_cast<std::int32_t>(std::lround(a.linear(1, 0) * kQ16))};
    return true;
}

void nearestRun(Stepper s, int count, ConstImageView grey, std::int16_t* out) noexcept
{
    for (int k = 0; k < count; ++k) {
        const int ix = (s.x + 0x8000) >> 16, iy = (s.y + 0x8000) >> 16;
        out[k] = grey.row(iy)[ix];
        s.x += s.dx;
        s.y += s.dy;
    }
}

void bilinearRun(Stepper s, int count, ConstImageView grey, std::int16_t* out) noexcept
{
    for (int k = 0; k < count; ++k) {
        const int ix = s.x >> 16, iy = s.y >> 16;
        const int fx = (s.x >> 8) & 0xff, fy = (s.y >> 8) & 0xff;
        const std::uint8_t* r0 = grey.row(iy) + ix;
        const std::uint8_t* r1 = r0 + grey.stride;
        const int top = r0[0] * 256 + (r0[1] - r0[0]) * fx;
        const int bottom = r1[0] * 256 + (r1[1] - r1[0]) * fx;
        out[k] = static_cast<std::int16_t>((top * 256 + (bottom - top) * fy + 0x8000) >> 16);
        s.x += s.dx;
        s.y += s.dy;
    }
}

/// A run crossing the border: each place clamped into the image; returns how many were outside.
int clampedRun(const WarpRun& r, const TriangleAffine& a, ConstImageView grey,
               std::int16_t* out) noexcept
{
    int outside = 0;
    for (int k = 0; k < r.count; ++k) {
        const Eigen::Vector2f p =
            a.linear * Eigen::Vector2f(static_cast<float>(r.x0 + k), static_cast<float>(r.y)) +
            a.offset;
        const auto width = static_cast<float>(grey.width), height = static_cast<float>(grey.height);
        const bool in =
            p.x() >= -0.5f && p.y() >= -0.5f && p.x() < width - 0.5f && p.y() < height - 0.5f;
        outside += in ? 0 : 1;
        // A NaN place (a degenerate shape) clamps to 0 like any other outside place.
        const float cx = std::clamp(std::isnan(p.x()) ? 0.f : p.x(), 0.f, width - 1.f);
        const float cy = std::clamp(std::isnan(p.y()) ? 0.f : p.y(), 0.f, height - 1.f);
        out[k] = grey.row(static_cast<int>(cy + 0.5f))[static_cast<int>(cx + 0.5f)];
    }
    return outside;
}

}  // namespace

void triangleAffines(const Tables& t, const float* shape, TriangleAffine* out) noexcept
{
    for (int i = 0; i < t.triangles; ++i) {
        const FrameTriangle& f = t.frameTriangles[static_cast<std::size_t>(i)];
        const Eigen::Vector2f u0(shape[2 * f.v[0]], shape[2 * f.v[0] + 1]);
        Eigen::Matrix2f edges;
        edges << shape[2 * f.v[1]] - u0.x(), shape[2 * f.v[2]] - u0.x(),
            shape[2 * f.v[1] + 1] - u0.y(), shape[2 * f.v[2] + 1] - u0.y();
        out[i].linear = edges * f.inverseEdges;
        out[i].offset = u0 - out[i].linear * f.origin;
    }
}

int warpImage(const Tables& t, const TriangleAffine* affines, ConstImageView grey,
              AamSampling sampling, std::int16_t* warped) noexcept
{
    const bool bilinear = sampling == AamSampling::Bilinear;
    // Bilinear reads the next pixel right and down: its places stay a pixel further in.
    const float margin = bilinear ? 1.01f : 0.01f;
    int outside = 0;
    for (const WarpRun& r : t.runs) {
        std::int16_t* out = warped + r.offset;
        const TriangleAffine& a = affines[r.triangle];
        Stepper s;
        if (!insideStepper(r, a, grey.width, grey.height, margin, s))
            outside += clampedRun(r, a, grey, out);
        else if (bilinear)
            bilinearRun(s, r.count, grey, out);
        else
            nearestRun(s, r.count, grey, out);
    }
    return outside;
}

}  // namespace vision::aam
