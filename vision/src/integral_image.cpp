#include "vision/integral_image.hpp"

#include <algorithm>

namespace vision {

IntegralImage::IntegralImage(Size size)
    : size_(size),
      tableStride_(size.width + 1),
      table_(std::make_unique<std::uint32_t[]>(static_cast<std::size_t>(size.width + 1) *
                                               static_cast<std::size_t>(size.height + 1)))
{
    // Row 0 and column 0 stay zero for ever: rectangle sums need no edge cases.
}

bool IntegralImage::compute(const ConstImageView& gray) noexcept
{
    if (!table_ || gray.empty() || gray.format != PixelFormat::Gray8 || gray.size() != size_) {
        return false;
    }
    const int w = size_.width;
    for (int y = 0; y < size_.height; ++y) {
        const std::uint8_t* src = gray.row(y);
        const std::uint32_t* above = table_.get() + static_cast<std::ptrdiff_t>(y) * tableStride_;
        std::uint32_t* out = table_.get() + static_cast<std::ptrdiff_t>(y + 1) * tableStride_;
        std::uint32_t rowSum = 0;
        for (int x = 0; x < w; ++x) {
            rowSum += src[x];
            out[x + 1] = above[x + 1] + rowSum;
        }
    }
    return true;
}

std::uint32_t IntegralImage::rectSum(const Rect& r) const noexcept
{
    const int x0 = std::clamp(r.x, 0, size_.width);
    const int y0 = std::clamp(r.y, 0, size_.height);
    const int x1 = std::clamp(r.x + r.width, 0, size_.width);
    const int y1 = std::clamp(r.y + r.height, 0, size_.height);
    if (x1 <= x0 || y1 <= y0 || !table_) {
        return 0;
    }
    return sum(x0, y0, x1, y1);
}

float IntegralImage::maskFraction(const Rect& r) const noexcept
{
    const int x0 = std::clamp(r.x, 0, size_.width);
    const int y0 = std::clamp(r.y, 0, size_.height);
    const int x1 = std::clamp(r.x + r.width, 0, size_.width);
    const int y1 = std::clamp(r.y + r.height, 0, size_.height);
    if (x1 <= x0 || y1 <= y0 || !table_) {
        return 0.0f;
    }
    const float area = static_cast<float>(x1 - x0) * static_cast<float>(y1 - y0);
    return static_cast<float>(sum(x0, y0, x1, y1)) / (255.0f * area);
}

}  // namespace vision
