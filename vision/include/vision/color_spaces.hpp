#pragma once
// The colour spaces of the illumination experiment (method ch. 3, METHOD.md §1): a double-precision
// reference for each (what colorlab measures with) and, where a tracker would use the space, a
// table-driven fixed-point version whose error bound against the reference is stated and tested
// (see color_spaces_fixed.hpp).

#include <array>
#include <cstdint>
#include <span>

namespace vision {

enum class ColorSpace : std::uint8_t {
    Rgb,                 ///< the input, for comparison
    Yiq,                 ///< 3.1.1
    Hsv,                 ///< 3.1.2, hue in degrees [-180, 180) (wraps near teal, not red)
    Hls,                 ///< 3.1.3
    Cielab,              ///< 3.1.4, sRGB (D65) RGB->XYZ matrix; white = XYZ of RGB (1,1,1)
    Chromaticity,        ///< 3.1.5, normalised RGB
    C1C2C3,              ///< 3.1.6, Gevers & Smeulders
    L1L2L3,              ///< 3.1.6, Gevers & Smeulders
    GaussianDerivative,  ///< 3.1.7, Geusebroek: H, C_l, C_ll
    LogHue,              ///< 3.1.8, Finlayson & Schaefer (one component)
};
inline constexpr int kColorSpaceCount = 10;

struct ColorSpaceInfo {
    ColorSpace space;
    const char* name;               ///< short, lower case, for files and tables: "yiq", "loghue"
    int components;                 ///< 1..3
    const char* componentNames[3];  ///< e.g. {"Y", "I", "Q"}
    /// Components that carry colour rather than brightness: the ones the invariance and
    /// discriminative-power measures use (Y of YIQ, V of HSV, L of HLS/CIELAB and H of the
    /// Gaussian derivative space are dropped, as in §1).
    bool chromatic[3];
};

/// Every space, in the order of the enum.
std::span<const ColorSpaceInfo> colorSpaces() noexcept;
const ColorSpaceInfo& colorSpaceInfo(ColorSpace space) noexcept;

/// Double-precision reference: 8-bit R, G, B (0..255) to the space's components, with the scaling
/// documented per space in color_spaces.cpp. Unused components are 0. Total: defined for every
/// input, including black and grey where a space is unstable (the value there is documented).
std::array<double, 3> convertReference(ColorSpace space, double r, double g, double b) noexcept;

}  // namespace vision
