// Grey image pyramid (METHOD.md §3, tracking): 5-tap binomial reduction in integer arithmetic.
#include "vision/image_pyramid.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace vision {

namespace {

/// Reflect-101 index into [0, n): -1 -> 1, n -> n - 2 (cv::BORDER_REFLECT_101, as cv::pyrDown).
inline int reflect101(int i, int n) noexcept
{
    if (i < 0) {
        i = -i;
    }
    if (i >= n) {
        i = 2 * n - 2 - i;
    }
    return i;
}

// The filter is the hot loop of the frame's pyramid: on x86-64 also build an AVX2 copy, chosen at
// load time (aarch64 has NEON as its baseline).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define MIRROR_PYR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MIRROR_PYR_CLONES
#endif

/// Five source rows filtered vertically by [1 4 6 4 1] at full width (sums up to 16 * 255).
MIRROR_PYR_CLONES void filterColumns(const std::uint8_t* r0, const std::uint8_t* r1,
                                     const std::uint8_t* r2, const std::uint8_t* r3,
                                     const std::uint8_t* r4, int w, std::uint16_t* out) noexcept
{
    for (int x = 0; x < w; ++x) {
        out[x] = static_cast<std::uint16_t>(r0[x] + r4[x] + 4 * (r1[x] + r3[x]) + 6 * r2[x]);
    }
}

/// The vertically filtered row filtered horizontally, subsampled by 2, rounded to 8 bits.
MIRROR_PYR_CLONES void filterRowDown(const std::uint16_t* v, int w, std::uint8_t* out,
                                     int dw) noexcept
{
    const int last = (w - 3) / 2;  // largest x with 2x + 2 <= w - 1: all taps inside
    for (int x = 1; x <= last; ++x) {
        const std::uint16_t* p = v + 2 * x;
        const std::uint32_t sum = static_cast<std::uint32_t>(p[-2]) + p[2] +
                                  4u * (static_cast<std::uint32_t>(p[-1]) + p[1]) + 6u * p[0];
        out[x] = static_cast<std::uint8_t>((sum + 128u) >> 8);
    }
    auto edge = [&](int x) {
        const int c = 2 * x;
        const std::uint32_t sum =
            static_cast<std::uint32_t>(v[reflect101(c - 2, w)]) + v[reflect101(c + 2, w)] +
            4u * (static_cast<std::uint32_t>(v[reflect101(c - 1, w)]) + v[reflect101(c + 1, w)]) +
            6u * v[c];
        out[x] = static_cast<std::uint8_t>((sum + 128u) >> 8);
    };
    edge(0);
    for (int x = std::max(last + 1, 1); x < dw; ++x) {
        edge(x);
    }
}

}  // namespace

ImagePyramid::ImagePyramid(Size size, int levels) : size_(size)
{
    if (size.width <= 0 || size.height <= 0) {
        throw std::runtime_error("ImagePyramid: empty frame size");
    }
    if (levels < 1 || levels > kMaxLevels) {
        throw std::runtime_error("ImagePyramid: " + std::to_string(levels) + " levels asked, 1.." +
                                 std::to_string(kMaxLevels) + " allowed");
    }
    levels_ = 1;
    int w = size.width;
    int h = size.height;
    while (levels_ < levels && (w + 1) / 2 >= 8 && (h + 1) / 2 >= 8) {
        w = (w + 1) / 2;
        h = (h + 1) / 2;
        buffers_[levels_] = ImageBuffer(w, h, PixelFormat::Gray8);
        ++levels_;
    }
    rowSums_ = std::make_unique<std::uint16_t[]>(static_cast<std::size_t>(size.width));
}

bool ImagePyramid::build(ConstImageView gray) noexcept
{
    if (gray.empty() || gray.format != PixelFormat::Gray8 || gray.size() != size_) {
        return false;
    }
    views_[0] = gray;
    for (int i = 1; i < levels_; ++i) {
        ImageView dst = buffers_[i].view();
        pyramidDown(views_[i - 1], dst, rowSums_.get());
        views_[i] = dst;
    }
    return true;
}

void pyramidDown(ConstImageView src, ImageView dst, std::uint16_t* rows) noexcept
{
    // Vertical first, over contiguous full-width rows, then horizontal with the halving: the
    // stride-2 pass runs on half the rows.
    const int h = src.height;
    for (int y = 0; y < dst.height; ++y) {
        const int c = 2 * y;
        filterColumns(src.row(reflect101(c - 2, h)), src.row(reflect101(c - 1, h)), src.row(c),
                      src.row(reflect101(c + 1, h)), src.row(reflect101(c + 2, h)), src.width,
                      rows);
        filterRowDown(rows, src.width, dst.row(y), dst.width);
    }
}

}  // namespace vision
