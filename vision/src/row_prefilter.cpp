// The row prefilter (METHOD.md §3: the cascade's first stages, where most windows are decided).
//
// Speed (about 3x OpenCV on one core with the default cascade, 2x with alt2): the first stages run
// for a whole row of windows at once, one weak classifier over consecutive windows (SIMD; step-2
// scales use a column-deinterleaved copy of the sum table so those windows are consecutive too),
// while at least a quarter of the row's span is alive. There the decisions are OpenCV's float
// comparisons themselves (a feature sum is exact in float, the product is rounded once, as in
// OpenCV) and the stage sums are Q20 in 32 bits (8 lanes per AVX2 vector, not 4): a stage decides
// a window only when the rounding cannot matter, otherwise the window goes to the exact path from
// that stage (FixedCascade::evaluate). So the results are those of the exact path.

#include "row_prefilter.hpp"

#include "simd.hpp"

#include <algorithm>

namespace vision {
namespace {

// The prefilter goes on to the next stage while at least 1 / divisor of the row is alive.
constexpr int kAliveDivisor = 4;

// The kernels: one weak classifier over `n` consecutive windows, the decisions in float exactly
// as OpenCV makes them (an integer feature sum below 2^24 is exact in float, the product rounded
// once), the leaves summed in Q20. Plain loops the compiler vectorises (NEON on aarch64); on
// x86-64 each is also built for AVX2 and chosen by simd::hasAvx2() (below the bodies).

// A feature's 12 corner pointers for the windows from `base` on, and its weights, as plain
// locals: the compiler must see that the stage sums the kernels write do not move them.
#define MIRROR_VJ_TAPS2(f, prefix)                                 \
    const auto& prefix##o = ways == 4 ? (f).split4 : ways == 2 ? (f).split : (f).plain; \
    const std::int32_t* const prefix##a0 = base + prefix##o[0][0]; \
    const std::int32_t* const prefix##a1 = base + prefix##o[0][1]; \
    const std::int32_t* const prefix##a2 = base + prefix##o[0][2]; \
    const std::int32_t* const prefix##a3 = base + prefix##o[0][3]; \
    const std::int32_t* const prefix##b0 = base + prefix##o[1][0]; \
    const std::int32_t* const prefix##b1 = base + prefix##o[1][1]; \
    const std::int32_t* const prefix##b2 = base + prefix##o[1][2]; \
    const std::int32_t* const prefix##b3 = base + prefix##o[1][3]; \
    const std::int32_t prefix##wa = (f).weight[0];                 \
    const std::int32_t prefix##wb = (f).weight[1]
#define MIRROR_VJ_TAPS(f, prefix)                                  \
    MIRROR_VJ_TAPS2(f, prefix);                                    \
    const std::int32_t* const prefix##c0 = base + prefix##o[2][0]; \
    const std::int32_t* const prefix##c1 = base + prefix##o[2][1]; \
    const std::int32_t* const prefix##c2 = base + prefix##o[2][2]; \
    const std::int32_t* const prefix##c3 = base + prefix##o[2][3]; \
    const std::int32_t prefix##wc = (f).weight[2]
// A rectangle's sum modulo 2^32, as the table wraps on big images (scaled_integrals.cpp).
#define MIRROR_VJ_RECT(p0, p1, p2, p3, j)                                        \
    static_cast<std::int32_t>(                                                   \
        static_cast<std::uint32_t>(p0[j]) - static_cast<std::uint32_t>(p1[j]) - \
        static_cast<std::uint32_t>(p2[j]) + static_cast<std::uint32_t>(p3[j]))
#define MIRROR_VJ_FEATURE2(prefix, j)                                                  \
    (prefix##wa * MIRROR_VJ_RECT(prefix##a0, prefix##a1, prefix##a2, prefix##a3, j) + \
     prefix##wb * MIRROR_VJ_RECT(prefix##b0, prefix##b1, prefix##b2, prefix##b3, j))
#define MIRROR_VJ_FEATURE(prefix, j) \
    (MIRROR_VJ_FEATURE2(prefix, j) + \
     prefix##wc * MIRROR_VJ_RECT(prefix##c0, prefix##c1, prefix##c2, prefix##c3, j))

MIRROR_SIMD_BODY void rowStumpPassBody(const RowStump& st, const std::int32_t* base, int ways,
                                       int n, const float* __restrict vnf,
                                       std::int32_t* __restrict acc) noexcept
{
    const float thr = st.threshold;
    const std::int32_t left = st.left;
    const std::int32_t right = st.right;
    if (st.feature.twoRects) {
        MIRROR_VJ_TAPS2(st.feature, f);
        for (int j = 0; j < n; ++j) {
            const float v = static_cast<float>(MIRROR_VJ_FEATURE2(f, j)) * vnf[j];
            acc[j] += v < thr ? left : right;
        }
        return;
    }
    MIRROR_VJ_TAPS(st.feature, f);
    for (int j = 0; j < n; ++j) {
        const float v = static_cast<float>(MIRROR_VJ_FEATURE(f, j)) * vnf[j];
        acc[j] += v < thr ? left : right;
    }
}

// One tree over the windows; F0 / F1: the features' value macros (two or three rectangles).
#define MIRROR_VJ_TREE_LOOP(F0, F1)                              \
    for (int j = 0; j < n; ++j) {                                \
        const float v0 = static_cast<float>(F0(f0, j)) * vnf[j]; \
        const float v1 = static_cast<float>(F1(f1, j)) * vnf[j]; \
        const bool toNode1 = (v0 < thr0) == node1OnBelow;        \
        const std::int32_t leaf1 = v1 < thr1 ? below1 : above1;  \
        acc[j] += toNode1 ? leaf1 : direct;                      \
    }

MIRROR_SIMD_BODY void rowTreePassBody(const RowTree& t, const std::int32_t* base, int ways, int n,
                                      const float* __restrict vnf,
                                      std::int32_t* __restrict acc) noexcept
{
    const float thr0 = t.threshold0;
    const float thr1 = t.threshold1;
    const bool node1OnBelow = t.node1OnBelow;
    const std::int32_t direct = t.direct;
    const std::int32_t below1 = t.below1;
    const std::int32_t above1 = t.above1;
    if (t.feature0.twoRects && t.feature1.twoRects) {
        MIRROR_VJ_TAPS2(t.feature0, f0);
        MIRROR_VJ_TAPS2(t.feature1, f1);
        MIRROR_VJ_TREE_LOOP(MIRROR_VJ_FEATURE2, MIRROR_VJ_FEATURE2)
    } else if (t.feature0.twoRects) {
        MIRROR_VJ_TAPS2(t.feature0, f0);
        MIRROR_VJ_TAPS(t.feature1, f1);
        MIRROR_VJ_TREE_LOOP(MIRROR_VJ_FEATURE2, MIRROR_VJ_FEATURE)
    } else if (t.feature1.twoRects) {
        MIRROR_VJ_TAPS(t.feature0, f0);
        MIRROR_VJ_TAPS2(t.feature1, f1);
        MIRROR_VJ_TREE_LOOP(MIRROR_VJ_FEATURE, MIRROR_VJ_FEATURE2)
    } else {
        MIRROR_VJ_TAPS(t.feature0, f0);
        MIRROR_VJ_TAPS(t.feature1, f1);
        MIRROR_VJ_TREE_LOOP(MIRROR_VJ_FEATURE, MIRROR_VJ_FEATURE)
    }
}

// A stage's outcome for windows [0, n) of a row from their Q20 sums: those alive (result 1)
// are rejected (-si), parked for the exact path from this stage (2, from = si) or stay alive.
// Branch-free: which windows a stage rejects is data dependent. Returns how many stay alive.
MIRROR_SIMD_BODY int settleStageBody(const std::int32_t* __restrict acc, int* __restrict result,
                                     int* __restrict from, int n, int si, std::int32_t rowReject,
                                     std::int32_t rowPass) noexcept
{
    int alive = 0;
    for (int j = 0; j < n; ++j) {
        const int r = result[j];
        const bool live = r == 1;
        const bool reject = live & (acc[j] < rowReject);
        const bool park = live & !reject & (acc[j] < rowPass);
        result[j] = reject ? -si : (park ? 2 : r);
        from[j] = park ? si : from[j];
        alive += live & !reject & !park;
    }
    return alive;
}

/// A stage's sums over windows [0, n): every weak classifier of stage `st` over the row.
MIRROR_SIMD_BODY void stageSumsBody(const FixedCascade& cascade, const FixedStage& st,
                                    const std::int32_t* base, int ways, int n,
                                    const float* __restrict vnf,
                                    std::int32_t* __restrict acc) noexcept
{
    std::fill_n(acc, n, 0);
    for (int i = st.first; i < st.first + st.count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (cascade.stumps())
            rowStumpPassBody(cascade.rowStumps()[k], base, ways, n, vnf, acc);
        else
            rowTreePassBody(cascade.rowTrees()[k], base, ways, n, vnf, acc);
    }
}

// The path for this CPU (simd.hpp): the bodies built for AVX2 or for the baseline.
#if defined(__x86_64__)
MIRROR_AVX2 void stageSumsAvx2(const FixedCascade& cascade, const FixedStage& st,
                               const std::int32_t* base, int ways, int n,
                               const float* __restrict vnf, std::int32_t* __restrict acc) noexcept
{
    stageSumsBody(cascade, st, base, ways, n, vnf, acc);
}
MIRROR_AVX2 int settleStageAvx2(const std::int32_t* __restrict acc, int* __restrict result,
                                int* __restrict from, int n, int si, std::int32_t rowReject,
                                std::int32_t rowPass) noexcept
{
    return settleStageBody(acc, result, from, n, si, rowReject, rowPass);
}
#endif

void stageSums(const FixedCascade& cascade, const FixedStage& st, const std::int32_t* base,
               int ways, int n, const float* vnf, std::int32_t* acc) noexcept
{
#if defined(__x86_64__)
    if (simd::hasAvx2())
        return stageSumsAvx2(cascade, st, base, ways, n, vnf, acc);
#endif
    stageSumsBody(cascade, st, base, ways, n, vnf, acc);
}

int settleStage(const std::int32_t* acc, int* result, int* from, int n, int si,
                std::int32_t rowReject, std::int32_t rowPass) noexcept
{
#if defined(__x86_64__)
    if (simd::hasAvx2())
        return settleStageAvx2(acc, result, from, n, si, rowReject, rowPass);
#endif
    return settleStageBody(acc, result, from, n, si, rowReject, rowPass);
}

}  // namespace

RowPrefilter::RowPrefilter(int maxWindows)
    : norm_(static_cast<std::size_t>(maxWindows)),
      acc_(norm_.size()),
      result_(norm_.size()),
      from_(norm_.size())
{
}

// Survivors cluster (faces, texture): each stage runs over the span from the first to the last
// window still alive, while at least 1 / kAliveDivisor of the span is alive.
int RowPrefilter::run(const FixedCascade& cascade, const ScaledIntegrals& tables, int y, int step,
                      int j0, int j1, const std::uint8_t* wanted, int endStage) noexcept
{
    // A masked scan wants a few windows of a row: the span is cut to them, and the others in it
    // are dead from the start (no norm, not counted alive), so the stages run over the wanted
    // windows' span only. Each window's decision is its own, so the wanted ones' results are
    // those of the whole row's run.
    if (wanted != nullptr) {
        while (j0 < j1 && wanted[j0] == 0)
            ++j0;
        while (j1 > j0 && wanted[j1 - 1] == 0)
            --j1;
    }
    const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(y) * tables.stride();
    int alive = 0;
    for (int j = j0; j < j1; ++j) {
        if (wanted != nullptr && wanted[j] == 0) {
            norm_[static_cast<std::size_t>(j)] = 0.0f;
            result_[static_cast<std::size_t>(j)] = -1;
            from_[static_cast<std::size_t>(j)] = 0;
            continue;
        }
        const std::ptrdiff_t at = row + static_cast<std::ptrdiff_t>(j) * step;
        const float vnf = cascade.windowNorm(tables.sum() + at, tables.squaredSum() + at);
        norm_[static_cast<std::size_t>(j)] = vnf;
        result_[static_cast<std::size_t>(j)] = vnf == 0.0f ? -1 : 1;
        from_[static_cast<std::size_t>(j)] = 0;
        alive += vnf != 0.0f;
    }
    // Windows `step` apart are consecutive entries of the table deinterleaved `step` ways.
    const int ways = step == 4 ? 4 : step == 2 ? 2 : 1;
    const std::int32_t* table =
        ways == 4 ? tables.split4Sum() + static_cast<std::ptrdiff_t>(y) * tables.split4Stride()
                  : (ways == 2 ? tables.splitSum() : tables.sum()) + row;
    const std::vector<FixedStage>& stages = cascade.stages();
    const int nstages = endStage >= 0 ? std::min(endStage, static_cast<int>(stages.size()))
                                      : static_cast<int>(stages.size());
    int lo = j0;
    int hi = j1;
    int si = 0;
    for (; si < nstages; ++si) {
        while (lo < hi && result_[static_cast<std::size_t>(lo)] != 1)
            ++lo;
        while (hi > lo && result_[static_cast<std::size_t>(hi - 1)] != 1)
            --hi;
        const int n = hi - lo;
        if (n == 0 || alive * kAliveDivisor < n)
            break;
        const FixedStage& st = stages[static_cast<std::size_t>(si)];
        const std::int32_t* base = table + lo;
        std::int32_t* acc = acc_.data() + lo;
        stageSums(cascade, st, base, ways, n, norm_.data() + lo, acc);
        alive = settleStage(acc, result_.data() + lo, from_.data() + lo, n, si, st.rowReject,
                            st.rowPass);
    }
    return si;
}

}  // namespace vision
