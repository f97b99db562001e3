#include "vision/frame_difference.hpp"

#include <cstdlib>
#include <cstring>

namespace vision {

namespace {

bool isColorFormat(PixelFormat f) noexcept
{
    return f == PixelFormat::RGB24 || f == PixelFormat::BGR24 || f == PixelFormat::XRGB8888;
}

template <int Step>
int updateRows(const ConstImageView& rgb, std::uint8_t* previous, int rowBytes, bool havePrevious,
               const ChromaticityPlanes& chroma, const ColorBounds& bounds, int threshold,
               const ImageView& mask) noexcept
{
    int changed = 0;
    const int w = rgb.width;
    for (int y = 0; y < rgb.height; ++y) {
        const std::uint8_t* p = rgb.row(y);
        std::uint8_t* q = previous + static_cast<std::ptrdiff_t>(y) * rowBytes;
        const std::uint8_t* pr = chroma.r.row(y);
        const std::uint8_t* pg = chroma.g.row(y);
        const std::uint8_t* pb = chroma.b.row(y);
        std::uint8_t* pm = mask.row(y);
        for (int x = 0; x < w; ++x, p += Step, q += Step) {
            const int d = std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]);
            if (!havePrevious || d > threshold) {
                pm[x] = matchesColor(bounds, pr[x], pg[x], pb[x]) ? 255 : 0;
                ++changed;
            }
        }
        std::memcpy(previous + static_cast<std::ptrdiff_t>(y) * rowBytes, rgb.row(y),
                    static_cast<std::size_t>(w) * Step);
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
