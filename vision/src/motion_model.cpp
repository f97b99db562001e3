// Least-squares motion model of a tracked face about its centre (METHOD.md §3, tracking).
#include "vision/motion_model.hpp"

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>

namespace vision {

namespace {

int minimalPairs(MotionKind kind) noexcept
{
    switch (kind) {
        case MotionKind::Translation:
            return 1;
        case MotionKind::Similarity:
            return 2;
        case MotionKind::Affine:
            return 3;
    }
    return 1;
}

float residual(const MotionModel& m, Point2f from, Point2f to) noexcept
{
    const Point2f p = m.apply(from);
    return std::hypot(p.x - to.x, p.y - to.y);
}

/// Fits over the pairs that `visit` names: visit(f) calls f(i) for each pair index i used.
template <typename Visit>
bool fitPairs(const Point2f* from, const Point2f* to, Visit visit, Point2f c, MotionKind kind,
              MotionModel& m) noexcept
{
    int k = 0;
    visit([&k](int) { ++k; });
    m = MotionModel{};
    m.kind = kind;
    m.centre = c;
    if (k < minimalPairs(kind)) {
        return false;
    }
    if (kind == MotionKind::Translation) {
        double sx = 0.0;
        double sy = 0.0;
        visit([&](int i) {
            sx += to[i].x - from[i].x;
            sy += to[i].y - from[i].y;
        });
        m.b1 = static_cast<float>(sx / k);
        m.b2 = static_cast<float>(sy / k);
        return true;
    }
    if (kind == MotionKind::Similarity) {
        // Unknowns (a1, a2, b1, b2); each pair gives the rows [u -v 1 0] and [v u 0 1].
        Eigen::Matrix4d ata = Eigen::Matrix4d::Zero();
        Eigen::Vector4d atb = Eigen::Vector4d::Zero();
        visit([&](int i) {
            const double u = from[i].x - c.x;
            const double v = from[i].y - c.y;
            const double xp = to[i].x - c.x;
            const double yp = to[i].y - c.y;
            const Eigen::Vector4d rx(u, -v, 1.0, 0.0);
            const Eigen::Vector4d ry(v, u, 0.0, 1.0);
            ata.noalias() += rx * rx.transpose() + ry * ry.transpose();
            atb.noalias() += rx * xp + ry * yp;
        });
        const Eigen::FullPivLU<Eigen::Matrix4d> lu(ata);
        if (!lu.isInvertible()) {
            return false;
        }
        const Eigen::Vector4d s = lu.solve(atb);
        if (!s.allFinite()) {
            return false;
        }
        m.a11 = m.a22 = static_cast<float>(s[0]);
        m.a21 = static_cast<float>(s[1]);
        m.a12 = -m.a21;
        m.b1 = static_cast<float>(s[2]);
        m.b2 = static_cast<float>(s[3]);
        return true;
    }
    // Affine: x and y share the normal matrix of the rows [u v 1].
    Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
    Eigen::Vector3d atx = Eigen::Vector3d::Zero();
    Eigen::Vector3d aty = Eigen::Vector3d::Zero();
    visit([&](int i) {
        const Eigen::Vector3d r(from[i].x - c.x, from[i].y - c.y, 1.0);
        ata.noalias() += r * r.transpose();
        atx.noalias() += r * (to[i].x - c.x);
        aty.noalias() += r * (to[i].y - c.y);
    });
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(ata);
    if (!lu.isInvertible()) {
        return false;
    }
    const Eigen::Vector3d sx = lu.solve(atx);
    const Eigen::Vector3d sy = lu.solve(aty);
    if (!sx.allFinite() || !sy.allFinite()) {
        return false;
    }
    m.a11 = static_cast<float>(sx[0]);
    m.a12 = static_cast<float>(sx[1]);
    m.b1 = static_cast<float>(sx[2]);
    m.a21 = static_cast<float>(sy[0]);
    m.a22 = static_cast<float>(sy[1]);
    m.b2 = static_cast<float>(sy[2]);
    return true;
}

/// Marks inliers of `m`; returns their count and their summed residual in `cost` (outliers
/// counted at the threshold, so ties between equal counts go to the tighter model).
int countInliers(const Point2f* from, const Point2f* to, int n, const MotionModel& m,
                 float threshold, std::uint8_t* mark, double& cost) noexcept
{
    int count = 0;
    cost = 0.0;
    for (int i = 0; i < n; ++i) {
        const float r = residual(m, from[i], to[i]);
        const bool in = r <= threshold;
        if (mark) {
            mark[i] = in ? 1 : 0;
        }
        count += in ? 1 : 0;
        cost += in ? r : threshold;
    }
    return count;
}

/// The next k-subset of {0..n-1} in lexicographic order; false after the last.
bool nextCombination(int* idx, int k, int n) noexcept
{
    for (int j = k - 1; j >= 0; --j) {
        if (idx[j] < n - k + j) {
            ++idx[j];
            for (int t = j + 1; t < k; ++t) {
                idx[t] = idx[t - 1] + 1;
            }
            return true;
        }
    }
    return false;
}

}  // namespace

float MotionModel::scale() const noexcept
{
    const float a1 = 0.5f * (a11 + a22);
    const float a2 = 0.5f * (a21 - a12);
    return std::hypot(a1, a2);
}

float MotionModel::roll() const noexcept
{
    const float a1 = 0.5f * (a11 + a22);
    const float a2 = 0.5f * (a21 - a12);
    return std::atan2(a2, a1);
}

bool fitMotionLeastSquares(const Point2f* from, const Point2f* to, int n, const std::uint8_t* use,
                           Point2f centre, MotionKind kind, MotionModel& model) noexcept
{
    auto visit = [n, use](auto&& f) {
        for (int i = 0; i < n; ++i) {
            if (!use || use[i]) {
                f(i);
            }
        }
    };
    return fitPairs(from, to, visit, centre, kind, model);
}

int fitMotionRobust(const Point2f* from, const Point2f* to, int n, Point2f centre,
                    const MotionFitOptions& options, MotionModel& model,
                    std::uint8_t* inliers) noexcept
{
    constexpr int kMaxPoints = kMaxMotionPairs;
    const int k = minimalPairs(options.kind);
    model = MotionModel{};
    model.kind = options.kind;
    model.centre = centre;
    if (n < k || n > kMaxPoints) {
        return 0;
    }
    // Every minimal sample when there are few (at most maxIterations), else a fixed-seed LCG.
    long combos = 1;
    for (int j = 0; j < k; ++j) {
        combos = combos * (n - j) / (j + 1);
    }
    const bool exhaustive = combos <= options.maxIterations;
    int sample[3] = {0, 1, 2};
    std::uint32_t rng = 0x9e3779b9u;
    auto draw = [&rng](int bound) {
        rng = rng * 1664525u + 1013904223u;
        return static_cast<int>((rng >> 8) % static_cast<std::uint32_t>(bound));
    };

    MotionModel best;
    int bestCount = -1;
    double bestCost = 0.0;
    const int iterations = exhaustive ? static_cast<int>(combos) : options.maxIterations;
    for (int it = 0; it < iterations; ++it) {
        if (exhaustive) {
            if (it > 0 && !nextCombination(sample, k, n)) {
                break;
            }
        } else {
            for (int j = 0; j < k; ++j) {
                bool repeated = true;
                while (repeated) {
                    sample[j] = draw(n);
                    repeated = false;
                    for (int t = 0; t < j; ++t) {
                        repeated = repeated || sample[t] == sample[j];
                    }
                }
            }
        }
        MotionModel hypothesis;
        auto visit = [&sample, k](auto&& f) {
            for (int j = 0; j < k; ++j) {
                f(sample[j]);
            }
        };
        if (!fitPairs(from, to, visit, centre, options.kind, hypothesis)) {
            continue;
        }
        double cost = 0.0;
        const int count =
            countInliers(from, to, n, hypothesis, options.inlierDistance, nullptr, cost);
        if (count > bestCount || (count == bestCount && cost < bestCost)) {
            best = hypothesis;
            bestCount = count;
            bestCost = cost;
        }
    }
    if (bestCount < k) {
        return 0;
    }
    std::uint8_t mark[kMaxPoints];
    double cost = 0.0;
    int count = countInliers(from, to, n, best, options.inlierDistance, mark, cost);
    for (int round = 0; round < 2; ++round) {
        MotionModel refit;
        if (!fitMotionLeastSquares(from, to, n, mark, centre, options.kind, refit)) {
            break;
        }
        std::uint8_t refitMark[kMaxPoints];
        const int refitCount =
            countInliers(from, to, n, refit, options.inlierDistance, refitMark, cost);
        if (refitCount < count) {
            break;
        }
        best = refit;
        count = refitCount;
        for (int i = 0; i < n; ++i) {
            mark[i] = refitMark[i];
        }
    }
    model = best;
    if (inliers) {
        for (int i = 0; i < n; ++i) {
            inliers[i] = mark[i];
        }
    }
    return count;
}

}  // namespace vision
