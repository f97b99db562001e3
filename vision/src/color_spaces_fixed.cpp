#include "vision/color_spaces_fixed.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vision {

namespace {
constexpr int kLogShift = 24;      // Q24 natural logarithms
constexpr int kAtanSteps = 4096;   // atan table over ratios [0, 1]
constexpr int kAtanFracBits = 4;   // ratio in Q16 = table index (Q12) + 4 interpolation bits
constexpr int kAtanScale = 65536;  // atan table unit: 1/65536 of the output unit (1/64 degree)
constexpr int kRecipShift = 30;    // 1/E table in Q30
constexpr int kMaxE = 100 * 255;   // 6 + 63 + 27 = 96 and 34 + 17 = 51 (C_ll's E is the same E)
}  // namespace

struct FixedColorSpaces::Tables {
    std::uint8_t atan2Table[256][256];  ///< [n][d] round(255 atan2(n, d) / (pi/2))
    std::uint16_t hue[256][256];        ///< [delta][num] round(3840 num / delta), num <= delta
    std::uint8_t saturation[256][256];  ///< [max][delta] round(255 delta / max)
    std::uint32_t recipE[kMaxE + 1];    ///< round(2^30 / E), 0 for E = 0
    std::int32_t log[256];              ///< round(ln(max(c, 1)) 2^24)
    std::int64_t atan[kAtanSteps + 2];  ///< round(atan(i / 4096) in 1/64 degree * 65536)
};

FixedColorSpaces::FixedColorSpaces()
{
    auto t = std::make_unique<Tables>();
    const double toC = 255.0 / (std::numbers::pi / 2.0);
    for (int n = 0; n < 256; ++n)
        for (int d = 0; d < 256; ++d) {
            t->atan2Table[n][d] = static_cast<std::uint8_t>(std::lround(toC * std::atan2(n, d)));
            t->hue[d][n] = static_cast<std::uint16_t>(d > 0 && n <= d ? (3840 * n + d / 2) / d : 0);
            // n is max, d is delta here; halves up as round(255 c / sum) elsewhere.
            t->saturation[n][d] =
                static_cast<std::uint8_t>(n > 0 && d <= n ? (510 * d + n) / (2 * n) : 0);
        }
    t->recipE[0] = 0;
    for (int e = 1; e <= kMaxE; ++e)
        t->recipE[e] = static_cast<std::uint32_t>(((std::int64_t{1} << kRecipShift) + e / 2) / e);
    for (int c = 0; c < 256; ++c)
        t->log[c] = static_cast<std::int32_t>(
            std::llround(std::log(std::max(c, 1)) * static_cast<double>(1 << kLogShift)));
    const double toUnits = 180.0 / std::numbers::pi * kHueUnitsPerDegree * kAtanScale;
    for (int i = 0; i <= kAtanSteps + 1; ++i)
        t->atan[i] = std::llround(std::atan(static_cast<double>(i) / kAtanSteps) * toUnits);
    t_ = std::move(t);
}

FixedColorSpaces::~FixedColorSpaces() = default;

std::array<std::uint8_t, 3> FixedColorSpaces::c1c2c3(int r, int g, int b) const noexcept
{
    return {t_->atan2Table[r][std::max(g, b)], t_->atan2Table[g][std::max(r, b)],
            t_->atan2Table[b][std::max(r, g)]};
}

std::int16_t FixedColorSpaces::hsvHue(int r, int g, int b) const noexcept
{
    const int mx = std::max({r, g, b});
    const int delta = mx - std::min({r, g, b});
    if (delta == 0)
        return 0;
    // Same sextant choice as the reference (red first, then green).
    int num, offset;
    if (mx == r)
        num = g - b, offset = 0;
    else if (mx == g)
        num = b - r, offset = 120 * kHueUnitsPerDegree;
    else
        num = r - g, offset = 240 * kHueUnitsPerDegree;
    const int mag = t_->hue[delta][num < 0 ? -num : num];
    int h = offset + (num < 0 ? -mag : mag);
    constexpr int kHalfTurn = 180 * kHueUnitsPerDegree;
    if (h >= kHalfTurn)
        h -= 2 * kHalfTurn;
    return static_cast<std::int16_t>(h);
}

std::uint8_t FixedColorSpaces::hsvSaturation(int r, int g, int b) const noexcept
{
    const int mx = std::max({r, g, b});
    return t_->saturation[mx][mx - std::min({r, g, b})];
}

std::array<std::int16_t, 2> FixedColorSpaces::gaussianInvariants(int r, int g, int b) const noexcept
{
    const int e = 6 * r + 63 * g + 27 * b;
    const std::int64_t el = 30 * r + 4 * g - 35 * b;
    const std::int64_t ell = 34 * r - 60 * g + 17 * b;
    const std::int64_t recip = t_->recipE[e];
    // Q30 reciprocal times the exact numerator, rounded (halves up) to Q12.
    constexpr int shift = kRecipShift - 12;
    constexpr std::int64_t half = std::int64_t{1} << (shift - 1);
    return {static_cast<std::int16_t>((el * recip + half) >> shift),
            static_cast<std::int16_t>((ell * recip + half) >> shift)};
}

std::int16_t FixedColorSpaces::logHue(int r, int g, int b) const noexcept
{
    const std::int64_t lr = t_->log[r], lg = t_->log[g], lb = t_->log[b];
    const std::int64_t num = lr - lg;
    std::int64_t den = lr + lg - 2 * lb;
    // True non-zero denominators of 8-bit inputs exceed 2^24 / 65025 (about 258 units); table
    // rounding leaves at most 2 units where R G = B^2 exactly.
    if (den >= -2 && den <= 2)
        den = 0;
    constexpr int kQuarter = 90 * kHueUnitsPerDegree;
    if (den == 0)
        return static_cast<std::int16_t>(num > 0 ? kQuarter : (num < 0 ? -kQuarter : 0));
    const std::int64_t a = num < 0 ? -num : num;
    const std::int64_t d = den < 0 ? -den : den;
    const bool swap = a > d;
    // Ratio in [0, 1] as Q16: table index (Q12) and 4 bits of linear interpolation.
    const std::int64_t ratio = swap ? ((d << 16) + a / 2) / a : ((a << 16) + d / 2) / d;
    const std::int64_t i = ratio >> kAtanFracBits;
    const std::int64_t frac = ratio & ((1 << kAtanFracBits) - 1);
    const std::int64_t angle =
        t_->atan[i] + (((t_->atan[i + 1] - t_->atan[i]) * frac) >> kAtanFracBits);
    std::int64_t h = (angle + kAtanScale / 2) / kAtanScale;
    if (swap)
        h = kQuarter - h;
    return static_cast<std::int16_t>((num < 0) != (den < 0) ? -h : h);
}

}  // namespace vision
