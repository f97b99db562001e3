#pragma once
// Table-driven fixed-point versions of the colour spaces a tracker would use (§1-§2): integer
// inputs R, G, B in 0..255, no floating point and no divides per pixel except where stated, each
// with its maximum error against the double-precision reference vision::convertReference
// (color_spaces.hpp), measured over the RGB cube and asserted in color_spaces_fixed_test.cpp.
//
// Chromaticity itself is in chromaticity.hpp (exact: round(255 c / sum), error <= 0.5).
//
// Scales (chosen so that each output is an integer with a fixed, documented unit):
//   c1c2c3          0..255, the reference's scale (pi/2 -> 255)
//   HSV hue         1/64 degree, in [-11520, 11520) (= [-180, 180) degrees, wrap at teal)
//   HSV saturation  0..255, the reference's scale
//   C_l, C_ll       Q12: value * 4096 (C_l in [-1.296, 5.0] -> [-5309, 20480])
//   log hue         1/64 degree, in [-5760, 5760] (= [-90, 90] degrees)

#include <array>
#include <cstdint>
#include <memory>

namespace vision {

class FixedColorSpaces {
public:
    static constexpr int kHueUnitsPerDegree = 64;
    static constexpr int kInvariantOne = 4096;  ///< Q12 1.0 of C_l and C_ll

    /// Builds the tables (about 390 KiB on the heap): start-up only.
    FixedColorSpaces();
    ~FixedColorSpaces();
    FixedColorSpaces(const FixedColorSpaces&) = delete;
    FixedColorSpaces& operator=(const FixedColorSpaces&) = delete;

    /// c1 = atan(R / max(G, B)) etc., 0..255: one look-up per component in a 256 x 256 table of
    /// round(255 atan2(n, d) / (pi/2)). Max |error| <= 0.5 units (rounding only).
    std::array<std::uint8_t, 3> c1c2c3(int r, int g, int b) const noexcept;

    /// HSV hue in 1/64 degree: 60 (num / delta) per sextant from a 256 x 256 table of
    /// round(3840 num / delta), plus the sextant's offset. Max |error| <= 0.5 units
    /// (1/128 degree), measured on the circle (179.999 and -180 are 0.001 degree apart);
    /// grey (max == min) gives 0 as the reference.
    std::int16_t hsvHue(int r, int g, int b) const noexcept;

    /// HSV saturation round(255 (max - min) / max), 0 at black: one look-up.
    /// Max |error| <= 0.5 units of 0..255.
    std::uint8_t hsvSaturation(int r, int g, int b) const noexcept;

    /// Gaussian colour-model invariants {C_l, C_ll} in Q12. E, E_l, E_ll are exact integers
    /// (the coefficients times 100); the division by E is a multiplication by a table of
    /// round(2^30 / E) (25501 entries) in 64-bit arithmetic. Black (E = 0) gives 0, 0 as the
    /// reference. Max |error| <= 0.55 Q12 units (0.000134): 0.5 from the final rounding plus at
    /// most |E_ll| 4096 / 2^31 <= 0.03 from the reciprocal's rounding.
    std::array<std::int16_t, 2> gaussianInvariants(int r, int g, int b) const noexcept;

    /// Log hue atan((ln R - ln G) / (ln R + ln G - 2 ln B)) in 1/64 degree, zero channels counted
    /// as 1 as in the reference. Logarithms from a 256-entry Q24 table; the ratio's arctangent
    /// from a 4097-entry table with linear interpolation; one 64-bit integer divide per pixel.
    /// Max |error| <= 0.6 units (1/107 degree) except on the singular set R G = B^2 (not grey),
    /// where the denominator is exactly 0 and the reference's sign depends on double rounding:
    /// there the result is +-90 degrees by the sign of the numerator (and 0 for grey).
    std::int16_t logHue(int r, int g, int b) const noexcept;

private:
    struct Tables;
    std::unique_ptr<const Tables> t_;
};

}  // namespace vision
