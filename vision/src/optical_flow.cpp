// Pyramidal Lucas-Kanade in fixed point (METHOD.md §3, tracking).
#include "vision/optical_flow.hpp"

#include "lk_window.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vision {

namespace {

// OpenCV's scale of the gradient matrix for its minimum-eigenvalue test (gradients are Scharr
// responses of 8-bit pixels, summed products scaled by 2^-20, then divided by the window area).
constexpr double kEigScale = 1.0 / (1 << 20);

using lk_detail::Bilinear;
using lk_detail::bilinearAt;
using lk_detail::kSlack;
using lk_detail::kValueBits;
using lk_detail::kWeightBits;
using lk_detail::windowRow;

// The scalar kernels: the reference (lk_window.hpp has their AVX2 builds).

/// Bilinear samples of a window wholly inside the image (one more column and row included).
void sampleInside(ConstImageView img, const Bilinear& w, int rows, int cols, int outStride,
                  std::int16_t* out) noexcept
{
    constexpr int shift = kWeightBits - kValueBits;
    constexpr int round = 1 << (shift - 1);
    for (int r = 0; r < rows; ++r) {
        const std::uint8_t* s0 = img.row(w.y0 + r) + w.x0;
        const std::uint8_t* s1 = s0 + img.stride;
        std::int16_t* o = out + r * outStride;
        for (int c = 0; c < cols; ++c) {
            o[c] = static_cast<std::int16_t>(
                (s0[c] * w.w00 + s0[c + 1] * w.w01 + s1[c] * w.w10 + s1[c + 1] * w.w11 + round) >>
                shift);
        }
    }
}

/// From the sampled window with its one-value rim (rows `pstride` apart): the window's values and
/// Scharr gradients rescaled to the response on 8-bit pixels (5 fractional bits dropped, rounded),
/// rows of `lanes` values with zeros past `win`, and the gradient matrix sums.
void windowGradients(const std::int16_t* __restrict patch, int pstride, int win, int lanes,
                     std::int16_t* __restrict ival, std::int16_t* __restrict ix,
                     std::int16_t* __restrict iy, std::int64_t& a11, std::int64_t& a12,
                     std::int64_t& a22) noexcept
{
    std::int64_t t11 = 0;
    std::int64_t t12 = 0;
    std::int64_t t22 = 0;
    for (int r = 0; r < win; ++r) {
        const std::int16_t* __restrict up = patch + r * pstride;
        const std::int16_t* __restrict mid = up + pstride;
        const std::int16_t* __restrict dn = mid + pstride;
        std::int16_t* __restrict vi = ival + r * lanes;
        std::int16_t* __restrict gx = ix + r * lanes;
        std::int16_t* __restrict gy = iy + r * lanes;
        for (int c = 0; c < lanes; ++c) {
            const int dx = 3 * (up[c + 2] - up[c] + dn[c + 2] - dn[c]) + 10 * (mid[c + 2] - mid[c]);
            const int dy =
                3 * (dn[c] - up[c] + dn[c + 2] - up[c + 2]) + 10 * (dn[c + 1] - up[c + 1]);
            vi[c] = mid[c + 1];
            gx[c] = static_cast<std::int16_t>((dx + 16) >> kValueBits);
            gy[c] = static_cast<std::int16_t>((dy + 16) >> kValueBits);
        }
        for (int c = win; c < lanes; ++c) {
            vi[c] = 0;
            gx[c] = 0;
            gy[c] = 0;
        }
        std::int32_t s11 = 0;
        std::int32_t s12 = 0;
        std::int32_t s22 = 0;
        for (int c = 0; c < lanes; ++c) {
            s11 += gx[c] * gx[c];
            s12 += gx[c] * gy[c];
            s22 += gy[c] * gy[c];
        }
        t11 += s11;
        t12 += s12;
        t22 += s22;
    }
    a11 = t11;
    a12 = t12;
    a22 = t22;
}

/// The mismatch vector b = sum (J - I) * grad I over the window, J sampled at `w` straight from
/// the image (the window and one more column and row inside it). Rows of `lanes` values; the
/// padding lanes have zero gradients, so they add nothing. One fused pass, no stores.
void mismatchInside(ConstImageView img, const Bilinear& w, int rows, int lanes,
                    const std::int16_t* ival, const std::int16_t* ix, const std::int16_t* iy,
                    std::int64_t& b1, std::int64_t& b2) noexcept
{
    constexpr int shift = kWeightBits - kValueBits;
    constexpr int round = 1 << (shift - 1);
    std::int64_t t1 = 0;
    std::int64_t t2 = 0;
    for (int r = 0; r < rows; ++r) {
        const auto [s0, s1, vi, gx, gy] = windowRow(img, w, r, lanes, ival, ix, iy);
        std::int32_t a1 = 0;
        std::int32_t a2 = 0;
        for (int c = 0; c < lanes; ++c) {
            const int j =
                (s0[c] * w.w00 + s0[c + 1] * w.w01 + s1[c] * w.w10 + s1[c + 1] * w.w11 + round) >>
                shift;
            const int d = j - vi[c];
            a1 += d * gx[c];
            a2 += d * gy[c];
        }
        t1 += a1;
        t2 += a2;
    }
    b1 = t1;
    b2 = t2;
}

// The path for this CPU (simd.hpp).
void gradientsOf(const std::int16_t* patch, int pstride, int win, int lanes, std::int16_t* ival,
                 std::int16_t* ix, std::int16_t* iy, std::int64_t& a11, std::int64_t& a12,
                 std::int64_t& a22) noexcept
{
#if defined(__x86_64__)
    if (simd::hasAvx2())
        return lk_detail::windowGradientsAvx2(patch, pstride, win, lanes, ival, ix, iy, a11, a12,
                                              a22);
#endif
    windowGradients(patch, pstride, win, lanes, ival, ix, iy, a11, a12, a22);
}

void mismatchOf(ConstImageView img, const Bilinear& w, int rows, int lanes,
                const std::int16_t* ival, const std::int16_t* ix, const std::int16_t* iy,
                std::int64_t& b1, std::int64_t& b2) noexcept
{
#if defined(__x86_64__)
    if (simd::hasAvx2())
        return lk_detail::mismatchInsideAvx2(img, w, rows, lanes, ival, ix, iy, b1, b2);
#endif
    mismatchInside(img, w, rows, lanes, ival, ix, iy, b1, b2);
}

}  // namespace

PyramidalLucasKanade::PyramidalLucasKanade(const OpticalFlowOptions& options) : options_(options)
{
    const int w = options.window;
    if (w < 3 || w > 31 || w % 2 == 0) {
        throw std::runtime_error("PyramidalLucasKanade: window " + std::to_string(w) +
                                 " must be odd and within 3..31");
    }
    if (options.maxLevel < 0 || options.maxIterations < 1) {
        throw std::runtime_error("PyramidalLucasKanade: maxLevel must be >= 0, maxIterations >= 1");
    }
    lanes_ = (w + 7) & ~7;
    const std::size_t area = static_cast<std::size_t>(w) * static_cast<std::size_t>(lanes_);
    patch_ = std::make_unique<std::int16_t[]>(
        static_cast<std::size_t>(w + 2) * static_cast<std::size_t>(lanes_ + 2) + kSlack);
    ival_ = std::make_unique<std::int16_t[]>(area + kSlack);
    ix_ = std::make_unique<std::int16_t[]>(area + kSlack);
    iy_ = std::make_unique<std::int16_t[]>(area + kSlack);
    edge_ = std::make_unique<std::uint8_t[]>(static_cast<std::size_t>(w + 3) *
                                             static_cast<std::size_t>(lanes_ + 3));
}

ConstImageView PyramidalLucasKanade::edgeCopy(ConstImageView img, int x0, int y0, int rows,
                                              int cols) noexcept
{
    const int maxX = img.width - 1;
    const int maxY = img.height - 1;
    const int stride = lanes_ + 3;
    std::uint8_t* dst = edge_.get();
    for (int r = 0; r <= rows; ++r) {
        const std::uint8_t* s = img.row(std::clamp(y0 + r, 0, maxY));
        std::uint8_t* d = dst + r * stride;
        int c = 0;
        for (; c <= cols && x0 + c < 0; ++c) {
            d[c] = s[0];
        }
        const int inside = std::min(cols + 1, maxX - x0 + 1) - c;
        if (inside > 0) {
            std::copy_n(s + x0 + c, inside, d + c);
            c += inside;
        }
        for (; c <= cols; ++c) {
            d[c] = s[maxX];
        }
    }
    return {dst, cols + 1, rows + 1, stride, PixelFormat::Gray8};
}

void PyramidalLucasKanade::sampleWindow(ConstImageView img, float x, float y, int rows, int cols,
                                        int outStride, std::int16_t* out) noexcept
{
    Bilinear w = bilinearAt(x, y);
    if (!(w.x0 >= 0 && w.y0 >= 0 && w.x0 + cols < img.width && w.y0 + rows < img.height)) {
        img = edgeCopy(img, w.x0, w.y0, rows, cols);
        w.x0 = 0;
        w.y0 = 0;
    }
#if defined(__x86_64__)
    if (simd::hasAvx2()) {
        lk_detail::sampleInsideAvx2(img, w, rows, cols, outStride, out);
        return;
    }
#endif
    sampleInside(img, w, rows, cols, outStride, out);
}

bool PyramidalLucasKanade::trackPoint(const ImagePyramid& prev, const ImagePyramid& next,
                                      Point2f from, Point2f guess, Point2f& to) noexcept
{
    to = from;
    const int levels = std::min({prev.levels(), next.levels(), options_.maxLevel + 1});
    if (levels < 1 || prev.size() != next.size() || prev.level(0).empty() ||
        next.level(0).empty()) {
        return false;
    }
    const int win = options_.window;
    const int side = win + 2;
    const float half = static_cast<float>(win - 1) * 0.5f;
    const int area = win * win;
    std::int16_t* patch = patch_.get();
    std::int16_t* ival = ival_.get();
    std::int16_t* ix = ix_.get();
    std::int16_t* iy = iy_.get();
    const int lanes = lanes_;
    const float eps2 = options_.epsilon * options_.epsilon;

    const float topScale = 1.f / static_cast<float>(1 << (levels - 1));
    Point2f est{guess.x * topScale, guess.y * topScale};
    bool ok = true;
    for (int level = levels - 1; level >= 0; --level) {
        const float s = 1.f / static_cast<float>(1 << level);
        const Point2f p{from.x * s, from.y * s};
        if (level != levels - 1) {
            est = {est.x * 2.f, est.y * 2.f};
        }
        const ConstImageView imgI = prev.level(level);
        const ConstImageView imgJ = next.level(level);
        // Written so that NaN fails too (it would make the pixel index undefined).
        if (!(p.x >= -half && p.y >= -half && p.x <= static_cast<float>(imgI.width) + half &&
              p.y <= static_cast<float>(imgI.height) + half)) {
            ok = level != 0 && ok;
            continue;
        }
        // On a coarse level a window reaching far past the border is mostly repeated edge
        // pixels, which pull the estimate; such levels are skipped, the finer ones do the work.
        const float inner = 0.5f * half;
        if (level > 0 &&
            (p.x < inner || p.y < inner || p.x > static_cast<float>(imgI.width - 1) - inner ||
             p.y > static_cast<float>(imgI.height - 1) - inner)) {
            continue;
        }

        // The previous frame's window with a one-pixel rim, then its Scharr gradients rescaled
        // to the response on 8-bit pixels (the 5 fractional bits dropped, rounded).
        sampleWindow(imgI, p.x - half - 1.f, p.y - half - 1.f, side, lanes + 2, lanes + 2, patch);
        std::int64_t a11 = 0;
        std::int64_t a12 = 0;
        std::int64_t a22 = 0;
        gradientsOf(patch, lanes + 2, win, lanes, ival, ix, iy, a11, a12, a22);
        const double g11 = static_cast<double>(a11) * kEigScale;
        const double g12 = static_cast<double>(a12) * kEigScale;
        const double g22 = static_cast<double>(a22) * kEigScale;
        const double det = g11 * g22 - g12 * g12;
        const double minEig =
            (g11 + g22 - std::sqrt((g11 - g22) * (g11 - g22) + 4.0 * g12 * g12)) / (2.0 * area);
        if (minEig < static_cast<double>(options_.minEigThreshold) || det < 1.19e-7) {
            ok = level != 0 && ok;
            continue;
        }
        const double invDet = 1.0 / det;

        Point2f prevDelta{0.f, 0.f};
        for (int it = 0; it < options_.maxIterations; ++it) {
            if (!(est.x >= -half && est.y >= -half &&
                  est.x <= static_cast<float>(imgJ.width) + half &&
                  est.y <= static_cast<float>(imgJ.height) + half)) {
                ok = level != 0 && ok;
                break;
            }
            std::int64_t b1 = 0;
            std::int64_t b2 = 0;
            Bilinear bw = bilinearAt(est.x - half, est.y - half);
            ConstImageView src = imgJ;
            if (!(bw.x0 >= 0 && bw.y0 >= 0 && bw.x0 + lanes < imgJ.width &&
                  bw.y0 + win < imgJ.height)) {
                src = edgeCopy(imgJ, bw.x0, bw.y0, win, lanes);
                bw.x0 = 0;
                bw.y0 = 0;
            }
            mismatchOf(src, bw, win, lanes, ival, ix, iy, b1, b2);
            // Values are 32 x pixels and Scharr responses 32 x the slope: the scales cancel.
            const double e1 = static_cast<double>(b1) * kEigScale;
            const double e2 = static_cast<double>(b2) * kEigScale;
            const Point2f delta{static_cast<float>((g12 * e2 - g22 * e1) * invDet),
                                static_cast<float>((g12 * e1 - g11 * e2) * invDet)};
            est.x += delta.x;
            est.y += delta.y;
            if (delta.x * delta.x + delta.y * delta.y <= eps2) {
                break;
            }
            // Oscillating between two positions: settle half way, as OpenCV does.
            if (it > 0 && std::fabs(delta.x + prevDelta.x) < 0.01f &&
                std::fabs(delta.y + prevDelta.y) < 0.01f) {
                est.x -= delta.x * 0.5f;
                est.y -= delta.y * 0.5f;
                break;
            }
            prevDelta = delta;
        }
    }
    const ConstImageView base = next.level(0);
    if (!ok || !std::isfinite(est.x) || !std::isfinite(est.y) || est.x < 0.f || est.y < 0.f ||
        est.x > static_cast<float>(base.width - 1) || est.y > static_cast<float>(base.height - 1)) {
        return false;
    }
    to = est;
    return true;
}

int PyramidalLucasKanade::track(const ImagePyramid& prev, const ImagePyramid& next,
                                const Point2f* prevPts, Point2f* nextPts, FlowStatus* status, int n,
                                float* fbError) noexcept
{
    int tracked = 0;
    for (int i = 0; i < n; ++i) {
        if (fbError) {
            fbError[i] = -1.f;
        }
        Point2f to;
        if (!trackPoint(prev, next, prevPts[i], prevPts[i], to)) {
            nextPts[i] = prevPts[i];
            status[i] = FlowStatus::Lost;
            continue;
        }
        nextPts[i] = to;
        if (options_.fbThreshold > 0.f) {
            Point2f back;
            float d = 1e30f;
            if (trackPoint(next, prev, to, to, back)) {
                d = std::hypot(back.x - prevPts[i].x, back.y - prevPts[i].y);
            }
            if (fbError) {
                fbError[i] = d;
            }
            if (d > options_.fbThreshold) {
                status[i] = FlowStatus::ForwardBackwardFailed;
                continue;
            }
        }
        status[i] = FlowStatus::Tracked;
        ++tracked;
    }
    return tracked;
}

}  // namespace vision
