#pragma once
// The measures of the illumination experiment (3.4): per-component standard deviation over time
// and the discriminative power between samples (eq. 19).

#include "sampling.hpp"
#include "vision/color_spaces.hpp"

#include <array>
#include <vector>

namespace colorlab {

/// The possible range (max - min) of a component as vision::convertReference scales it, used to
/// express a standard deviation as a percentage of the range (the dissertation's Figure 67);
/// 0 for the unbounded H = E_l / E_ll of the derivative space.
double componentRange(vision::ColorSpace space, int component) noexcept;

/// One sample's series in one space, over the frames used.
struct ComponentStats {
    std::array<double, 3> mean{};
    std::array<double, 3> stdev{};  ///< sample standard deviation (n - 1), 0 for one frame
};

/// Discriminative power between two samples over the chromatic components c (the space's
/// ColorSpaceInfo::chromatic), eq. 19: |mean(c_i) - mean(c_j)| / (|stdev(c_i)| + |stdev(c_j)|),
/// |.| the Euclidean norm over those components. A zero denominator gives kDpCap when the means
/// differ and 0 when they do not; larger values are capped at kDpCap too.
inline constexpr double kDpCap = 1e6;
double discriminativePower(const vision::ColorSpaceInfo& info, const ComponentStats& a,
                           const ComponentStats& b) noexcept;

/// Everything computed for one space.
struct SpaceStats {
    vision::ColorSpace space{};
    std::vector<ComponentStats> samples;  ///< per sample
    /// Per component: the mean over samples of the standard deviation, absolute and as % of the
    /// component range (NaN where the range is unbounded).
    std::array<double, 3> meanStdev{};
    std::array<double, 3> meanStdevPercent{};
    /// Invariance: the mean of meanStdevPercent over the chromatic components (lower is better).
    double invariancePercent = 0.0;
    /// DP for every pair i < j, in the order (0,1), (0,2), ..., (1,2), ...
    std::vector<double> dp;
    double dpMean = 0.0;
    double dpMin = 0.0;
    int pairsBelowOne = 0;  ///< pairs the noise makes indistinguishable (DP < 1)
};

/// Converts every used row of the recording to `space` and computes its statistics. `useRow[i]`
/// says whether row i counts (false for excluded saturated frames).
SpaceStats computeSpaceStats(const Recording& rec, const std::vector<bool>& useRow,
                             vision::ColorSpace space);

/// The pair (i, j) of DP index k for n samples.
std::array<int, 2> pairOf(int n, int k) noexcept;

}  // namespace colorlab
