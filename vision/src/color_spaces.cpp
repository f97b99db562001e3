// Double-precision reference of every colour space of ch. 3 (METHOD.md §1).
//
// Input: 8-bit R, G, B as doubles in 0..255 (fractional values allowed: colorlab passes the mean
// over a disc of pixels). Scaling of the components, per space:
//
//   rgb           R, G, B              0..255, the input unchanged.
//   yiq           Y                    0..255
//                 I, Q                 the eq. 4 matrix applied to 0..255 values:
//                                      I in [-151.98, 151.98], Q in [-133.37, 133.37].
//   hsv           H                    degrees in [-180, 180): red 0, green 120, blue -120; the
//                                      wrap is at teal (cyan is -180), as in the
//                                      dissertation's 3.1.2.
//                 S                    (mx-mn)/mx scaled to 0..255.
//                 V                    mx, 0..255.
//   hls           H                    as HSV.
//                 L                    (mx+mn)/2, 0..255.
//                 S                    eq. 6 scaled to 0..255.
//   cielab        L*                   0..100, the standard CIE units (eqs. 7-9).
//                 a*, b*               standard CIE units (about -128..127).
//                 XYZ from the RGB value with the sRGB (D65) matrix (eq. 10 is garbled in the
//                 text), applied to R/255, G/255, B/255 directly: like the dissertation we treat
//                 camera RGB as linear (no sRGB gamma expansion), so grey v has
//                 L* = 116 (v/255)^(1/3) - 16; primaries and white match published sRGB values
//                 exactly because 0 and 1 are fixed points of any gamma. White point = XYZ of
//                 RGB (1, 1, 1) (= D65), so every grey has a* = b* = 0.
//   chromaticity  r, g, b              255 c / (R+G+B), 0..255 (the same scale as the fixed-point
//                                      round(255 c / (R+G+B)) of chromaticity.hpp).
//   c1c2c3        c1, c2, c3           atan(R / max(G, B)) etc. scaled from [0, pi/2] to 0..255
//                                      (grey: 127.5).
//   l1l2l3        l1, l2, l3           eq. 13 scaled to 0..255 (they sum to 255 off the grey axis).
//   derivative    H                    E_l / E_ll, a dimensionless ratio, unbounded (hence dropped
//                                      from the chromatic components, as in the
//                                      dissertation's 3.4).
//                 C_l, C_ll            E_l / E and E_ll / E, dimensionless: C_l in
//                                      [-1.296, 5.0], C_ll in [-0.952, 5.667] (the extremes are
//                                      the pure primaries).
//                 [E, E_l, E_ll] = M RGB, M = [[.06,.63,.27],[.30,.04,-.35],[.34,-.60,.17]] (eq.
//                 17, the product of the RGB->XYZ and XYZ->E matrices).
//   loghue        H                    degrees in [-90, 90]: atan of eq. 18 (not atan2; the text's
//                                      formula folds opposite hues together, kept as published).
//
// Every function is total. At the points where a space is unstable the value is defined as:
//   - chromaticity at black (sum 0): r = g = b = 0, as the fixed-point version;
//   - c1c2c3 at black: 0, 0, 0 (atan2(0, 0)); a zero denominator with a positive numerator is
//     the limit pi/2 (255);
//   - l1l2l3 on the grey axis (D = 0, including black): 0, 0, 0;
//   - HSV/HLS hue on the grey axis (mx = mn): 0; HSV S at black and HLS S at black and white: 0;
//   - derivative at black (E = 0): C_l = C_ll = 0; H where E_ll = 0: 0;
//   - log hue: a zero channel counts as 1 (one 8-bit code) so the logarithms are finite; a zero
//     denominator gives +-90 (the limit of atan) or 0 when the numerator is 0 too (grey);
//   - inputs outside 0..255 are clamped to it first, so the ranges above hold.

#include "vision/color_spaces.hpp"

#include "vision/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vision {
namespace {

constexpr ColorSpaceInfo kSpaces[kColorSpaceCount] = {
    {ColorSpace::Rgb, "rgb", 3, {"R", "G", "B"}, {true, true, true}},
    {ColorSpace::Yiq, "yiq", 3, {"Y", "I", "Q"}, {false, true, true}},
    {ColorSpace::Hsv, "hsv", 3, {"H", "S", "V"}, {true, true, false}},
    {ColorSpace::Hls, "hls", 3, {"H", "L", "S"}, {true, false, true}},
    {ColorSpace::Cielab, "cielab", 3, {"L", "a", "b"}, {false, true, true}},
    {ColorSpace::Chromaticity, "chromaticity", 3, {"r", "g", "b"}, {true, true, true}},
    {ColorSpace::C1C2C3, "c1c2c3", 3, {"c1", "c2", "c3"}, {true, true, true}},
    {ColorSpace::L1L2L3, "l1l2l3", 3, {"l1", "l2", "l3"}, {true, true, true}},
    {ColorSpace::GaussianDerivative, "derivative", 3, {"H", "Cl", "Cll"}, {false, true, true}},
    {ColorSpace::LogHue, "loghue", 1, {"H", "", ""}, {true, false, false}},
};

/// Hue of HSV/HLS (eqs. 5-6) in degrees, wrapped to [-180, 180).
double hueDegrees(double r, double g, double b, double mx, double mn) noexcept
{
    const double d = mx - mn;
    if (d <= 0.0) {
        return 0.0;
    }
    double h;
    if (mx == r) {
        h = 60.0 * (g - b) / d;
    } else if (mx == g) {
        h = 60.0 * (2.0 + (b - r) / d);
    } else {
        h = 60.0 * (4.0 + (r - g) / d);
    }
    // Raw h is in [-60, 300); one step of 360 brings it into [-180, 180).
    if (h >= 180.0) {
        h -= 360.0;
    }
    if (h < -180.0) {
        h += 360.0;
    }
    return h;
}

std::array<double, 3> yiq(double r, double g, double b) noexcept
{
    return {0.299 * r + 0.587 * g + 0.114 * b, 0.596 * r - 0.275 * g - 0.321 * b,
            0.212 * r - 0.523 * g + 0.311 * b};
}

std::array<double, 3> hsv(double r, double g, double b) noexcept
{
    const double mx = std::max({r, g, b});
    const double mn = std::min({r, g, b});
    const double s = mx > 0.0 ? 255.0 * (mx - mn) / mx : 0.0;
    return {hueDegrees(r, g, b, mx, mn), s, mx};
}

std::array<double, 3> hls(double r, double g, double b) noexcept
{
    const double mx8 = std::max({r, g, b});
    const double mn8 = std::min({r, g, b});
    const double mx = mx8 / 255.0;
    const double mn = mn8 / 255.0;
    const double l = (mx + mn) / 2.0;
    double s = 0.0;
    if (mx > mn) {
        s = l <= 0.5 ? (mx - mn) / (mx + mn) : (mx - mn) / (2.0 - mx - mn);
    }
    return {hueDegrees(r, g, b, mx8, mn8), 255.0 * l, 255.0 * s};
}

/// sRGB (D65) RGB -> XYZ (IEC 61966-2-1), applied to linear-treated RGB in 0..1.
constexpr double kRgbToXyz[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                    {0.2126729, 0.7151522, 0.0721750},
                                    {0.0193339, 0.1191920, 0.9503041}};

double labF(double t) noexcept
{
    return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0;
}

std::array<double, 3> cielab(double r, double g, double b) noexcept
{
    const double in[3] = {r / 255.0, g / 255.0, b / 255.0};
    double xyz[3];
    double white[3];  // XYZ of RGB (1, 1, 1): the row sums
    for (int i = 0; i < 3; ++i) {
        xyz[i] = kRgbToXyz[i][0] * in[0] + kRgbToXyz[i][1] * in[1] + kRgbToXyz[i][2] * in[2];
        white[i] = kRgbToXyz[i][0] + kRgbToXyz[i][1] + kRgbToXyz[i][2];
    }
    const double yr = xyz[1] / white[1];
    const double l = yr > 0.008856 ? 116.0 * std::cbrt(yr) - 16.0 : 903.3 * yr;
    const double fx = labF(xyz[0] / white[0]);
    const double fy = labF(yr);
    const double fz = labF(xyz[2] / white[2]);
    return {l, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

std::array<double, 3> chromaticity(double r, double g, double b) noexcept
{
    const double sum = r + g + b;
    if (sum <= 0.0) {
        return {0.0, 0.0, 0.0};
    }
    return {255.0 * r / sum, 255.0 * g / sum, 255.0 * b / sum};
}

std::array<double, 3> c1c2c3(double r, double g, double b) noexcept
{
    // atan2(n, d) with n, d >= 0 is atan(n / d), pi/2 at d = 0 < n, and 0 at black.
    constexpr double k = 255.0 / (std::numbers::pi / 2.0);
    return {k * std::atan2(r, std::max(g, b)), k * std::atan2(g, std::max(r, b)),
            k * std::atan2(b, std::max(r, g))};
}

std::array<double, 3> l1l2l3(double r, double g, double b) noexcept
{
    const double rg = (r - g) * (r - g);
    const double rb = (r - b) * (r - b);
    const double gb = (g - b) * (g - b);
    const double d = rg + rb + gb;
    if (d <= 0.0) {
        return {0.0, 0.0, 0.0};
    }
    return {255.0 * rg / d, 255.0 * rb / d, 255.0 * gb / d};
}

std::array<double, 3> gaussianDerivative(double r, double g, double b) noexcept
{
    const double e = 0.06 * r + 0.63 * g + 0.27 * b;
    const double el = 0.30 * r + 0.04 * g - 0.35 * b;
    const double ell = 0.34 * r - 0.60 * g + 0.17 * b;
    const double h = ell != 0.0 ? el / ell : 0.0;
    if (e <= 0.0) {
        return {h, 0.0, 0.0};
    }
    return {h, el / e, ell / e};
}

std::array<double, 3> logHue(double r, double g, double b) noexcept
{
    const double lr = std::log(std::max(r, 1.0));
    const double lg = std::log(std::max(g, 1.0));
    const double lb = std::log(std::max(b, 1.0));
    const double num = lr - lg;
    const double den = lr + lg - 2.0 * lb;
    double h;
    if (den != 0.0) {
        h = toDegrees(std::atan(num / den));
    } else {
        h = num > 0.0 ? 90.0 : (num < 0.0 ? -90.0 : 0.0);
    }
    return {h, 0.0, 0.0};
}

}  // namespace

std::span<const ColorSpaceInfo> colorSpaces() noexcept
{
    return kSpaces;
}

const ColorSpaceInfo& colorSpaceInfo(ColorSpace space) noexcept
{
    const auto i = static_cast<std::size_t>(space);
    return i < std::size(kSpaces) ? kSpaces[i] : kSpaces[0];
}

std::array<double, 3> convertReference(ColorSpace space, double r, double g, double b) noexcept
{
    // NaN fails every comparison, so clamp it to 0 explicitly.
    auto clamp = [](double v) { return v > 0.0 ? (v < 255.0 ? v : 255.0) : 0.0; };
    r = clamp(r);
    g = clamp(g);
    b = clamp(b);
    switch (space) {
        case ColorSpace::Rgb:
            return {r, g, b};
        case ColorSpace::Yiq:
            return yiq(r, g, b);
        case ColorSpace::Hsv:
            return hsv(r, g, b);
        case ColorSpace::Hls:
            return hls(r, g, b);
        case ColorSpace::Cielab:
            return cielab(r, g, b);
        case ColorSpace::Chromaticity:
            return chromaticity(r, g, b);
        case ColorSpace::C1C2C3:
            return c1c2c3(r, g, b);
        case ColorSpace::L1L2L3:
            return l1l2l3(r, g, b);
        case ColorSpace::GaussianDerivative:
            return gaussianDerivative(r, g, b);
        case ColorSpace::LogHue:
            return logHue(r, g, b);
    }
    return {0.0, 0.0, 0.0};
}

}  // namespace vision
