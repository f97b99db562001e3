#include "statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colorlab {

double componentRange(vision::ColorSpace space, int component) noexcept
{
    using vision::ColorSpace;
    // The bounds documented in vision/src/color_spaces.cpp.
    static constexpr double kRanges[vision::kColorSpaceCount][3] = {
        {255.0, 255.0, 255.0},                                // rgb
        {255.0, 2 * 151.98, 2 * 133.365},                     // yiq
        {360.0, 255.0, 255.0},                                // hsv
        {360.0, 255.0, 255.0},                                // hls
        {100.0, 256.0, 256.0},                                // cielab (a*, b* nominally -128..127)
        {255.0, 255.0, 255.0},                                // chromaticity
        {255.0, 255.0, 255.0},                                // c1c2c3
        {255.0, 255.0, 255.0},                                // l1l2l3
        {0.0, 5.0 + 0.35 / 0.27, 0.34 / 0.06 + 0.60 / 0.63},  // derivative (H unbounded)
        {180.0, 0.0, 0.0},                                    // loghue
    };
    const auto s = static_cast<std::size_t>(space);
    if (s >= std::size(kRanges) || component < 0 || component > 2) {
        return 0.0;
    }
    return kRanges[s][component];
}

double discriminativePower(const vision::ColorSpaceInfo& info, const ComponentStats& a,
                           const ComponentStats& b) noexcept
{
    double d2 = 0.0;
    double sa2 = 0.0;
    double sb2 = 0.0;
    for (int c = 0; c < info.components; ++c) {
        if (!info.chromatic[c]) {
            continue;
        }
        d2 += (a.mean[c] - b.mean[c]) * (a.mean[c] - b.mean[c]);
        sa2 += a.stdev[c] * a.stdev[c];
        sb2 += b.stdev[c] * b.stdev[c];
    }
    const double num = std::sqrt(d2);
    const double den = std::sqrt(sa2) + std::sqrt(sb2);
    if (den <= 0.0) {
        return num > 0.0 ? kDpCap : 0.0;
    }
    return std::min(num / den, kDpCap);
}

std::array<int, 2> pairOf(int n, int k) noexcept
{
    for (int i = 0; i < n; ++i) {
        const int row = n - 1 - i;
        if (k < row) {
            return {i, i + 1 + k};
        }
        k -= row;
    }
    return {0, 0};
}

SpaceStats computeSpaceStats(const Recording& rec, const std::vector<bool>& useRow,
                             vision::ColorSpace space)
{
    const auto& info = vision::colorSpaceInfo(space);
    const std::size_t n = rec.samples.size();
    SpaceStats out;
    out.space = space;
    out.samples.resize(n);
    for (std::size_t s = 0; s < n; ++s) {
        // Two passes (mean, then squared deviations) for accuracy.
        std::vector<std::array<double, 3>> values;
        for (std::size_t row = 0; row < rec.measurements.size(); ++row) {
            if (useRow[row]) {
                const Measurement& m = rec.measurements[row][s];
                values.push_back(vision::convertReference(space, m.r, m.g, m.b));
            }
        }
        ComponentStats& cs = out.samples[s];
        for (int c = 0; c < 3; ++c) {
            double sum = 0.0;
            for (const auto& v : values) {
                sum += v[c];
            }
            cs.mean[c] = values.empty() ? 0.0 : sum / static_cast<double>(values.size());
            double sq = 0.0;
            for (const auto& v : values) {
                sq += (v[c] - cs.mean[c]) * (v[c] - cs.mean[c]);
            }
            cs.stdev[c] =
                values.size() > 1 ? std::sqrt(sq / static_cast<double>(values.size() - 1)) : 0.0;
        }
    }
    int chromatic = 0;
    out.invariancePercent = 0.0;
    for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (const auto& cs : out.samples) {
            sum += cs.stdev[c];
        }
        out.meanStdev[c] = n > 0 ? sum / static_cast<double>(n) : 0.0;
        const double range = componentRange(space, c);
        out.meanStdevPercent[c] = range > 0.0 ? 100.0 * out.meanStdev[c] / range
                                              : std::numeric_limits<double>::quiet_NaN();
        if (c < info.components && info.chromatic[c]) {
            out.invariancePercent += out.meanStdevPercent[c];
            ++chromatic;
        }
    }
    out.invariancePercent /= std::max(chromatic, 1);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i + 1; j < n; ++j) {
            out.dp.push_back(discriminativePower(info, out.samples[i], out.samples[j]));
        }
    }
    if (!out.dp.empty()) {
        double sum = 0.0;
        out.dpMin = out.dp.front();
        for (double d : out.dp) {
            sum += d;
            out.dpMin = std::min(out.dpMin, d);
            out.pairsBelowOne += d < 1.0 ? 1 : 0;
        }
        out.dpMean = sum / static_cast<double>(out.dp.size());
    }
    return out;
}

}  // namespace colorlab
