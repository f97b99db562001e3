#pragma once
// Summaries of absolute errors as the evaluations print them (mirror-eval roll and track, and the
// roll peer tests that follow mirror-eval roll's protocol): mean, fraction within a limit,
// percentile; and the covariance behind mirror-eval roll's truth-noise estimate.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace mirror_eval {

/// Mean of `v`; 0 when empty.
inline double meanOf(const std::vector<double>& v)
{
    double sum = 0;
    for (double x : v)
        sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

/// Sample covariance of `a` and `b` (the same length, at least 2; else 0).
inline double covarianceOf(const std::vector<double>& a, const std::vector<double>& b)
{
    if (a.size() != b.size() || a.size() < 2)
        return 0.0;
    const double ma = meanOf(a), mb = meanOf(b);
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        sum += (a[i] - ma) * (b[i] - mb);
    return sum / static_cast<double>(a.size() - 1);
}

/// The absolute errors (degrees, pixels) of one estimator or configuration.
struct ErrorStats {
    const char* name = "";
    std::vector<double> values;

    double mean() const { return meanOf(values); }
    /// Fraction of the errors at most `limit`; 0 when empty.
    double within(double limit) const
    {
        const auto n =
            std::count_if(values.begin(), values.end(), [&](double x) { return x <= limit; });
        return values.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(values.size());
    }
    /// The error at fraction `q` (0..1) of the sorted errors; 0 when empty.
    double percentile(double q) const
    {
        if (values.empty())
            return 0.0;
        std::vector<double> v = values;
        std::sort(v.begin(), v.end());
        return v[std::min(v.size() - 1,
                          static_cast<std::size_t>(q * static_cast<double>(v.size())))];
    }
};

}  // namespace mirror_eval
