#include "ranking.hpp"

#include <algorithm>
#include <functional>

namespace colorlab {
namespace {

/// Competition ranks (1, 2, 2, 4) of `value` over the spaces, `better(a, b)` when a ranks first.
std::vector<int> ranks(const std::vector<double>& value,
                       const std::function<bool(double, double)>& better)
{
    std::vector<int> r(value.size(), 1);
    for (std::size_t i = 0; i < value.size(); ++i) {
        for (std::size_t j = 0; j < value.size(); ++j) {
            if (better(value[j], value[i])) {
                ++r[i];
            }
        }
    }
    return r;
}

}  // namespace

std::vector<RankedSpace> rankSpaces(const std::vector<SpaceStats>& stats)
{
    std::vector<double> inv, mean, min;
    for (const SpaceStats& s : stats) {
        inv.push_back(s.invariancePercent);
        mean.push_back(s.dpMean);
        min.push_back(s.dpMin);
    }
    const auto lower = [](double a, double b) { return a < b; };
    const auto higher = [](double a, double b) { return a > b; };
    const auto invRank = ranks(inv, lower);
    const auto meanRank = ranks(mean, higher);
    const auto minRank = ranks(min, higher);
    std::vector<RankedSpace> out;
    for (std::size_t i = 0; i < stats.size(); ++i) {
        out.push_back({stats[i].space, invRank[i], meanRank[i], minRank[i],
                       invRank[i] + meanRank[i] + minRank[i]});
    }
    std::stable_sort(out.begin(), out.end(), [&](const RankedSpace& a, const RankedSpace& b) {
        if (a.score != b.score) {
            return a.score < b.score;
        }
        return a.dpMeanRank < b.dpMeanRank;
    });
    return out;
}

std::string rankingLine(const std::vector<RankedSpace>& ranking)
{
    std::string line = "ranking:";
    for (std::size_t i = 0; i < ranking.size(); ++i) {
        line += i == 0 ? " " : " > ";
        line += vision::colorSpaceInfo(ranking[i].space).name;
    }
    return line;
}

}  // namespace colorlab
