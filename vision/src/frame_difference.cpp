#include "vision/frame_difference.hpp"

#include <cstdlib>
#include <cstring>

namespace vision {

namespace {

bool isColorFormat(PixelFormat f) noexcept
{
    return f == PixelFormat::RGB24 || f == PixelFormat::BGR24 || f == PixelFormat::XRGB8888;
}

/// One row: where |dR| + |dG| + |dB| exceeds the threshold (or everywhere without a previous
/// frame), the mask becomes the colour test's answer. Written without branches or early exits so
/// the compiler turns it into vector code (NEON's de-interleaving loads on the product): the test
/// and the difference cost a few instructions per pixel, instead of a branch per pixel.
template <int Step>
int updateRow(const std::uint8_t* __restrict p, const std::uint8_t* __restrict q,
              const std::uint8_t* __restrict pr, const std::uint8_t* __restrict pg,
              const std::uint8_t* __restrict pb, std::uint8_t* __restrict pm, int w, int threshold,
              bool havePrevious, const ColorBounds& bounds) noexcept
{
    const std::uint8_t lo0 = bounds.lo[0], lo1 = bounds.lo[1], lo2 = bounds.lo[2];
    // An empty channel range (lo > hi) matches nothing.
    const bool empty =
        bounds.lo[0] > bounds.hi[0] || bounds.lo[1] > bounds.hi[1] || bounds.lo[2] > bounds.hi[2];
    const std::uint8_t span0 = empty ? 0 : static_cast<std::uint8_t>(bounds.hi[0] - lo0);
    const std::uint8_t span1 = static_cast<std::uint8_t>(bounds.hi[1] - lo1);
    const std::uint8_t span2 = static_cast<std::uint8_t>(bounds.hi[2] - lo2);
    const std::uint8_t none = empty ? 0 : 255;
    const int limit = havePrevious ? threshold : -1;
    int changed = 0;
    for (int x = 0; x < w; ++x) {
        const int d = std::abs(p[Step * x] - q[Step * x]) +
                      std::abs(p[Step * x + 1] - q[Step * x + 1]) +
                      std::abs(p[Step * x + 2] - q[Step * x + 2]);
        // 0 or 255 each, combined with & and | (no && or ?: : those are branches).
        const std::uint8_t match =
            static_cast<std::uint8_t>(-(static_cast<std::uint8_t>(pr[x] - lo0) <= span0)) &
            static_cast<std::uint8_t>(-(static_cast<std::uint8_t>(pg[x] - lo1) <= span1)) &
            static_cast<std::uint8_t>(-(static_cast<std::uint8_t>(pb[x] - lo2) <= span2)) & none;
        const std::uint8_t change = static_cast<std::uint8_t>(-(d > limit));
        pm[x] = static_cast<std::uint8_t>((match & change) | (pm[x] & ~change));
        changed += change & 1;
    }
    return changed;
}

template <int Step>
int updateRows(const ConstImageView& rgb, std::uint8_t* previous, int rowBytes, bool havePrevious,
               const ChromaticityPlanes& chroma, const ColorBounds& bounds, int threshold,
               const ImageView& mask) noexcept
{
    int changed = 0;
    const int w = rgb.width;
    for (int y = 0; y < rgb.height; ++y) {
        std::uint8_t* q = previous + static_cast<std::ptrdiff_t>(y) * rowBytes;
        changed += updateRow<Step>(rgb.row(y), q, chroma.r.row(y), chroma.g.row(y), chroma.b.row(y),
                                   mask.row(y), w, threshold, havePrevious, bounds);
        std::memcpy(q, rgb.row(y), static_cast<std::size_t>(w) * Step);
    }
    return changed;
}

}  // namespace

FrameDifference::FrameDifference(Size size)
    : size_(size),
      rowBytes_(size.width * 4),
      previous_(std::make_unique<std::uint8_t[]>(static_cast<std::size_t>(size.width) * 4 *
                                                 static_cast<std::size_t>(size.height)))
{
}

int FrameDifference::updateMask(const ConstImageView& rgb, const ChromaticityPlanes& chroma,
                                const ColorBounds& bounds, int threshold,
                                const ImageView& mask) noexcept
{
    if (rgb.size() != size_ || !isColorFormat(rgb.format) || mask.size() != size_ ||
        chroma.r.size() != size_ || chroma.g.size() != size_ || chroma.b.size() != size_)
        return -1;
    const bool have = havePrevious_ && previousFormat_ == rgb.format;
    const int n =
        rgb.format == PixelFormat::XRGB8888
            ? updateRows<4>(rgb, previous_.get(), rowBytes_, have, chroma, bounds, threshold, mask)
            : updateRows<3>(rgb, previous_.get(), rowBytes_, have, chroma, bounds, threshold, mask);
    havePrevious_ = true;
    previousFormat_ = rgb.format;
    return n;
}

void FrameDifference::remember(const ConstImageView& rgb) noexcept
{
    if (rgb.size() != size_ || !isColorFormat(rgb.format))
        return;
    const std::size_t bytes = static_cast<std::size_t>(size_.width) * bytesPerPixel(rgb.format);
    for (int y = 0; y < size_.height; ++y)
        std::memcpy(previous_.get() + static_cast<std::ptrdiff_t>(y) * rowBytes_, rgb.row(y),
                    bytes);
    havePrevious_ = true;
    previousFormat_ = rgb.format;
}

}  // namespace vision
