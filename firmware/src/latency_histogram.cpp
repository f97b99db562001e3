#include "firmware/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace firmware {

namespace {
constexpr double kMinNs = 1e3;   // 1 us: everything faster lands in bin 0
constexpr double kMaxNs = 1e10;  // 10 s: everything slower lands in the last bin
const double kLogSpan = std::log(kMaxNs / kMinNs);
}  // namespace

int LatencyHistogram::binOf(std::int64_t ns) noexcept
{
    if (ns <= static_cast<std::int64_t>(kMinNs))
        return 0;
    const double f = std::log(static_cast<double>(ns) / kMinNs) / kLogSpan;
    return std::clamp(static_cast<int>(f * (kBins - 1)) + 1, 1, kBins - 1);
}

double LatencyHistogram::binUpperNs(int bin) noexcept
{
    if (bin <= 0)
        return kMinNs;
    return kMinNs * std::exp(kLogSpan * bin / (kBins - 1));
}

void LatencyHistogram::record(std::int64_t ns) noexcept
{
    ns = std::max<std::int64_t>(ns, 0);
    ++bins_[static_cast<std::size_t>(binOf(ns))];
    ++count_;
    sumNs_ += static_cast<double>(ns);
    maxNs_ = std::max(maxNs_, ns);
}

void LatencyHistogram::reset() noexcept
{
    *this = LatencyHistogram{};
}

double LatencyHistogram::meanMs() const noexcept
{
    return count_ ? sumNs_ / static_cast<double>(count_) * 1e-6 : 0.0;
}

double LatencyHistogram::percentileMs(double p) const noexcept
{
    if (count_ == 0)
        return 0.0;
    // The rank of the quantile, 1-based, so p = 0.5 of 2 samples is the first one.
    const auto rank = static_cast<std::uint64_t>(
        std::max(1.0, std::ceil(std::clamp(p, 0.0, 1.0) * static_cast<double>(count_))));
    std::uint64_t seen = 0;
    for (int i = 0; i < kBins; ++i) {
        seen += bins_[static_cast<std::size_t>(i)];
        if (seen >= rank)
            return std::min(binUpperNs(i), static_cast<double>(maxNs_)) * 1e-6;
    }
    return maxMs();
}

}  // namespace firmware
