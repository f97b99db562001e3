#pragma once
// Chromaticity (normalised RGB), METHOD.md §1-§2 (dissertation ch. 3, 4.3):
// r = R/(R+G+B), g = G/(R+G+B), b = B/(R+G+B), stored as 8-bit values 0..255. Chosen by the
// illumination experiment (§1) as the most invariant space that is also the cheapest: one table
// look-up per channel.
//
// Exactness: every output equals round(255 * c / (R+G+B)) with halves rounded up, and 0 when the
// sum is 0 (the dissertation's Table 1 OpenCV code divides by 3 in 8 bits first and is off by up to
// 255). The table loop below is the reference; the SIMD paths (NEON on the product, AVX2 on an
// x86-64 development machine; ChromaticityPath) compute the same bytes arithmetically and are
// tested bit-exact against it.

#include "vision/image.hpp"

#include <array>
#include <cstdint>

namespace vision {

/// The look-up table of §2 (dissertation 4.3): entry [sum][c] = round(255 * c / sum) for sum in
/// 0..765, c in 0..255. 196 KiB, built once at start-up; per pixel the row for its sum is selected
/// once and indexed by each channel (3 look-ups, no divides).
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

/// Implementations of the conversion. Every path produces exactly the table's values
/// (round(255 c / sum), halves up, 0 for sum 0); the SIMD paths compute them with a reciprocal and
/// an exact integer correction instead of the table (proof in chromaticity.cpp).
enum class ChromaticityPath : std::uint8_t {
    Scalar,  ///< the table look-up loop of §2 (dissertation 4.3), unrolled by 4: the reference
    Avx2,    ///< x86-64 with AVX2: 32 pixels a step, byte shuffles de-interleave them
    Neon,    ///< aarch64 (the product): 16 pixels a step, vld3/vld4 de-interleave them
    Best,    ///< the fastest path this CPU supports (Scalar on x86-64 without AVX2)
};

const char* chromaticityPathName(ChromaticityPath path) noexcept;
/// True when this build and CPU can run the path (Scalar and Best always).
bool chromaticityPathAvailable(ChromaticityPath path) noexcept;
/// The concrete path Best stands for on this CPU.
ChromaticityPath bestChromaticityPath() noexcept;

/// Converts an image to chromaticity planes. Formats: RGB24, BGR24, XRGB8888, and the YUV camera
/// formats YUYV and NV12 (even width; NV12 even height), which are first converted to RGB with the
/// fixed-point BT.601 formula of yuv.hpp (in 256-pixel pieces on the stack): chromaticity of YUV
/// input is by definition the chromaticity of that fixed-point RGB. Returns false (and writes
/// nothing) on an unsupported format, a size mismatch, or a path this CPU cannot run.
bool convertChromaticity(const ChromaticityTable& table, const ConstImageView& input,
                         const ChromaticityPlanes& output, ChromaticityPath path) noexcept;

/// The same with ChromaticityPath::Best (what the pipeline uses).
bool convertChromaticity(const ChromaticityTable& table, const ConstImageView& input,
                         const ChromaticityPlanes& output) noexcept;

/// For tests: out[i] = table entry row(sum[i])[min(c[i], sum[i])] computed by the path's own
/// arithmetic (no table on SIMD paths), sum[i] in 0..765, c[i] in 0..255. Lets a test run every
/// (c, sum) pair through the SIMD kernel. Returns false for an unavailable path.
bool chromaticityQuotients(const ChromaticityTable& table, ChromaticityPath path,
                           const std::uint16_t* c, const std::uint16_t* sum, std::uint8_t* out,
                           int n) noexcept;

}  // namespace vision
