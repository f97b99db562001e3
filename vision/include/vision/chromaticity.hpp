#pragma once
// Chromaticity (normalised RGB), method ch. 3 and 4.3: r = R/(R+G+B), g = G/(R+G+B), b = B/(R+G+B),
// stored as 8-bit values 0..255. Chosen by the illumination experiment (ch. 3) as the most
// invariant space that is also the cheapest: one table look-up per channel.
//
// Exactness: every output equals round(255 * c / (R+G+B)) with halves rounded up, and 0 when the
// sum is 0 (the dissertation's Table 1 OpenCV code divides by 3 in 8 bits first and is off by up to
// 255).

#include "vision/image.hpp"

#include <array>
#include <cstdint>

namespace vision {

/// The look-up table of 4.3: entry [sum][c] = round(255 * c / sum) for sum in 0..765, c in 0..255.
/// 196 KiB, built once at start-up; per pixel the row for its sum is selected once and indexed by
/// each channel (3 look-ups, no divides).
class ChromaticityTable {
public:
    static constexpr int kSums = 766;

    ChromaticityTable();
    const std::uint8_t* row(int sum) const noexcept
    {
        return &table_[static_cast<std::size_t>(sum) * 256];
    }
    /// The exact value the table stores, computed directly (the reference for tests).
    static std::uint8_t exact(int c, int sum) noexcept;

private:
    std::array<std::uint8_t, kSums * 256> table_;
};

/// Output planes: three Gray8 images of the input's size (r, g, b chromaticity).
struct ChromaticityPlanes {
    ImageView r;
    ImageView g;
    ImageView b;
};

/// Converts an RGB24, BGR24 or XRGB8888 image to chromaticity planes with the table; the scalar
/// path, unrolled by 4 (4.3). Returns false (and writes nothing) on an unsupported format or size
/// mismatch.
bool convertChromaticity(const ChromaticityTable& table, const ConstImageView& input,
                         const ChromaticityPlanes& output) noexcept;

}  // namespace vision
