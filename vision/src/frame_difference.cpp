#include "vision/frame_difference.hpp"

#include "frame_difference_kernels.hpp"

#include <cstring>

namespace vision {

namespace {

namespace dd = difference_detail;

bool isColorFormat(PixelFormat f) noexcept
{
    return f == PixelFormat::RGB24 || f == PixelFormat::BGR24 || f == PixelFormat::XRGB8888;
}

using RowKernel = int (*)(const dd::Row&, int, int, const ColorBands&) noexcept;

/// The row kernel of `path` for `step` bytes a pixel; null when this build has no such path.
RowKernel kernelFor(DifferencePath path, int step) noexcept
{
#if defined(__aarch64__)
    if (path == DifferencePath::Neon || path == DifferencePath::Best)
        return step == 4 ? dd::updateRowNeon4 : dd::updateRowNeon3;
#else
    if (path == DifferencePath::Neon)
        return nullptr;
#endif
    return step == 4 ? dd::updateRowScalar<4> : dd::updateRowScalar<3>;
}

}  // namespace

bool differencePathAvailable(DifferencePath path) noexcept
{
    return kernelFor(path, 3) != nullptr;
}

FrameDifference::FrameDifference(Size size)
    : size_(size),
      rowBytes_(size.width * 4),
      previous_(std::make_unique<std::uint8_t[]>(static_cast<std::size_t>(size.width) * 4 *
                                                 static_cast<std::size_t>(size.height)))
{
}

// §2 step 3, one row at a time: where the frame changed the mask is the colour test's answer,
// elsewhere it keeps its value; the row is then remembered for the next frame.
int FrameDifference::updateMask(const ConstImageView& rgb, const ChromaticityPlanes& chroma,
                                const ColorBounds& bounds, int threshold, const ImageView& mask,
                                DifferencePath path) noexcept
{
    if (rgb.size() != size_ || !isColorFormat(rgb.format) || mask.size() != size_ ||
        chroma.r.size() != size_ || chroma.g.size() != size_ || chroma.b.size() != size_)
        return -1;
    const int step = rgb.format == PixelFormat::XRGB8888 ? 4 : 3;
    const RowKernel kernel = kernelFor(path, step);
    if (kernel == nullptr)
        return -1;
    const bool have = havePrevious_ && previousFormat_ == rgb.format;
    const int limit = have ? threshold : -1;
    const ColorBands bands = bandsOf(bounds);
    int changed = 0;
    for (int y = 0; y < size_.height; ++y) {
        const dd::Row row{
            rgb.row(y),      previous_.get() + static_cast<std::ptrdiff_t>(y) * rowBytes_,
            chroma.r.row(y), chroma.g.row(y),
            chroma.b.row(y), mask.row(y)};
        changed += kernel(row, size_.width, limit, bands);
    }
    havePrevious_ = true;
    previousFormat_ = rgb.format;
    return changed;
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
