#include "vision/motion_detector.hpp"

#include "simd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#if defined(__aarch64__)
#include <arm_neon.h>
#endif

namespace vision {

namespace {

constexpr std::uint32_t kOne = 32768;  // weight 1.0 in q15

std::uint16_t toQ8(float v) noexcept
{
    return static_cast<std::uint16_t>(std::clamp(std::lround(v * 256.0f), 0L, 65535L));
}

void require(bool ok, const char* what)
{
    if (!ok) {
        throw std::runtime_error(std::string("MotionDetector: ") + what);
    }
}

/// Calls f(0) ... f(N - 1) unrolled at compile time: the loops over the K distributions must be
/// gone before the vectoriser looks at the loop over pixels.
template <int N, typename F>
inline __attribute__((always_inline)) void unrolled(F&& f) noexcept
{
    [&]<int... I>(std::integer_sequence<int, I...>)
    {
        (f(I), ...);
    }
    (std::make_integer_sequence<int, N>{});
}

/// cond ? a : b as arithmetic: GCC's if-conversion gives up on the many selects of the kernel,
/// masks vectorise.
inline int pick(bool cond, int a, int b) noexcept
{
    return b ^ ((a ^ b) & -static_cast<int>(cond));
}

// The model. Every pixel of a grey image is modelled by K Gaussians (mean, variance, weight), kept
// sorted by weight. A new value x matches the first (heaviest) distribution with (x - mean)^2 <
// lambda^2 * variance. Then, with learning rate a:
//   weights  w_k <- (1 - a) w_k + a M_k   (M_k = 1 for the matched distribution, else 0)
//   matched  mean <- mean + a (x - mean);  variance <- variance + a ((x - mean)^2 - variance)
//   no match: the lightest distribution is replaced by (x, initialVariance) with weight taking
//             what the others lost, i.e. (1 - a) w_old + a.
// (rho = a for the mean and variance, the usual simplification of Stauffer-Grimson's
// rho = a * eta(x | mean, sigma), which avoids an exp and a division per pixel.)
// The background is the first B distributions, B = argmin_b (sum_{k<=b} w_k > T); a pixel whose
// value matches none of them is foreground. The test uses the model before this frame's update.
//
// Fixed-point formats, one buffer of 3K planes of uint16 (weights of distribution 0..K-1, then
// means, then variances; structure of arrays so the per-pixel update vectorises across pixels):
//   weight   q15 in uint16 (32768 = 1). The weights always sum to exactly 32768: non-matched
//            weights decay rounding up, the matched/new one takes the remainder.
//   mean     q8  in uint16 (grey 0..255 with 8 fraction bits).
//   variance q8  in uint16 (grey^2, 0..255.99), clamped to [minVariance, maxVariance].
//   learning rate q16 (1..32767, i.e. up to 0.5); lambda^2 q8.
// Resolution: with learning rate a, a mean settles within about 1 / (512 a) grey of the data.
struct Params {
    int alpha;                    // q16
    int threshold;                // T, q15
    std::uint32_t lambda2;        // q8
    int initVar, minVar, maxVar;  // q8
};

/// One row of the mixture update (the model: above): `src` holds grey values in q8,
/// `out` receives 1 for foreground, 0 for background.
/// Every pixel is independent and the body is branch-free (selects as arithmetic), so the
/// compiler vectorises the loop over x after unrolling the loops over k. On x86-64 it is also
/// built for AVX2 (updateRow, below): plain SSE2 has no 32-bit multiply.
template <int K>
MIRROR_SIMD_BODY void updateRowBody(const std::uint16_t* src, std::uint16_t* out,
                                    std::uint16_t* planes, int width, std::ptrdiff_t n,
                                    const Params& p) noexcept
{
    const int alpha = p.alpha;
    const int threshold = p.threshold;
    const std::uint32_t lambda2 = p.lambda2;
    const int initVar = p.initVar;
    const int minVar = p.minVar;
    const int maxVar = p.maxVar;
    constexpr int one = static_cast<int>(kOne);
#pragma GCC ivdep
    for (int x = 0; x < width; ++x) {
        int w[K], m[K], v[K];
        unrolled<K>([&](int k) __attribute__((always_inline)) {
            w[k] = planes[k * n + x];
            m[k] = planes[(K + k) * n + x];
            v[k] = planes[(2 * K + k) * n + x];
        });
        const int value = src[x];

        // Match: the first (heaviest) distribution within lambda standard deviations.
        int match = K;
        unrolled<K>([&](int j) __attribute__((always_inline)) {
            const int k = K - 1 - j;  // from the lightest up, so the heaviest hit wins
            const int d = value - m[k];
            const std::uint32_t ad = static_cast<std::uint32_t>(std::abs(d));
            const bool hit =
                (w[k] != 0) & (ad * ad < lambda2 * static_cast<std::uint32_t>(v[k]));  // q16
            match = pick(hit, k, match);
        });
        // Background iff the match is among the first B: the weight ranked before it is at
        // most T (otherwise B would already be reached before it).
        int before = 0, matchBefore = one;
        unrolled<K>([&](int k) __attribute__((always_inline)) {
            matchBefore = pick(match == k, before, matchBefore);
            before += w[k];
        });
        const bool isForeground = matchBefore > threshold;
        out[x] = static_cast<std::uint16_t>(isForeground);

        // Update. No match: the lightest (last) distribution is replaced by the value.
        // Weights: the others decay by (1 - a) rounding the decay up (so unused ones reach
        // 0); the selected one takes the rest, keeping the sum exactly 1.
        const bool matched = match < K;
        const int sel = std::min(match, K - 1);
        // The selected distribution's update is computed once, then written back by selects.
        int mSel = 0, vSel = 0;
        unrolled<K>([&](int k) __attribute__((always_inline)) {
            mSel = pick(k == sel, m[k], mSel);
            vSel = pick(k == sel, v[k], vSel);
        });
        const int d = value - mSel;
        const std::uint32_t ad = static_cast<std::uint32_t>(std::abs(d));
        const int d2 = static_cast<int>(std::min((ad * ad) >> 8, 65535u));
        const int newMean = pick(matched, mSel + ((d * alpha + 32768) >> 16), value);
        const int newVar =
            pick(matched,
                 std::min(std::max(vSel + (((d2 - vSel) * alpha + 32768) >> 16), minVar), maxVar),
                 initVar);
        int others = 0;
        unrolled<K>([&](int k) __attribute__((always_inline)) {
            const bool isSel = k == sel;
            m[k] = pick(isSel, newMean, m[k]);
            v[k] = pick(isSel, newVar, v[k]);
            w[k] = w[k] - ((w[k] * alpha + 65535) >> 16);
            others += w[k] & (static_cast<int>(isSel) - 1);
        });
        unrolled<K>([&](int k) __attribute__((always_inline)) {
            w[k] = pick(k == sel, one - others, w[k]);
        });
        // Keep the order by weight: only the selected one can have overtaken others, and one
        // bottom-up pass of compare-exchange carries it to its place.
        unrolled<K - 1>([&](int j0) __attribute__((always_inline)) {
            const int j = j0 + 1;
            const int k = K - j;
            const bool up = w[k] > w[k - 1];
            const int tw = w[k], tm = m[k], tv = v[k];
            w[k] = pick(up, w[k - 1], w[k]);
            m[k] = pick(up, m[k - 1], m[k]);
            v[k] = pick(up, v[k - 1], v[k]);
            w[k - 1] = pick(up, tw, w[k - 1]);
            m[k - 1] = pick(up, tm, m[k - 1]);
            v[k - 1] = pick(up, tv, v[k - 1]);
        });
        unrolled<K>([&](int k) __attribute__((always_inline)) {
            planes[k * n + x] = static_cast<std::uint16_t>(w[k]);
            planes[(K + k) * n + x] = static_cast<std::uint16_t>(m[k]);
            planes[(2 * K + k) * n + x] = static_cast<std::uint16_t>(v[k]);
        });
    }
}

// The path for this CPU (simd.hpp): the body built for AVX2 or for the baseline.
#if defined(__x86_64__)
template <int K>
MIRROR_AVX2 void updateRowAvx2(const std::uint16_t* src, std::uint16_t* out, std::uint16_t* planes,
                               int width, std::ptrdiff_t n, const Params& p) noexcept
{
    updateRowBody<K>(src, out, planes, width, n, p);
}
#endif

template <int K>
void updateRow(const std::uint16_t* src, std::uint16_t* out, std::uint16_t* planes, int width,
               std::ptrdiff_t n, const Params& p) noexcept
{
#if defined(__x86_64__)
    if (simd::hasAvx2())
        return updateRowAvx2<K>(src, out, planes, width, n, p);
#endif
    updateRowBody<K>(src, out, planes, width, n, p);
}

}  // namespace

MotionDetector::MotionDetector(Size size, const MotionDetectorOptions& options)
    : size_(size), options_(options), K_(options.components)
{
    require(size.width > 0 && size.height > 0, "image size must be positive");
    require(options.components >= 1 && options.components <= 5, "components must be 1..5");
    require(options.learningRate > 0.0f && options.learningRate <= 0.5f,
            "learningRate must be in (0, 0.5]");
    require(options.backgroundRatio > 0.0f && options.backgroundRatio < 1.0f,
            "backgroundRatio must be in (0, 1)");
    require(options.matchThreshold > 0.0f && options.matchThreshold <= 8.0f,
            "matchThreshold must be in (0, 8] standard deviations");
    require(options.minVariance >= 1.0f / 256.0f && options.minVariance <= options.maxVariance &&
                options.maxVariance < 256.0f,
            "variances must satisfy 1/256 <= minVariance <= maxVariance < 256");
    require(options.initialVariance >= options.minVariance &&
                options.initialVariance <= options.maxVariance,
            "initialVariance must be within [minVariance, maxVariance]");

    alpha_ = static_cast<std::uint32_t>(
        std::clamp(std::lround(options.learningRate * 65536.0f), 1L, 32767L));
    threshold_ = static_cast<std::uint32_t>(std::lround(options.backgroundRatio * kOne));
    lambda2_ = static_cast<std::uint32_t>(
        std::lround(options.matchThreshold * options.matchThreshold * 256.0f));
    initVar_ = toQ8(options.initialVariance);
    minVar_ = toQ8(options.minVariance);
    maxVar_ = toQ8(options.maxVariance);
    planeSize_ = static_cast<std::ptrdiff_t>(size.width) * size.height;
    rowIn_ = std::make_unique<std::uint16_t[]>(static_cast<std::size_t>(size.width));
    rowOut_ = std::make_unique<std::uint16_t[]>(static_cast<std::size_t>(size.width));
    model_ = std::make_unique<std::uint16_t[]>(static_cast<std::size_t>(size.width) *
                                               static_cast<std::size_t>(size.height) * 3 *
                                               static_cast<std::size_t>(K_));
    reset();
}

void MotionDetector::reset() noexcept
{
    // Unused distributions have weight 0 and never match.
    std::memset(model_.get(), 0,
                static_cast<std::size_t>(size_.width) * static_cast<std::size_t>(size_.height) * 3 *
                    static_cast<std::size_t>(K_) * sizeof(std::uint16_t));
    empty_ = true;
}

void MotionDetector::initialise(const ConstImageView& gray, const ImageView& mask) noexcept
{
    std::uint16_t* model = model_.get();
    for (int y = 0; y < size_.height; ++y) {
        const std::uint8_t* src = gray.row(y);
        std::memset(mask.row(y), 0, static_cast<std::size_t>(size_.width));
        const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(y) * size_.width;
        for (int x = 0; x < size_.width; ++x) {
            model[row + x] = static_cast<std::uint16_t>(kOne);
            model[K_ * planeSize_ + row + x] = static_cast<std::uint16_t>(src[x] << 8);
            model[2 * K_ * planeSize_ + row + x] = initVar_;
        }
    }
    empty_ = false;
}

int MotionDetector::framesToBecomeBackground() const noexcept
{
    const double a = alpha_ / 65536.0;
    const double t = static_cast<double>(threshold_) / kOne;
    return static_cast<int>(std::ceil(std::log(t) / std::log1p(-a)));
}

template <int K>
int MotionDetector::applyK(const ConstImageView& gray, const ImageView& mask) noexcept
{
    const Params p{static_cast<int>(alpha_),
                   static_cast<int>(threshold_),
                   lambda2_,
                   initVar_,
                   minVar_,
                   maxVar_};
    const int width = size_.width;
    std::uint16_t* in = rowIn_.get();
    std::uint16_t* fg = rowOut_.get();
    int foreground = 0;
    for (int y = 0; y < size_.height; ++y) {
        // The kernel works on 16-bit rows: with bytes in it the vectoriser would process 32
        // pixels per iteration and spill most of its registers.
        const std::uint8_t* src = gray.row(y);
        for (int x = 0; x < width; ++x) {
            in[x] = static_cast<std::uint16_t>(src[x] << 8);
        }
        updateRow<K>(in, fg, model_.get() + static_cast<std::ptrdiff_t>(y) * width, width,
                     planeSize_, p);
        std::uint8_t* out = mask.row(y);
        int count = 0;
        for (int x = 0; x < width; ++x) {
            out[x] = static_cast<std::uint8_t>(-fg[x]);
            count += fg[x];
        }
        foreground += count;
    }
    return foreground;
}

int MotionDetector::apply(const ConstImageView& gray, const ImageView& mask) noexcept
{
    if (gray.empty() || mask.empty() || gray.format != PixelFormat::Gray8 ||
        mask.format != PixelFormat::Gray8 || gray.size() != size_ || mask.size() != size_) {
        return -1;
    }
    if (empty_) {
        initialise(gray, mask);
        return 0;
    }
    switch (K_) {
        case 1:
            return applyK<1>(gray, mask);
        case 2:
            return applyK<2>(gray, mask);
        case 3:
            return applyK<3>(gray, mask);
        case 4:
            return applyK<4>(gray, mask);
        default:
            return applyK<5>(gray, mask);
    }
}

namespace {

// 2x2 box of a packed RGB-like image into grey: sum the four pixels per channel, then luma with
// the divide by 4 folded into the shift.
#if defined(__aarch64__)
/// halveRgb's sums for 8 output pixels of a 3-byte format with NEON (the camera's BGR24 at
/// half size: a sixth of the motion stage): vld3 de-interleaves 16 pixels of each row, pairwise
/// long adds sum each 2x2 box per channel (at most 1020), the luma in 32-bit lanes. The same
/// integers as the scalar loop, so the same bytes.
template <int R, int G, int B>
int halveRgb3Neon(const std::uint8_t* a, const std::uint8_t* b, std::uint8_t* out,
                  int width) noexcept
{
    int x = 0;
    for (; x + 8 <= width; x += 8, a += 48, b += 48) {
        const uint8x16x3_t pa = vld3q_u8(a);
        const uint8x16x3_t pb = vld3q_u8(b);
        const uint16x8_t r = vpadalq_u8(vpaddlq_u8(pa.val[R]), pb.val[R]);
        const uint16x8_t g = vpadalq_u8(vpaddlq_u8(pa.val[G]), pb.val[G]);
        const uint16x8_t bl = vpadalq_u8(vpaddlq_u8(pa.val[B]), pb.val[B]);
        const uint32x4_t half = vdupq_n_u32(512);
        uint32x4_t lo = vmlal_n_u16(half, vget_low_u16(r), 77);
        uint32x4_t hi = vmlal_high_n_u16(half, r, 77);
        lo = vmlal_n_u16(lo, vget_low_u16(g), 150);
        hi = vmlal_high_n_u16(hi, g, 150);
        lo = vmlal_n_u16(lo, vget_low_u16(bl), 29);
        hi = vmlal_high_n_u16(hi, bl, 29);
        const uint16x8_t luma = vcombine_u16(vshrn_n_u32(lo, 10), vshrn_n_u32(hi, 10));
        vst1_u8(out + x, vmovn_u16(luma));
    }
    return x;
}
#endif

template <int Bpp, int R, int G, int B>
void halveRgb(const ConstImageView& src, const ImageView& dst) noexcept
{
    for (int y = 0; y < dst.height; ++y) {
        const std::uint8_t* a = src.row(2 * y);
        const std::uint8_t* b = src.row(2 * y + 1);
        std::uint8_t* out = dst.row(y);
        int x = 0;
#if defined(__aarch64__)
        if constexpr (Bpp == 3) {
            x = halveRgb3Neon<R, G, B>(a, b, out, dst.width);
            a += 2 * Bpp * x;
            b += 2 * Bpp * x;
        }
#endif
        for (; x < dst.width; ++x, a += 2 * Bpp, b += 2 * Bpp) {
            const unsigned r = a[R] + a[Bpp + R] + b[R] + b[Bpp + R];
            const unsigned g = a[G] + a[Bpp + G] + b[G] + b[Bpp + G];
            const unsigned bl = a[B] + a[Bpp + B] + b[B] + b[Bpp + B];
            out[x] = static_cast<std::uint8_t>((77 * r + 150 * g + 29 * bl + 512) >> 10);
        }
    }
}

void halveGray(const ConstImageView& src, const ImageView& dst) noexcept
{
    for (int y = 0; y < dst.height; ++y) {
        const std::uint8_t* a = src.row(2 * y);
        const std::uint8_t* b = src.row(2 * y + 1);
        std::uint8_t* out = dst.row(y);
        for (int x = 0; x < dst.width; ++x) {
            out[x] = static_cast<std::uint8_t>(
                (a[2 * x] + a[2 * x + 1] + b[2 * x] + b[2 * x + 1] + 2) >> 2);
        }
    }
}

// Any factor and format (not the hot path): sums, then one integer division per output pixel.
void boxGeneric(const ConstImageView& src, int factor, const ImageView& dst) noexcept
{
    const bool isGray = src.format == PixelFormat::Gray8;
    const RgbLayout lay = rgbLayout(src.format);
    const int bpp = isGray ? 1 : lay.bytesPerPixel;
    const unsigned area = static_cast<unsigned>(factor * factor);
    for (int y = 0; y < dst.height; ++y) {
        std::uint8_t* out = dst.row(y);
        for (int x = 0; x < dst.width; ++x) {
            unsigned luma256 = 0;  // grey * 256, summed over the box
            for (int dy = 0; dy < factor; ++dy) {
                const std::uint8_t* p = src.row(y * factor + dy) + x * factor * bpp;
                for (int dx = 0; dx < factor; ++dx, p += bpp) {
                    luma256 +=
                        isGray ? 256u * p[0] : 77u * p[lay.r] + 150u * p[lay.g] + 29u * p[lay.b];
                }
            }
            out[x] = static_cast<std::uint8_t>((luma256 + 128u * area) / (256u * area));
        }
    }
}

}  // namespace

// Grey, not per-channel: a third of the memory and time, which matters more at 25 Hz on the
// target than the rare motion visible only in chroma (faces and hands differ from the background
// in luminance too); the stage converts and halves the camera frame in one pass.
bool downscaleToGray(const ConstImageView& src, int factor, const ImageView& dst) noexcept
{
    if (factor < 1 || factor > 4 || src.empty() || dst.empty() ||
        dst.format != PixelFormat::Gray8 || dst.width != src.width / factor ||
        dst.height != src.height / factor) {
        return false;
    }
    if (src.format != PixelFormat::Gray8 && rgbLayout(src.format).bytesPerPixel == 0) {
        return false;
    }
    if (factor != 2) {
        boxGeneric(src, factor, dst);
        return true;
    }
    switch (src.format) {
        case PixelFormat::RGB24:
            halveRgb<3, 0, 1, 2>(src, dst);
            break;
        case PixelFormat::BGR24:
            halveRgb<3, 2, 1, 0>(src, dst);
            break;
        case PixelFormat::XRGB8888:
            halveRgb<4, 2, 1, 0>(src, dst);
            break;
        default:
            halveGray(src, dst);
            break;
    }
    return true;
}

}  // namespace vision
