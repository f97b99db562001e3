#pragma once
// Grey image pyramid for pyramidal Lucas-Kanade (METHOD.md §3, "Tracking"): level 0 is the frame
// itself (a view, not a copy), each further level halves the previous one with the 5-tap binomial
// filter [1 4 6 4 1]/16 in both directions (the filter of cv::pyrDown, in integer arithmetic,
// borders reflected without repeating the edge pixel), so a point at (x, y) on level 0 is at
// (x / 2^L, y / 2^L) on level L.

#include "vision/image.hpp"

#include <memory>

namespace vision {

/// A pyramid of Gray8 levels. The buffers for levels 1.. are allocated once for the configured
/// frame size; build() fills them for each frame and never allocates. Level 0 is a view of the
/// frame passed to build(), which must stay valid while the pyramid is used.
class ImagePyramid {
public:
    static constexpr int kMaxLevels = 8;

    ImagePyramid() = default;
    /// Buffers for a frame of `size` and `levels` levels (1..kMaxLevels, 4 by default). Levels are
    /// dropped while the smallest would be under 8 pixels wide or high. Throws std::runtime_error
    /// on an empty size or a bad level count.
    explicit ImagePyramid(Size size, int levels = 4);

    /// Builds all levels from a Gray8 frame of the configured size; false (pyramid unchanged) on a
    /// wrong size or format.
    bool build(ConstImageView gray) noexcept;

    int levels() const noexcept { return levels_; }
    Size size() const noexcept { return size_; }
    /// Level `i` (0 = the frame); empty before the first successful build().
    ConstImageView level(int i) const noexcept { return views_[i]; }

private:
    Size size_{};
    int levels_ = 0;
    ImageBuffer buffers_[kMaxLevels];           ///< levels 1.. (index 0 unused)
    ConstImageView views_[kMaxLevels]{};        ///< all levels, level 0 = the frame
    std::unique_ptr<std::uint16_t[]> rowSums_;  ///< 5 rows of horizontally filtered sums
};

/// Halves `src` into `dst` ((src.width + 1) / 2 x (src.height + 1) / 2) with the 5-tap binomial
/// filter; `rows` is scratch for src.width values. Both Gray8.
void pyramidDown(ConstImageView src, ImageView dst, std::uint16_t* rows) noexcept;

}  // namespace vision
