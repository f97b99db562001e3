#pragma once
// LatencyHistogram: per-stage timing with a fixed number of logarithmic bins, so recording a sample
// never allocates and percentiles (p50, p99) come out in constant time and memory.
// Range 1 us .. 10 s over 256 bins: each bin spans ~6.5%, the resolution percentiles report.

#include <array>
#include <cstdint>

namespace firmware {

class LatencyHistogram {
public:
    static constexpr int kBins = 256;

    void record(std::int64_t nanoseconds) noexcept;
    void reset() noexcept;
    std::uint64_t count() const noexcept { return count_; }
    double meanMs() const noexcept;
    double maxMs() const noexcept { return static_cast<double>(maxNs_) * 1e-6; }
    /// Upper edge of the bin holding the p-quantile (p in 0..1), in ms; 0 when empty.
    double percentileMs(double p) const noexcept;

    /// Bin index of a duration, and a bin's upper edge in ns (exposed for tests).
    static int binOf(std::int64_t nanoseconds) noexcept;
    static double binUpperNs(int bin) noexcept;

private:
    std::array<std::uint32_t, kBins> bins_{};
    std::uint64_t count_ = 0;
    double sumNs_ = 0.0;
    std::int64_t maxNs_ = 0;
};

}  // namespace firmware
