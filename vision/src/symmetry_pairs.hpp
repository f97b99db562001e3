#pragma once
// The inner loop of the roll by image symmetry (METHOD.md §4; the dissertation's 5.2 future work):
// the normalised asymmetry of a prepared patch's feature planes about a vertical mirror axis.
// `pairAsymmetry` is the reference for any axis; `pairAsymmetryWholeAxis` is the same sum for an
// axis on a whole number of half pixels with uniform pair weights (the coarse scan's case: most
// of the estimate's work), without the partner's interpolation and weight, whose terms are then
// exactly the partner's value and 1: the same bits. Private to vision/src.
#include <algorithm>
#include <cmath>
#include <cstddef>

namespace vision::symmetry_detail {

/// The prepared planes (n x n, row-major) and the compared rows [y0, y1); partners read up to
/// column `hi`. `weight[d]`: a pair's weight by its distance d = |x - x'|; null: every weight
/// is 1 (1 x s is s: the same bits without looking it up).
struct PairPlanes {
    const float* a;
    const float* b;  ///< the vertical gradients (gradient feature); unused otherwise
    const float* weight;
    int n;
    int y0, y1;
    int hi;
    bool gradient;
};

/// The pairs' sums, kept as NEON keeps them: pair k of a row (k = x - xFirst) in partial sum
/// k % 4 while the row has four pairs left, its last (xEnd - xFirst) % 4 pairs in a fifth, added
/// at the end in a fixed order. Scalar and NEON code then add the same numbers in the same
/// order: the same bits on both paths (no multiplications here, so no fused ones either).
struct PairSums {
    float cost[4] = {0.f, 0.f, 0.f, 0.f};
    float norm[4] = {0.f, 0.f, 0.f, 0.f};
    float tailCost = 0.f;
    float tailNorm = 0.f;

    /// cost / norm, or 1 when the pairs compare nothing.
    float ratio() const noexcept
    {
        const float c = ((cost[0] + cost[1]) + (cost[2] + cost[3])) + tailCost;
        const float n = ((norm[0] + norm[1]) + (norm[2] + norm[3])) + tailNorm;
        return n > 1e-3f ? c / n : 1.f;
    }
};

/// Adds pair(x, cost, norm) for xFirst <= x < xEnd of every row y0 <= y < y1 into PairSums' lanes
/// and returns their ratio. `pair` adds its terms to the two floats it is given.
template <class Pair>
inline float sumPairs(int y0, int y1, int xFirst, int xEnd, const Pair& pair) noexcept
{
    PairSums s;
    const int full = xFirst + (xEnd - xFirst) / 4 * 4;
    for (int y = y0; y < y1; ++y) {
        int x = xFirst;
        for (; x < full; x += 4)
            for (int lane = 0; lane < 4; ++lane)
                pair(y, x + lane, s.cost[lane], s.norm[lane]);
        for (; x < xEnd; ++x)
            pair(y, x, s.tailCost, s.tailNorm);
    }
    return s.ratio();
}

/// Sum of the pairs (x, a2 - x) for xFirst <= x < xEnd over the rows; cost / norm, or 1 when the
/// pairs compare nothing. The reference, for any a2.
inline float pairAsymmetry(const PairPlanes& p, int xFirst, int xEnd, float a2) noexcept
{
    return sumPairs(p.y0, p.y1, xFirst, xEnd, [&p, a2](int y, int x, float& cost, float& norm) {
        const float* a = p.a + static_cast<std::ptrdiff_t>(y) * p.n;
        const float* b = p.b + static_cast<std::ptrdiff_t>(y) * p.n;
        const float m = a2 - static_cast<float>(x);
        const int m0 = std::min(static_cast<int>(m), p.hi - 1);
        const float f = m - static_cast<float>(m0);
        const float am = a[m0] + f * (a[m0 + 1] - a[m0]);
        const float w =
            p.weight != nullptr
                ? p.weight[static_cast<std::size_t>(std::lround(m - static_cast<float>(x)))]
                : 1.f;
        if (p.gradient) {
            const float bm = b[m0] + f * (b[m0 + 1] - b[m0]);
            cost += w * (std::fabs(a[x] + am) + std::fabs(b[x] - bm));
            norm += w * (std::fabs(a[x]) + std::fabs(am) + std::fabs(b[x]) + std::fabs(bm));
        } else {
            cost += w * std::fabs(a[x] - am);
            norm += w * (std::fabs(a[x]) + std::fabs(am));
        }
    });
}

/// pairAsymmetry for a whole a2 (partners a2 - x <= hi - 1: no interpolation), every weight 1
/// and the gradient feature. Same bits: the partner term a[m] + 0 x (a[m + 1] - a[m]) is a[m]
/// (the planes are finite; a zero's sign is lost in the absolute values) and 1 x s is s.
inline float pairAsymmetryWholeAxisScalar(const PairPlanes& p, int xFirst, int xEnd,
                                          int a2) noexcept
{
    return sumPairs(p.y0, p.y1, xFirst, xEnd, [&p, a2](int y, int x, float& cost, float& norm) {
        const float* a = p.a + static_cast<std::ptrdiff_t>(y) * p.n;
        const float* b = p.b + static_cast<std::ptrdiff_t>(y) * p.n;
        const float am = a[a2 - x];
        const float bm = b[a2 - x];
        cost += std::fabs(a[x] + am) + std::fabs(b[x] - bm);
        norm += std::fabs(a[x]) + std::fabs(am) + std::fabs(b[x]) + std::fabs(bm);
    });
}

#if defined(__aarch64__)
/// NEON, four pairs a step (symmetry_pairs_neon.cpp): the same bits as the scalar one.
float pairAsymmetryWholeAxisNeon(const PairPlanes& p, int xFirst, int xEnd, int a2) noexcept;
#endif

/// The coarse scan's sum (most of the roll estimate's work): NEON where there is NEON.
inline float pairAsymmetryWholeAxis(const PairPlanes& p, int xFirst, int xEnd, int a2) noexcept
{
#if defined(__aarch64__)
    return pairAsymmetryWholeAxisNeon(p, xFirst, xEnd, a2);
#else
    return pairAsymmetryWholeAxisScalar(p, xFirst, xEnd, a2);
#endif
}

}  // namespace vision::symmetry_detail
