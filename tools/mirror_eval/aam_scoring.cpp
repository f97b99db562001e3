// Scoring of fitted points on CANDIDE vertices (aam_scoring.hpp).
#include "aam_scoring.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mirror_eval {

CandidePoints candidePointsOf(const aam::AnnotationScheme& scheme,
                              const std::vector<Eigen::Vector2d>& annotation)
{
    if (static_cast<int>(annotation.size()) != scheme.pointCount)
        throw std::invalid_argument(std::to_string(annotation.size()) + " points, the " +
                                    std::string(scheme.name) + " scheme has " +
                                    std::to_string(scheme.pointCount));
    CandidePoints points;
    for (const aam::SchemeRow& row : scheme.rows)
        points[row.candideVertex] = row.at.of(annotation);
    return points;
}

CandidePoints candidePointsOf(const std::vector<int>& candideNumber,
                              const std::vector<Eigen::Vector2d>& vertices)
{
    CandidePoints points;
    for (std::size_t v = 0; v < vertices.size() && v < candideNumber.size(); ++v)
        points[candideNumber[v]] = vertices[v];
    return points;
}

PointGroup pointGroupOf(int n) noexcept
{
    switch (n) {
        case 10:
        case 30:
        case 32:
        case 63:
        case 65:
            return PointGroup::Jaw;
        case 15:
        case 16:
        case 17:
        case 18:
        case 48:
        case 49:
        case 50:
        case 51:
            return PointGroup::Brow;
        default:
            return PointGroup::Inner;
    }
}

std::optional<double> eyeCornerDistance(const CandidePoints& truth)
{
    const auto left = truth.find(20), right = truth.find(53);
    if (left == truth.end() || right == truth.end())
        return std::nullopt;
    const double d = (left->second - right->second).norm();
    return d > 0 ? std::optional<double>(d) : std::nullopt;
}

std::optional<double> mouthOpening(const CandidePoints& points, double eyeDistance)
{
    const auto upper = points.find(87), lower = points.find(40);
    if (upper == points.end() || lower == points.end() || eyeDistance <= 0)
        return std::nullopt;
    return (upper->second - lower->second).norm() / eyeDistance;
}

std::optional<FrameNme> frameNme(const CandidePoints& truth, const CandidePoints& estimate,
                                 double eyeDistance, const CandidePoints* only)
{
    if (!(eyeDistance > 0))
        return std::nullopt;
    FrameNme r;
    double inner = 0, all = 0;
    for (const auto& [vertex, at] : truth) {
        const auto e = estimate.find(vertex);
        if (e == estimate.end() || (only && !only->count(vertex)))
            continue;
        const double d = (e->second - at).norm() / eyeDistance;
        all += d;
        ++r.allPoints;
        if (pointGroupOf(vertex) == PointGroup::Inner) {
            inner += d;
            ++r.innerPoints;
        }
    }
    if (r.innerPoints == 0)
        return std::nullopt;
    r.inner = inner / r.innerPoints;
    r.all = all / r.allPoints;
    return r;
}

double pearson(const std::vector<double>& a, const std::vector<double>& b)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (a.size() != b.size() || a.size() < 2)
        return nan;
    const double n = static_cast<double>(a.size());
    double ma = 0, mb = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        ma += a[i] / n, mb += b[i] / n;
    double ab = 0, aa = 0, bb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ab += (a[i] - ma) * (b[i] - mb);
        aa += (a[i] - ma) * (a[i] - ma);
        bb += (b[i] - mb) * (b[i] - mb);
    }
    return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : nan;
}

PairNme fgnetIbugNme(const std::vector<Eigen::Vector2d>& fgnet,
                     const std::vector<Eigen::Vector2d>& ibug)
{
    constexpr int kFgnetChin = 7, kFgnetRightOuter = 27, kFgnetLeftOuter = 32;
    if (fgnet.size() != 68 || ibug.size() != 68)
        throw std::invalid_argument("the FGNet-iBUG pairs need 68 points on each side");
    const double eyes = (fgnet[kFgnetRightOuter] - fgnet[kFgnetLeftOuter]).norm();
    PairNme r;
    double inner = 0, innerAndChin = 0, all = 0;
    for (const aam::FgnetIbugPair& pair : aam::fgnetIbugPairs()) {
        const double d = (pair.fgnet.of(fgnet) - pair.ibug.of(ibug)).norm() / eyes;
        const int first = pair.fgnet.points[0];
        const bool isInner = first >= 27;  // eyes, nose, lips (the brows are 15-26, jaw 0-14)
        all += d, ++r.allPoints;
        if (isInner)
            inner += d, ++r.innerPoints;
        if (isInner || first == kFgnetChin)
            innerAndChin += d, ++r.innerAndChinPoints;
    }
    // The centres: the mean of an iBUG contour against FGNet's own centre point.
    double centres = 0;
    const auto contourMean = [&](int first, int last) {
        Eigen::Vector2d sum = Eigen::Vector2d::Zero();
        for (int i = first; i <= last; ++i)
            sum += ibug[static_cast<std::size_t>(i)];
        return Eigen::Vector2d(sum / (last - first + 1));
    };
    centres += (fgnet[31] - contourMean(36, 41)).norm() / eyes;
    centres += (fgnet[36] - contourMean(42, 47)).norm() / eyes;
    centres += (fgnet[66] - contourMean(60, 67)).norm() / eyes;
    r.withCentresPoints = r.innerPoints + 3;
    r.withCentresAndChinPoints = r.innerAndChinPoints + 3;
    r.withCentres = (inner + centres) / r.withCentresPoints;
    r.withCentresAndChin = (innerAndChin + centres) / r.withCentresAndChinPoints;
    r.inner = inner / std::max(1, r.innerPoints);
    r.innerAndChin = innerAndChin / std::max(1, r.innerAndChinPoints);
    r.all = all / std::max(1, r.allPoints);
    return r;
}

PairNme meanPairNme(const std::vector<PairNme>& frames)
{
    if (frames.empty())
        return {};
    PairNme m = frames.front();
    m.inner = m.innerAndChin = m.all = m.withCentres = m.withCentresAndChin = 0;
    const double n = static_cast<double>(frames.size());
    for (const PairNme& f : frames) {
        m.inner += f.inner / n, m.innerAndChin += f.innerAndChin / n, m.all += f.all / n;
        m.withCentres += f.withCentres / n, m.withCentresAndChin += f.withCentresAndChin / n;
    }
    return m;
}

}  // namespace mirror_eval
