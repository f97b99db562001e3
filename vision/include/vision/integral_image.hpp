#pragma once
// IntegralImage: summed-area table of an 8-bit image (Viola-Jones; METHOD.md §3). Entry (x, y) of
// the (width + 1) x (height + 1) table is the sum of all pixels above and left of (x, y), so the
// sum over any rectangle costs four reads. The face detector uses it on the motion mask to skip
// windows with too little motion: fraction = rectSum / (255 * area) for a 0/255 mask.
//
// Sums are uint32: exact for images up to 16 843 009 pixels (4096 x 4096 of 255 would overflow),
// far above the reduced resolutions the vision core runs at.

#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <memory>

namespace vision {

class IntegralImage {
public:
    IntegralImage() = default;
    /// Allocates the table for an image of `size` (start-up only).
    explicit IntegralImage(Size size);

    /// Recomputes the table from a Gray8 image of the constructed size. Returns false (table
    /// unchanged) on a size or format mismatch.
    bool compute(const ConstImageView& gray) noexcept;

    /// Sum of the pixels x0 <= x < x1, y0 <= y < y1. The corners must lie in
    /// [0, width] x [0, height] with x0 <= x1 and y0 <= y1 (not checked: hot path).
    std::uint32_t sum(int x0, int y0, int x1, int y1) const noexcept
    {
        const std::uint32_t* top = table_.get() + static_cast<std::ptrdiff_t>(y0) * tableStride_;
        const std::uint32_t* bottom = table_.get() + static_cast<std::ptrdiff_t>(y1) * tableStride_;
        // Unsigned wrap-around cancels: the result is exact even if an intermediate wraps.
        return bottom[x1] - bottom[x0] - top[x1] + top[x0];
    }

    /// Sum over `r` clipped to the image; 0 for an empty intersection.
    std::uint32_t rectSum(const Rect& r) const noexcept;

    /// Mean pixel value over `r` clipped to the image, divided by 255: for a 0/255 mask the
    /// fraction of set pixels. 0 for an empty intersection.
    float maskFraction(const Rect& r) const noexcept;

    Size size() const noexcept { return size_; }
    /// Entries per table row (width + 1).
    int tableStride() const noexcept { return tableStride_; }
    /// The raw (width + 1) x (height + 1) table, row-major.
    const std::uint32_t* table() const noexcept { return table_.get(); }

private:
    Size size_;
    int tableStride_ = 0;
    std::unique_ptr<std::uint32_t[]> table_;
};

}  // namespace vision
