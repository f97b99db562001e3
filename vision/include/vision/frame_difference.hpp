#pragma once
// FrameDifference: step 3 of the card tracker (METHOD.md §2). The object mask is updated only where
// the frame changed since the previous frame: |dR| + |dG| + |dB| above a threshold. Unchanged
// pixels keep their mask value, so a still hand over the card stays masked out and the test
// costs nothing on a static scene.

#include "vision/card_color_model.hpp"
#include "vision/chromaticity.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <memory>

namespace vision {

/// The code that computes the mask: every path gives the same bytes as the scalar reference.
enum class DifferencePath : std::uint8_t {
    Scalar,  ///< the reference loop
    Neon,    ///< aarch64 (the product): 16 pixels a step
    Best,    ///< the fastest path this build has (NEON on aarch64, Scalar elsewhere)
};

/// True when this build can run the path (Scalar and Best always).
bool differencePathAvailable(DifferencePath path) noexcept;

class FrameDifference {
public:
    /// Keeps a copy of the previous frame of `size` (up to 4 bytes per pixel).
    explicit FrameDifference(Size size);

    /// Re-tests the colour of every changed pixel of `rgb` (RGB24, BGR24 or XRGB8888; the sum of
    /// channel differences does not depend on the order) and writes 255/0 into `mask` there;
    /// then remembers `rgb` as the previous frame. The first frame (or after forget()) counts as
    /// changed everywhere. Returns the number of changed pixels, -1 on a size/format mismatch or
    /// a path this build does not have.
    int updateMask(const ConstImageView& rgb, const ChromaticityPlanes& chroma,
                   const ColorBounds& bounds, int threshold, const ImageView& mask,
                   DifferencePath path = DifferencePath::Best) noexcept;

    /// Only remembers `rgb` (for frames whose mask is computed otherwise).
    void remember(const ConstImageView& rgb) noexcept;
    /// The next frame counts as changed everywhere.
    void forget() noexcept { havePrevious_ = false; }

private:
    Size size_;
    int rowBytes_ = 0;  // bytes of one stored row: width * 4 at most
    std::unique_ptr<std::uint8_t[]> previous_;
    PixelFormat previousFormat_ = PixelFormat::Gray8;
    bool havePrevious_ = false;
};

}  // namespace vision
