// Viola-Jones evaluation of an OpenCV Haar cascade in integer arithmetic (METHOD.md §3); what is
// matched of OpenCV 4.6's cascadedetect.cpp and why is listed in face_detector.hpp.

#include "vision/face_detector.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace vision {
namespace {

constexpr int kNormShift = 48;  // Q of the per-window normalisation factor and node thresholds
constexpr double kNormScale = 281474976710656.0;  // 2^kNormShift
constexpr int kLeafShift = 40;                    // Q of leaf values and stage thresholds
constexpr float kStageThresholdEps = 1e-5f;       // OpenCV's THRESHOLD_EPS
constexpr int kResizeShift = 8;                   // INTER_LINEAR_EXACT weights for 8-bit images
// The row prefilter goes on to the next stage while at least 1 / divisor of the row is alive,
// and runs on rows with at least kPrefilterMinWindows windows to evaluate.
constexpr int kPrefilterAliveDivisor = 4;
constexpr int kPrefilterMinWindows = 4;

// A rectangle feature as integral-image offsets for the detector's table stride.
struct FixedFeature {
    std::int32_t ofs[3][4];
    std::int32_t weight[3];
    int rectCount;
};

struct Stump {
    FixedFeature feature;
    std::int64_t threshold;  // Q48, half a float step below the file's threshold (see header)
    std::int64_t left;       // Q40
    std::int64_t right;
    std::int64_t restMax;  // most / least the stage's later stumps can still add (exit early)
    std::int64_t restMin;
    int featureIndex;
    float fileThreshold;  // as in the file: the row prefilter compares floats like OpenCV
};

// A feature for the row prefilter: offsets in the plain table (step-1 scales) and in the
// column-deinterleaved one (step-2 scales), so the windows of a row are consecutive entries.
struct RowFeature {
    std::int32_t plain[3][4];
    std::int32_t split[3][4];
    std::int32_t weight[3];
    bool twoRects;  // weight[2] == 0: most features; a kernel without the third rectangle
};

// Leaves in the row prefilter: Q20 in 32 bits (8 lanes per AVX2 vector, not 4), each within half
// a unit of the exact Q40 value; a stage decides only where the rounding cannot matter.
constexpr int kRowLeafShift = 20;

std::int32_t rowLeaf(std::int64_t q40)
{
    constexpr int shift = kLeafShift - kRowLeafShift;
    return static_cast<std::int32_t>((q40 + (std::int64_t{1} << (shift - 1))) >> shift);
}

struct RowStump {
    RowFeature feature;
    float threshold;
    std::int32_t left;  // Q20
    std::int32_t right;
};

// A two-node tree (alt2): node 0 leads to a leaf (`direct`) or to node 1 (leaves below1 and
// above1); node1OnBelow says which way.
struct RowTree {
    RowFeature feature0;
    RowFeature feature1;
    float threshold0;
    float threshold1;
    bool node1OnBelow;
    std::int32_t direct;  // Q20
    std::int32_t below1;
    std::int32_t above1;
};

// The row prefilter's kernels: one weak classifier over `n` consecutive windows, the decisions
// in float exactly as OpenCV makes them (an integer feature sum below 2^24 is exact in float,
// the product rounded once), the leaves summed in Q20 (rowLeaf). On x86-64 also built for AVX2,
// chosen at load time (aarch64: NEON is the baseline).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define MIRROR_VJ_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MIRROR_VJ_CLONES
#endif

// A feature's 12 corner pointers for the windows from `base` on, and its weights, as plain
// locals: the compiler must see that the stage sums the kernels write do not move them.
#define MIRROR_VJ_TAPS2(f, prefix)                                 \
    const auto& prefix##o = split ? (f).split : (f).plain;         \
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
#define MIRROR_VJ_FEATURE2(prefix, j)                                               \
    (prefix##wa * (prefix##a0[j] - prefix##a1[j] - prefix##a2[j] + prefix##a3[j]) + \
     prefix##wb * (prefix##b0[j] - prefix##b1[j] - prefix##b2[j] + prefix##b3[j]))
#define MIRROR_VJ_FEATURE(prefix, j) \
    (MIRROR_VJ_FEATURE2(prefix, j) + \
     prefix##wc * (prefix##c0[j] - prefix##c1[j] - prefix##c2[j] + prefix##c3[j]))

MIRROR_VJ_CLONES void rowStumpPass(const RowStump& st, const std::int32_t* base, bool split, int n,
                                   const float* __restrict vnf,
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

MIRROR_VJ_CLONES void rowTreePass(const RowTree& t, const std::int32_t* base, bool split, int n,
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
MIRROR_VJ_CLONES int settleStage(const std::int32_t* __restrict acc, int* __restrict result,
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

struct TreeNode {
    FixedFeature feature;
    std::int64_t threshold;
    int left;
    int right;
    int featureIndex;
    float fileThreshold;
};

struct FixedWeak {
    int firstNode;
    int firstLeaf;
    std::int64_t restMax;
    std::int64_t restMin;
};

struct FixedStage {
    std::int64_t threshold;  // Q40 of (float(threshold) - 1e-5f)
    int first;               // first stump (stump cascades) or weak classifier (trees)
    int count;
    // Row prefilter, Q20 sums: below rowReject the exact sum is surely below the threshold, from
    // rowPass on surely not; between, the exact scalar path decides.
    std::int32_t rowReject;
    std::int32_t rowPass;
};

// The exact comparison "float(f * vnf) < thr" as "f * K < q" with K = vnf * 2^48 (an integer:
// vnf >= 2^-25 here): float(p) < thr exactly when p lies below the midpoint between thr and the
// float before it, or on it when rounding to even takes it down.
std::int64_t nodeThreshold(float thr)
{
    if (!(std::fabs(thr) < 8192.0f))
        throw std::runtime_error("node threshold out of range");
    const float below = std::nextafter(thr, -std::numeric_limits<float>::infinity());
    const double mid = (static_cast<double>(below) + static_cast<double>(thr)) * 0.5;
    const double scaled = std::ldexp(mid, kNormShift);
    const double whole = std::nearbyint(scaled);
    std::int64_t q = static_cast<std::int64_t>(whole);
    const bool belowEven = (std::bit_cast<std::uint32_t>(below) & 1u) == 0;
    if (whole == scaled && belowEven)
        ++q;  // the tie rounds down to `below`: counts as below thr
    if (whole != scaled && whole < scaled)
        ++q;  // tiny thresholds: nearest representable
    return q;
}

std::int64_t leafFixed(double v)
{
    if (!(std::fabs(v) < 1048576.0))
        throw std::runtime_error("leaf value out of range");
    return static_cast<std::int64_t>(std::nearbyint(std::ldexp(v, kLeafShift)));
}

// Per-scale tables of the bit-exact bilinear resize: source offsets and 8-bit weights.
struct ResizeAxis {
    int* ofs0;
    int* ofs1;
    std::int32_t* w0;
    std::int32_t* w1;
};

void resizeTable(int srcSize, int dstSize, ResizeAxis t) noexcept
{
    // OpenCV: inv_scale = dst / src (double); scale = 1 / inv_scale; fval = scale * (d + 0.5) -
    // 0.5; weights rounded to 1/256, the first weight being 256 minus the second.
    const double invScale = static_cast<double>(dstSize) / static_cast<double>(srcSize);
    const double scale = 1.0 / invScale;
    for (int d = 0; d < dstSize; ++d) {
        const double fval = scale * (static_cast<double>(d) + 0.5) - 0.5;
        const int ival = static_cast<int>(std::floor(fval));
        if (ival >= 0 && srcSize > 1 && ival < srcSize - 1) {
            const int w1 = static_cast<int>(
                std::nearbyint((fval - static_cast<double>(ival)) * (1 << kResizeShift)));
            t.ofs0[d] = ival;
            t.ofs1[d] = ival + 1;
            t.w1[d] = w1;
            t.w0[d] = (1 << kResizeShift) - w1;
        } else {
            const int edge = ival < 0 || srcSize <= 1 ? 0 : srcSize - 1;
            t.ofs0[d] = edge;
            t.ofs1[d] = edge;
            t.w0[d] = 1 << kResizeShift;
            t.w1[d] = 0;
        }
    }
}

inline std::int32_t rectSum(const std::int32_t* p, const std::int32_t* o) noexcept
{
    return p[o[0]] - p[o[1]] - p[o[2]] + p[o[3]];
}

inline std::int64_t featureValue(const FixedFeature& f, const std::int32_t* p) noexcept
{
    // A 2-rectangle feature has weight 0 and offsets 0 for the third: computing it anyway is
    // cheaper than a branch that mispredicts between the two kinds.
    return f.weight[0] * rectSum(p, f.ofs[0]) + f.weight[1] * rectSum(p, f.ofs[1]) +
           f.weight[2] * rectSum(p, f.ofs[2]);
}

}  // namespace

struct FaceDetector::Impl {
    FaceDetectorOptions options;
    int winW = 0;
    int winH = 0;
    int stride = 0;  // entries per integral table row
    bool stumps = true;
    bool twoNodeTrees = false;  // every tree: node 0 -> (leaf | node 1), node 1 -> leaves
    std::vector<Stump> stumpList;
    std::vector<TreeNode> nodes;
    std::vector<std::int64_t> leaves;
    std::vector<FixedWeak> weak;
    std::vector<FixedStage> stages;
    std::int32_t normOfs[4] = {};
    double normArea = 0.0;
    std::int64_t nfRejectBelow = 0;  // nf below this is surely flat (std dev <= 10)

    // The row prefilter (stumps and two-node trees): the weak classifiers in stage order,
    // parallel to stumpList / weak.
    bool rowPrefilter = false;
    std::vector<RowStump> rowStumps;
    std::vector<RowTree> rowTrees;

    // Per-frame buffers, sized for maxFrameSize.
    std::vector<std::uint8_t> scaled;
    std::vector<std::int32_t> sum;
    std::vector<std::int32_t> sumSplit;  // `sum` with even columns first (step-2 scales)
    std::vector<float> rowNorm;          // per window of a row: vnf, 0 when flat
    std::vector<std::int32_t> rowAcc;    // stage sums, Q20
    std::vector<int> rowResult;  // 1: alive; 2: to the exact path from rowFrom; else as runAt
    std::vector<int> rowFrom;    // stage from which the exact path continues
    std::vector<std::uint8_t> rowWanted;  // not masked out nor excluded
    std::vector<std::uint32_t> sqsum;
    std::vector<std::uint32_t> rowTmp;
    std::vector<int> xofs0, xofs1, yofs0, yofs1;
    std::vector<std::int32_t> xw0, xw1, yw0, yw1;

    std::vector<Rect> raw;
    int rawCount = 0;
    bool rawOverflow = false;
    std::vector<Rect> faces;
    int faceCount = 0;
    long windows = 0;

    // groupRectangles working arrays.
    std::vector<int> parent, label, classCount;
    std::vector<Rect> classSum;

    char error[160] = "";

    void setError(const char* msg) noexcept { std::snprintf(error, sizeof error, "%s", msg); }

    FixedFeature fixFeature(const HaarFeature& f) const
    {
        if (f.tilted)
            throw std::runtime_error("tilted Haar features are not supported");
        FixedFeature out{};
        out.rectCount = f.rectCount;
        for (int i = 0; i < f.rectCount; ++i) {
            const HaarRect& r = f.rects[static_cast<std::size_t>(i)];
            if (r.weight != std::nearbyint(r.weight) || std::fabs(r.weight) > 64.0f) {
                throw std::runtime_error("rectangle weight " + std::to_string(r.weight) +
                                         " is not a small integer");
            }
            out.weight[i] = static_cast<std::int32_t>(r.weight);
            out.ofs[i][0] = r.y * stride + r.x;
            out.ofs[i][1] = r.y * stride + r.x + r.width;
            out.ofs[i][2] = (r.y + r.height) * stride + r.x;
            out.ofs[i][3] = (r.y + r.height) * stride + r.x + r.width;
        }
        return out;
    }

    RowFeature rowFeature(const HaarFeature& f) const
    {
        RowFeature out{};
        out.twoRects = f.rectCount <= 2;
        const int half = (stride + 1) / 2;
        // Column c of the deinterleaved table: even columns first, odd ones from `half` on.
        auto split = [&](int r, int c) { return r * stride + (c & 1 ? half : 0) + (c >> 1); };
        for (int i = 0; i < f.rectCount; ++i) {
            const HaarRect& r = f.rects[static_cast<std::size_t>(i)];
            out.weight[i] = static_cast<std::int32_t>(r.weight);
            const int xs[4] = {r.x, r.x + r.width, r.x, r.x + r.width};
            const int ys[4] = {r.y, r.y, r.y + r.height, r.y + r.height};
            for (int k = 0; k < 4; ++k) {
                out.plain[i][k] = ys[k] * stride + xs[k];
                out.split[i][k] = split(ys[k], xs[k]);
            }
        }
        return out;
    }

    // OpenCV's variance normalisation factor of the window at p/q, 0 when the window is flat.
    float windowNorm(const std::int32_t* p, const std::uint32_t* q) const noexcept
    {
        const std::int32_t valsum = rectSum(p, normOfs);
        const std::uint32_t valsq = q[normOfs[0]] - q[normOfs[1]] - q[normOfs[2]] + q[normOfs[3]];
        const std::int64_t nfi = static_cast<std::int64_t>(normArea) * valsq -
                                 static_cast<std::int64_t>(valsum) * valsum;
        if (nfi < nfRejectBelow)
            return 0.0f;
        // As OpenCV: vnf = float(1 / sqrt(nf)); flat when area * vnf >= 0.1.
        const float vnf = static_cast<float>(1.0 / std::sqrt(static_cast<double>(nfi)));
        if (!(normArea * static_cast<double>(vnf) < 1e-1))
            return 0.0f;
        return vnf;
    }

    // The inverse of OpenCV's runAt: 1 = pass, -s = rejected at stage s, -1 = flat window.
    // Stages before firstStage are taken as passed (the row prefilter evaluated them).
    int runAt(const std::int32_t* p, const std::uint32_t* q, int firstStage = 0) const noexcept
    {
        const float vnf = windowNorm(p, q);
        if (vnf == 0.0f)
            return -1;
        // vnf is a float >= 2^-25 here: vnf * 2^48 is an integer (exponent arithmetic only).
        const auto k = static_cast<std::int64_t>(static_cast<double>(vnf) * kNormScale);

        const int nstages = static_cast<int>(stages.size());
        if (stumps) {
            const Stump* s =
                stumpList.data() +
                (firstStage < nstages ? stages[static_cast<std::size_t>(firstStage)].first : 0);
            for (int si = firstStage; si < nstages; ++si) {
                const FixedStage& st = stages[static_cast<std::size_t>(si)];
                std::int64_t acc = 0;
                const Stump* end = s + st.count;
                // Integer sums are exact in any order, so a stage can stop as soon as the rest
                // of its stumps can no longer change the outcome.
                for (; s != end; ++s) {
                    // Branch-free: the comparison is data dependent and mispredicts often.
                    const std::int64_t below =
                        -static_cast<std::int64_t>(featureValue(s->feature, p) * k < s->threshold);
                    acc += s->right + ((s->left - s->right) & below);
                    if (acc + s->restMax < st.threshold)
                        return -si;
                    if (acc + s->restMin >= st.threshold)
                        break;
                }
                s = end;
            }
            return 1;
        }
        for (int si = firstStage; si < nstages; ++si) {
            const FixedStage& st = stages[static_cast<std::size_t>(si)];
            std::int64_t acc = 0;
            for (int i = 0; i < st.count; ++i) {
                const FixedWeak& w = weak[static_cast<std::size_t>(st.first + i)];
                const TreeNode* tree = nodes.data() + w.firstNode;
                if (twoNodeTrees) {
                    // Node 0 leads to a leaf or to node 1: evaluate both, pick without branches.
                    const int b0 =
                        -static_cast<int>(featureValue(tree[0].feature, p) * k < tree[0].threshold);
                    const int b1 =
                        -static_cast<int>(featureValue(tree[1].feature, p) * k < tree[1].threshold);
                    const int i0 = tree[0].right + ((tree[0].left - tree[0].right) & b0);
                    const int i1 = tree[1].right + ((tree[1].left - tree[1].right) & b1);
                    const int leaf = i0 > 0 ? i1 : i0;
                    acc += leaves[static_cast<std::size_t>(w.firstLeaf - leaf)];
                    if (acc + w.restMax < st.threshold)
                        return -si;
                    if (acc + w.restMin >= st.threshold)
                        break;
                    continue;
                }
                int idx = 0;
                do {
                    const TreeNode& n = tree[idx];
                    const int below =
                        -static_cast<int>(featureValue(n.feature, p) * k < n.threshold);
                    idx = n.right + ((n.left - n.right) & below);
                } while (idx > 0);
                acc += leaves[static_cast<std::size_t>(w.firstLeaf - idx)];
                if (acc + w.restMax < st.threshold)
                    return -si;
                if (acc + w.restMin >= st.threshold)
                    break;
            }
        }
        return 1;
    }

    // Shrinks `gray` to dw x dh (bit-exact bilinear) and builds the integral tables.
    // With `split`, also the column-deinterleaved sum table for the row prefilter.
    void prepare(const ConstImageView& gray, int dw, int dh, bool split = false) noexcept
    {
        resizeTable(gray.width, dw, {xofs0.data(), xofs1.data(), xw0.data(), xw1.data()});
        resizeTable(gray.height, dh, {yofs0.data(), yofs1.data(), yw0.data(), yw1.data()});
        const bool copy = dw == gray.width && dh == gray.height;
        const int sstride = options.maxFrameSize.width;
        for (int y = 0; y < dh; ++y) {
            std::uint8_t* out = scaled.data() + static_cast<std::ptrdiff_t>(y) * sstride;
            if (copy) {
                std::memcpy(out, gray.row(y), static_cast<std::size_t>(dw));
                continue;
            }
            const std::uint8_t* r0 = gray.row(yofs0[static_cast<std::size_t>(y)]);
            const std::uint8_t* r1 = gray.row(yofs1[static_cast<std::size_t>(y)]);
            const std::uint32_t a = static_cast<std::uint32_t>(yw0[static_cast<std::size_t>(y)]);
            const std::uint32_t b = static_cast<std::uint32_t>(yw1[static_cast<std::size_t>(y)]);
            for (int x = 0; x < dw; ++x) {
                const int o0 = xofs0[static_cast<std::size_t>(x)];
                const int o1 = xofs1[static_cast<std::size_t>(x)];
                const auto c0 = static_cast<std::uint32_t>(xw0[static_cast<std::size_t>(x)]);
                const auto c1 = static_cast<std::uint32_t>(xw1[static_cast<std::size_t>(x)]);
                const std::uint32_t h0 = r0[o0] * c0 + r0[o1] * c1;
                const std::uint32_t h1 = r1[o0] * c0 + r1[o1] * c1;
                out[x] = static_cast<std::uint8_t>((h0 * a + h1 * b + (1u << 15)) >> 16);
            }
        }
        // Integral tables: row 0 and column 0 stay zero (set at construction).
        for (int y = 0; y < dh; ++y) {
            const std::uint8_t* in = scaled.data() + static_cast<std::ptrdiff_t>(y) * sstride;
            std::int32_t* s1 = sum.data() + static_cast<std::ptrdiff_t>(y + 1) * stride + 1;
            const std::int32_t* s0 = s1 - stride;
            std::uint32_t* q1 = sqsum.data() + static_cast<std::ptrdiff_t>(y + 1) * stride + 1;
            const std::uint32_t* q0 = q1 - stride;
            std::int32_t rs = 0;
            std::uint32_t rq = 0;
            for (int x = 0; x < dw; ++x) {
                const std::uint32_t v = in[x];
                rs += static_cast<std::int32_t>(v);
                rq += v * v;  // wraps like OpenCV's 32-bit table; window sums stay exact
                s1[x] = s0[x] + rs;
                q1[x] = q0[x] + rq;
            }
        }
        if (split) {
            const int half = (stride + 1) / 2;
            for (int y = 0; y <= dh; ++y) {
                const std::int32_t* in = sum.data() + static_cast<std::ptrdiff_t>(y) * stride;
                std::int32_t* even = sumSplit.data() + static_cast<std::ptrdiff_t>(y) * stride;
                std::int32_t* odd = even + half;
                for (int x = 0; x + 1 <= dw; x += 2) {
                    even[x >> 1] = in[x];
                    odd[x >> 1] = in[x + 1];
                }
                if ((dw & 1) == 0)
                    even[dw >> 1] = in[dw];
            }
        }
    }

    // Evaluates stages 0.. of the row's windows j0 <= j < j1 (x = j * step, rows y) together,
    // a weak classifier at a time over all of them (vectorised), while at least a quarter of
    // them is still alive: rowResult[j] = 1 when window j passed those stages, 2 when a stage
    // sum was too close to its threshold to decide in Q20 (runAt continues from rowFrom[j]),
    // else runAt's value. Returns how many stages were done; runAt continues from there for
    // the windows still alive. Decisions are OpenCV's float comparisons (the integer path's
    // equivalent) and sure stage outcomes only, so the results are those of runAt.
    int prefilterRow(int y, int step, int j0, int j1) noexcept
    {
        const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(y) * stride;
        int alive = 0;
        for (int j = j0; j < j1; ++j) {
            const std::ptrdiff_t at = row + static_cast<std::ptrdiff_t>(j) * step;
            const float vnf = windowNorm(sum.data() + at, sqsum.data() + at);
            rowNorm[static_cast<std::size_t>(j)] = vnf;
            rowResult[static_cast<std::size_t>(j)] = vnf == 0.0f ? -1 : 1;
            rowFrom[static_cast<std::size_t>(j)] = 0;
            alive += vnf != 0.0f;
        }
        const bool split = step == 2;
        const std::int32_t* table = (split ? sumSplit.data() : sum.data()) + row;
        const int nstages = static_cast<int>(stages.size());
        // Survivors cluster (faces, texture): each stage runs over the span from the first
        // to the last window still alive, while at least 1 / divisor of the span is alive.
        int lo = j0;
        int hi = j1;
        int si = 0;
        for (; si < nstages; ++si) {
            while (lo < hi && rowResult[static_cast<std::size_t>(lo)] != 1)
                ++lo;
            while (hi > lo && rowResult[static_cast<std::size_t>(hi - 1)] != 1)
                --hi;
            const int n = hi - lo;
            if (n == 0 || alive * kPrefilterAliveDivisor < n)
                break;
            const FixedStage& st = stages[static_cast<std::size_t>(si)];
            const std::int32_t* base = table + lo;
            const float* vnf = rowNorm.data() + lo;
            std::int32_t* acc = rowAcc.data() + lo;
            std::fill_n(acc, n, 0);
            for (int i = st.first; i < st.first + st.count; ++i) {
                const auto k = static_cast<std::size_t>(i);
                if (stumps)
                    rowStumpPass(rowStumps[k], base, split, n, vnf, acc);
                else
                    rowTreePass(rowTrees[k], base, split, n, vnf, acc);
            }
            alive = settleStage(acc, rowResult.data() + lo, rowFrom.data() + lo, n, si,
                                st.rowReject, st.rowPass);
        }
        return si;
    }

    // Where a scan stands: the next scale of OpenCV's list and the next window in it. detect()
    // runs a scan from start to end in one call; detectMaskedIncremental() keeps it between calls.
    struct Cursor {
        bool active = false;   // a scan is in progress
        bool inScale = false;  // the scale fields below describe the scale being scanned
        Size image{};          // size of the images of this scan
        double nextFactor = 1.0;
        int nstripes = 0;
        float sc = 1.0f;
        int dw = 0, dh = 0, step = 2, xEnd = 0, yEnd = 0, boxW = 0, boxH = 0;
        int y = 0, x = 0;  // next window of the scale
    };
    Cursor cursor;

    enum class Stop { Done, Budget, FirstHit };

    void startScan(Size image) noexcept
    {
        rawCount = 0;
        rawOverflow = false;
        cursor = {};
        cursor.active = true;
        cursor.image = image;
    }

    // Moves the cursor to the next scale with windows to scan, as OpenCV's
    // detectMultiScaleNoGrouping lists them; false past the last one.
    bool enterNextScale() noexcept
    {
        Cursor& c = cursor;
        const int imgW = c.image.width;
        const int imgH = c.image.height;
        const int maxW = options.maxSize.width > 0 ? options.maxSize.width : imgW;
        const int maxH = options.maxSize.height > 0 ? options.maxSize.height : imgH;
        if (imgW < winW || imgH < winH)
            return false;
        for (;;) {
            const double factor = c.nextFactor;
            c.nextFactor *= options.scaleFactor;
            if (std::lrint(winW * factor) > imgW || std::lrint(winH * factor) > imgH)
                return false;
            const auto sc = static_cast<float>(factor);
            const long ww = std::lrint(static_cast<float>(winW) * sc);
            const long wh = std::lrint(static_cast<float>(winH) * sc);
            if (ww > maxW || wh > maxH)
                return false;
            if (ww < options.minSize.width || wh < options.minSize.height)
                continue;

            const int dw = static_cast<int>(std::lrint(static_cast<float>(imgW) / sc));
            const int dh = static_cast<int>(std::lrint(static_cast<float>(imgH) / sc));
            const int step = sc >= 2.0f ? 1 : 2;
            const int xEnd = std::max(dw + 1 - winW, 0);
            const int rows = std::max(dh + 1 - winH, 0);
            // OpenCV cuts the rows into ceil(w0 / 32) stripes (w0: the first scale's working
            // width) of a whole number of steps, rounding the step count down: the last row of
            // a scale can fall outside every stripe and is then never scanned.
            if (c.nstripes == 0)
                c.nstripes = std::max((xEnd + 31) / 32, 1);
            const int stripe = std::max((rows / step + c.nstripes - 1) / c.nstripes, 1) * step;
            const int yEnd = std::min(c.nstripes * stripe, rows);
            if (xEnd == 0 || yEnd == 0)
                continue;
            c.sc = sc;
            c.dw = dw;
            c.dh = dh;
            c.step = step;
            c.xEnd = xEnd;
            c.yEnd = yEnd;
            c.boxW = static_cast<int>(ww);
            c.boxH = static_cast<int>(wh);
            c.y = 0;
            c.x = 0;
            c.inScale = true;
            return true;
        }
    }

    // The scan of cv::CascadeClassifier::detectMultiScaleNoGrouping from the cursor on, over
    // `gray` (the frame of this call), evaluating at most `budget` windows. A window is skipped
    // (not counted) when its centre lies in an `exclude` box or, with a mask, its mask fraction
    // is below minFraction. A scale is shrunk from `gray` only when one of its windows is
    // evaluated in this call. With firstHit, stops after the first window that passes.
    Stop run(const ConstImageView& gray, const IntegralImage* mask, float minFraction,
             std::span<const Rect> exclude, bool firstHit, long budget) noexcept
    {
        Cursor& c = cursor;
        windows = 0;
        const int imgW = gray.width;
        const int imgH = gray.height;
        const Size maskSize = mask != nullptr ? mask->size() : Size{};
        bool prepared = false;  // the cursor's scale is shrunk from this call's frame
        for (;;) {
            if (!c.inScale) {
                if (!enterNextScale()) {
                    c.active = false;
                    return Stop::Done;
                }
                prepared = false;
            }
            const float sc = c.sc;
            const int step = c.step;
            const int boxW = c.boxW;
            const int boxH = c.boxH;
            const int stepShift = step == 2 ? 1 : 0;  // x / step without a division
            for (; c.y < c.yEnd; c.y += step, c.x = 0) {
                const int y = c.y;
                const int by = static_cast<int>(std::lrint(static_cast<float>(y) * sc));
                // The windows of the row (from the cursor on) that the mask and the exclusions
                // let through.
                const int j0 = c.x >> stepShift;
                const int j1 = (c.xEnd + step - 1) / step;
                int wanted = 0;
                const bool everyWindow = exclude.empty() && mask == nullptr;
                for (int j = j0; j < j1 && everyWindow; ++j)
                    rowWanted[static_cast<std::size_t>(j)] = 1;
                if (everyWindow)
                    wanted = j1 - j0;
                for (int j = j0; j < j1 && !everyWindow; ++j) {
                    const int bx = static_cast<int>(std::lrint(static_cast<float>(j * step) * sc));
                    bool ok = true;
                    if (!exclude.empty()) {
                        const int cx = bx + boxW / 2;
                        const int cy = by + boxH / 2;
                        for (const Rect& e : exclude) {
                            if (cx >= e.x && cx < e.x + e.width && cy >= e.y &&
                                cy < e.y + e.height) {
                                ok = false;
                                break;
                            }
                        }
                    }
                    if (ok && mask != nullptr) {
                        const int mx0 = bx * maskSize.width / imgW;
                        const int my0 = by * maskSize.height / imgH;
                        const int mx1 = ((bx + boxW) * maskSize.width + imgW - 1) / imgW;
                        const int my1 = ((by + boxH) * maskSize.height + imgH - 1) / imgH;
                        ok = mask->maskFraction({mx0, my0, mx1 - mx0, my1 - my0}) >= minFraction;
                    }
                    rowWanted[static_cast<std::size_t>(j)] = ok;
                    wanted += ok;
                }
                if (wanted == 0)
                    continue;
                if (windows >= budget)
                    return Stop::Budget;  // resumes at this row's first window to evaluate
                if (!prepared) {
                    prepare(gray, c.dw, c.dh, rowPrefilter && step == 2);
                    prepared = true;
                }
                const int done = rowPrefilter && wanted >= kPrefilterMinWindows
                                     ? prefilterRow(y, step, j0, j1)
                                     : 0;
                for (; c.x < c.xEnd; c.x += step) {
                    const int x = c.x;
                    const auto j = static_cast<std::size_t>(x >> stepShift);
                    if (!rowWanted[j])
                        continue;
                    if (windows >= budget)
                        return Stop::Budget;  // resumes at this window
                    ++windows;
                    const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(y) * stride + x;
                    // After the prefilter: decided (<= 0), alive after `done` stages (1), or
                    // parked at an undecidable stage sum (2).
                    const int pre = done > 0 ? rowResult[j] : 1;
                    const int result = pre <= 0 ? pre
                                                : runAt(sum.data() + at, sqsum.data() + at,
                                                        pre == 1 ? done : rowFrom[j]);
                    if (result > 0) {
                        const int bx = static_cast<int>(std::lrint(static_cast<float>(x) * sc));
                        if (rawCount < static_cast<int>(raw.size())) {
                            raw[static_cast<std::size_t>(rawCount++)] = {bx, by, boxW, boxH};
                        } else {
                            rawOverflow = true;
                        }
                        if (firstHit) {
                            c.x += step;
                            return Stop::FirstHit;
                        }
                    }
                    if (result == 0)
                        c.x += step;  // OpenCV skips past a first-stage rejection
                }
            }
            c.inScale = false;
        }
    }

    // A whole scan in one call (detect, detectMasked, detectFirst).
    Stop scanWhole(const ConstImageView& gray, const IntegralImage* mask, float minFraction,
                   std::span<const Rect> exclude, bool firstHit) noexcept
    {
        startScan(gray.size());
        const Stop stop =
            run(gray, mask, minFraction, exclude, firstHit, std::numeric_limits<long>::max());
        cursor.active = false;
        return stop;
    }

    int group(std::span<const Rect> rects, int minNeighbors, double eps,
              std::span<Rect> out) noexcept
    {
        const int n = static_cast<int>(std::min(rects.size(), parent.size()));
        if (minNeighbors <= 0) {
            const int m = std::min(n, static_cast<int>(out.size()));
            std::copy_n(rects.begin(), m, out.begin());
            return m;
        }
        // cv::partition with SimilarRects: connected components of the similarity graph,
        // numbered by first appearance.
        auto find = [&](int i) {
            while (parent[static_cast<std::size_t>(i)] != i) {
                parent[static_cast<std::size_t>(i)] =
                    parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
                i = parent[static_cast<std::size_t>(i)];
            }
            return i;
        };
        for (int i = 0; i < n; ++i)
            parent[static_cast<std::size_t>(i)] = i;
        for (int i = 0; i < n; ++i) {
            const Rect& a = rects[static_cast<std::size_t>(i)];
            for (int j = i + 1; j < n; ++j) {
                const Rect& b = rects[static_cast<std::size_t>(j)];
                const double delta =
                    eps * (std::min(a.width, b.width) + std::min(a.height, b.height)) * 0.5;
                if (std::abs(a.x - b.x) <= delta && std::abs(a.y - b.y) <= delta &&
                    std::abs(a.x + a.width - b.x - b.width) <= delta &&
                    std::abs(a.y + a.height - b.y - b.height) <= delta) {
                    const int ra = find(i);
                    const int rb = find(j);
                    if (ra != rb)
                        parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
                }
            }
        }
        int nclasses = 0;
        for (int i = 0; i < n; ++i) {
            const int root = find(i);
            if (root == i) {
                label[static_cast<std::size_t>(i)] = nclasses;
                classSum[static_cast<std::size_t>(nclasses)] = {};
                classCount[static_cast<std::size_t>(nclasses)] = 0;
                ++nclasses;
            } else {
                label[static_cast<std::size_t>(i)] = label[static_cast<std::size_t>(root)];
            }
            const int c = label[static_cast<std::size_t>(i)];
            Rect& s = classSum[static_cast<std::size_t>(c)];
            const Rect& r = rects[static_cast<std::size_t>(i)];
            s.x += r.x;
            s.y += r.y;
            s.width += r.width;
            s.height += r.height;
            ++classCount[static_cast<std::size_t>(c)];
        }
        for (int c = 0; c < nclasses; ++c) {
            Rect& s = classSum[static_cast<std::size_t>(c)];
            const float inv = 1.0f / static_cast<float>(classCount[static_cast<std::size_t>(c)]);
            s = {static_cast<int>(std::lrint(static_cast<float>(s.x) * inv)),
                 static_cast<int>(std::lrint(static_cast<float>(s.y) * inv)),
                 static_cast<int>(std::lrint(static_cast<float>(s.width) * inv)),
                 static_cast<int>(std::lrint(static_cast<float>(s.height) * inv))};
        }
        int count = 0;
        for (int i = 0; i < nclasses; ++i) {
            const Rect r1 = classSum[static_cast<std::size_t>(i)];
            const int n1 = classCount[static_cast<std::size_t>(i)];
            if (n1 <= minNeighbors)
                continue;
            bool inside = false;
            // Drop small groups inside larger, better-supported ones.
            for (int j = 0; j < nclasses && !inside; ++j) {
                const int n2 = classCount[static_cast<std::size_t>(j)];
                if (j == i || n2 <= minNeighbors)
                    continue;
                const Rect r2 = classSum[static_cast<std::size_t>(j)];
                const int dx = static_cast<int>(std::lrint(r2.width * eps));
                const int dy = static_cast<int>(std::lrint(r2.height * eps));
                inside = r1.x >= r2.x - dx && r1.y >= r2.y - dy &&
                         r1.x + r1.width <= r2.x + r2.width + dx &&
                         r1.y + r1.height <= r2.y + r2.height + dy &&
                         (n2 > std::max(3, n1) || n1 < 3);
            }
            if (!inside && count < static_cast<int>(out.size())) {
                out[static_cast<std::size_t>(count++)] = r1;
            }
        }
        return count;
    }

    bool checkImage(const ConstImageView& gray) noexcept
    {
        if (gray.empty() || gray.format != PixelFormat::Gray8) {
            setError("face detector: expected a Gray8 image");
            return false;
        }
        if (gray.width > options.maxFrameSize.width || gray.height > options.maxFrameSize.height) {
            setError("face detector: image larger than the configured maxFrameSize");
            return false;
        }
        return true;
    }

    // As cv::CascadeClassifier::detectMultiScale: groups, then clips the boxes to the image
    // (a window at the last position can reach past the edge by the size rounding).
    int finish(Size image) noexcept
    {
        const std::span<Rect> out{faces.data(), faces.size()};
        int n = 0;
        if (options.minNeighbors <= 0) {
            n = std::min(rawCount, static_cast<int>(out.size()));
            std::copy_n(raw.begin(), n, out.begin());
        } else {
            n = group({raw.data(), static_cast<std::size_t>(rawCount)}, options.minNeighbors, 0.2,
                      out);
        }
        faceCount = 0;
        for (int i = 0; i < n; ++i) {
            const Rect r = out[static_cast<std::size_t>(i)];
            const int x0 = std::max(r.x, 0);
            const int y0 = std::max(r.y, 0);
            const int x1 = std::min(r.x + r.width, image.width);
            const int y1 = std::min(r.y + r.height, image.height);
            if (x1 > x0 && y1 > y0)
                out[static_cast<std::size_t>(faceCount++)] = {x0, y0, x1 - x0, y1 - y0};
        }
        return faceCount;
    }
};

FaceDetector::FaceDetector(const HaarCascade& cascade, const FaceDetectorOptions& options)
    : impl_(std::make_unique<Impl>())
{
    Impl& d = *impl_;
    d.options = options;
    if (!(options.scaleFactor > 1.0))
        throw std::runtime_error("face detector: scaleFactor <= 1");
    if (options.maxFrameSize.width <= 0 || options.maxFrameSize.height <= 0 ||
        options.maxRawHits <= 0 || options.maxFaces <= 0) {
        throw std::runtime_error("face detector: bad frame size or capacities");
    }
    if (cascade.stages.empty() || cascade.windowWidth < 3 || cascade.windowHeight < 3) {
        throw std::runtime_error("face detector: empty cascade");
    }
    d.winW = cascade.windowWidth;
    d.winH = cascade.windowHeight;
    d.stride = options.maxFrameSize.width + 1;
    d.stumps = cascade.stumpsOnly();

    // OpenCV normalises over the window minus a 1-pixel border.
    const int nw = d.winW - 2;
    const int nh = d.winH - 2;
    d.normOfs[0] = d.stride + 1;
    d.normOfs[1] = d.stride + 1 + nw;
    d.normOfs[2] = (1 + nh) * d.stride + 1;
    d.normOfs[3] = (1 + nh) * d.stride + 1 + nw;
    d.normArea = static_cast<double>(nw) * nh;
    // Std dev <= 10 <=> nf <= (10 * area)^2: below 99.9% of that, surely flat (the exact float
    // test decides the rest).
    d.nfRejectBelow = static_cast<std::int64_t>(0.999 * (10.0 * d.normArea) * (10.0 * d.normArea));

    std::vector<FixedFeature> features;
    features.reserve(cascade.features.size());
    bool floatExact = true;
    for (const HaarFeature& f : cascade.features) {
        features.push_back(d.fixFeature(f));
        // |f * K| must fit: K <= 2^48 / (10 * area) for windows that are not flat.
        double bound = 0.0;
        for (int i = 0; i < f.rectCount; ++i) {
            const HaarRect& r = f.rects[static_cast<std::size_t>(i)];
            bound += std::fabs(r.weight) * r.width * r.height * 255.0;
        }
        if (bound * std::ldexp(1.0, kNormShift) / (10.0 * d.normArea) > std::ldexp(1.0, 62)) {
            throw std::runtime_error("face detector: feature range too large for fixed point");
        }
        // The row prefilter converts feature sums to float: exact below 2^24.
        floatExact = floatExact && bound < 16777216.0;
    }

    for (const HaarStage& s : cascade.stages) {
        FixedStage st{};
        st.threshold = leafFixed(static_cast<double>(s.threshold - kStageThresholdEps));
        st.first = d.stumps ? static_cast<int>(d.stumpList.size()) : s.firstWeak;
        st.count = s.weakCount;
        for (int i = 0; i < s.weakCount; ++i) {
            const HaarWeakClassifier& w = cascade.weak[static_cast<std::size_t>(s.firstWeak + i)];
            if (d.stumps) {
                const HaarNode& n = cascade.nodes[static_cast<std::size_t>(w.firstNode)];
                // A stump's children are leaves: left 0 -> leaf 0, right -1 -> leaf 1.
                const float leftLeaf =
                    cascade.leaves[static_cast<std::size_t>(w.firstLeaf - n.left)];
                const float rightLeaf =
                    cascade.leaves[static_cast<std::size_t>(w.firstLeaf - n.right)];
                d.stumpList.push_back({features[static_cast<std::size_t>(n.featureIndex)],
                                       nodeThreshold(n.threshold), leafFixed(leftLeaf),
                                       leafFixed(rightLeaf), 0, 0, n.featureIndex, n.threshold});
            }
        }
        if (d.stumps) {
            // Most decisive stumps first, so the early exits come sooner.
            const auto first = d.stumpList.begin() + st.first;
            std::stable_sort(first, d.stumpList.end(), [](const Stump& a, const Stump& b) {
                return std::abs(a.left - a.right) > std::abs(b.left - b.right);
            });
            std::int64_t restMax = 0;
            std::int64_t restMin = 0;
            for (auto it = d.stumpList.end(); it != first;) {
                --it;
                it->restMax = restMax;
                it->restMin = restMin;
                restMax += std::max(it->left, it->right);
                restMin += std::min(it->left, it->right);
            }
        }
        d.stages.push_back(st);
    }
    if (!d.stumps) {
        d.twoNodeTrees = true;
        for (const HaarWeakClassifier& w : cascade.weak) {
            if (w.nodeCount != 2) {
                d.twoNodeTrees = false;
                break;
            }
            const HaarNode& n0 = cascade.nodes[static_cast<std::size_t>(w.firstNode)];
            const HaarNode& n1 = cascade.nodes[static_cast<std::size_t>(w.firstNode + 1)];
            if ((n0.left > 0) == (n0.right > 0) || n1.left > 0 || n1.right > 0)
                d.twoNodeTrees = false;
        }
        for (const HaarNode& n : cascade.nodes) {
            d.nodes.push_back({features[static_cast<std::size_t>(n.featureIndex)],
                               nodeThreshold(n.threshold), n.left, n.right, n.featureIndex,
                               n.threshold});
        }
        for (const float leaf : cascade.leaves)
            d.leaves.push_back(leafFixed(leaf));
        for (const HaarWeakClassifier& w : cascade.weak)
            d.weak.push_back({w.firstNode, w.firstLeaf, 0, 0});
        // Per stage: the trees with the widest leaf range first (exact in any order: integer
        // sums), then what the remaining trees can still add, for the early exits.
        auto spread = [&](const FixedWeak& w, bool high) {
            const int leafCount = [&] {
                for (const HaarWeakClassifier& hw : cascade.weak) {
                    if (hw.firstLeaf == w.firstLeaf)
                        return hw.nodeCount + 1;
                }
                return 0;
            }();
            std::int64_t hi = std::numeric_limits<std::int64_t>::min();
            std::int64_t lo = std::numeric_limits<std::int64_t>::max();
            for (int l = 0; l < leafCount; ++l) {
                const std::int64_t v = d.leaves[static_cast<std::size_t>(w.firstLeaf + l)];
                hi = std::max(hi, v);
                lo = std::min(lo, v);
            }
            return high ? hi : lo;
        };
        for (const FixedStage& st : d.stages) {
            const auto first = d.weak.begin() + st.first;
            const auto last = first + st.count;
            std::stable_sort(first, last, [&](const FixedWeak& a, const FixedWeak& b) {
                return spread(a, true) - spread(a, false) > spread(b, true) - spread(b, false);
            });
            std::int64_t restMax = 0;
            std::int64_t restMin = 0;
            for (auto it = last; it != first;) {
                --it;
                it->restMax = restMax;
                it->restMin = restMin;
                restMax += spread(*it, true);
                restMin += spread(*it, false);
            }
        }
    }

    const auto maxW = static_cast<std::size_t>(options.maxFrameSize.width);
    const auto maxH = static_cast<std::size_t>(options.maxFrameSize.height);
    if (options.rowPrefilter && floatExact && d.stumps) {
        for (const Stump& st : d.stumpList) {
            d.rowStumps.push_back(
                {d.rowFeature(cascade.features[static_cast<std::size_t>(st.featureIndex)]),
                 st.fileThreshold, rowLeaf(st.left), rowLeaf(st.right)});
        }
        d.rowPrefilter = true;
    } else if (options.rowPrefilter && floatExact && d.twoNodeTrees) {
        for (const FixedWeak& w : d.weak) {
            const TreeNode& n0 = d.nodes[static_cast<std::size_t>(w.firstNode)];
            const TreeNode& n1 = d.nodes[static_cast<std::size_t>(w.firstNode + 1)];
            auto leaf = [&](int child) {
                return rowLeaf(d.leaves[static_cast<std::size_t>(w.firstLeaf - child)]);
            };
            RowTree t{};
            t.feature0 = d.rowFeature(cascade.features[static_cast<std::size_t>(n0.featureIndex)]);
            t.feature1 = d.rowFeature(cascade.features[static_cast<std::size_t>(n1.featureIndex)]);
            t.threshold0 = n0.fileThreshold;
            t.threshold1 = n1.fileThreshold;
            t.node1OnBelow = n0.left > 0;
            t.direct = leaf(n0.left > 0 ? n0.right : n0.left);
            t.below1 = leaf(n1.left);
            t.above1 = leaf(n1.right);
            d.rowTrees.push_back(t);
        }
        d.rowPrefilter = true;
    }

    d.scaled.assign(maxW * maxH, 0);
    d.sum.assign((maxW + 1) * (maxH + 1), 0);
    d.sqsum.assign((maxW + 1) * (maxH + 1), 0);
    if (d.rowPrefilter)
        d.sumSplit.assign((maxW + 1) * (maxH + 1), 0);
    d.rowNorm.assign(maxW + 1, 0.0f);
    d.rowAcc.assign(maxW + 1, 0);
    d.rowResult.assign(maxW + 1, 0);
    d.rowFrom.assign(maxW + 1, 0);
    // The Q20 sum of n leaves is within n / 2 units of the exact sum.
    for (FixedStage& st : d.stages) {
        constexpr int shift = kLeafShift - kRowLeafShift;
        const std::int64_t slack = std::int64_t{st.count} << (shift - 1);
        auto ceilQ20 = [](std::int64_t v) { return -((-v) >> shift); };
        st.rowReject = static_cast<std::int32_t>(ceilQ20(st.threshold - slack));
        st.rowPass = static_cast<std::int32_t>(ceilQ20(st.threshold + slack));
    }
    d.rowWanted.assign(maxW + 1, 0);
    for (auto* v : {&d.xofs0, &d.xofs1})
        v->assign(maxW, 0);
    for (auto* v : {&d.yofs0, &d.yofs1})
        v->assign(maxH, 0);
    for (auto* v : {&d.xw0, &d.xw1})
        v->assign(maxW, 0);
    for (auto* v : {&d.yw0, &d.yw1})
        v->assign(maxH, 0);
    const auto rawCap = static_cast<std::size_t>(options.maxRawHits);
    d.raw.assign(rawCap, Rect{});
    d.faces.assign(static_cast<std::size_t>(options.maxFaces), Rect{});
    d.parent.assign(rawCap, 0);
    d.label.assign(rawCap, 0);
    d.classCount.assign(rawCap, 0);
    d.classSum.assign(rawCap, Rect{});
}

FaceDetector::~FaceDetector() = default;
FaceDetector::FaceDetector(FaceDetector&&) noexcept = default;
FaceDetector& FaceDetector::operator=(FaceDetector&&) noexcept = default;

int FaceDetector::detect(const ConstImageView& gray) noexcept
{
    Impl& d = *impl_;
    if (!d.checkImage(gray))
        return -1;
    d.scanWhole(gray, nullptr, 0.0f, {}, false);
    return d.finish(gray.size());
}

int FaceDetector::detectMasked(const ConstImageView& gray, const IntegralImage& mask,
                               float minFraction, std::span<const Rect> exclude) noexcept
{
    Impl& d = *impl_;
    if (!d.checkImage(gray))
        return -1;
    if (mask.size().width <= 0 || mask.size().height <= 0) {
        d.setError("face detector: empty mask integral image");
        return -1;
    }
    d.scanWhole(gray, &mask, minFraction, exclude, false);
    return d.finish(gray.size());
}

bool FaceDetector::detectMaskedIncremental(const ConstImageView& gray, const IntegralImage* mask,
                                           float minFraction, std::span<const Rect> exclude,
                                           long windowBudget) noexcept
{
    Impl& d = *impl_;
    d.windows = 0;
    if (!d.checkImage(gray)) {
        d.cursor.active = false;
        return false;
    }
    if (mask != nullptr && (mask->size().width <= 0 || mask->size().height <= 0)) {
        d.setError("face detector: empty mask integral image");
        d.cursor.active = false;
        return false;
    }
    if (!d.cursor.active || d.cursor.image != gray.size())
        d.startScan(gray.size());
    const long budget = windowBudget > 0 ? windowBudget : std::numeric_limits<long>::max();
    if (d.run(gray, mask, minFraction, exclude, false, budget) != Impl::Stop::Done)
        return false;
    d.finish(gray.size());
    return true;
}

void FaceDetector::resetIncremental() noexcept
{
    impl_->cursor.active = false;
}

bool FaceDetector::incrementalScanActive() const noexcept
{
    return impl_->cursor.active;
}

bool FaceDetector::detectFirst(const ConstImageView& gray, Rect& hit) noexcept
{
    Impl& d = *impl_;
    d.faceCount = 0;
    if (!d.checkImage(gray))
        return false;
    if (d.scanWhole(gray, nullptr, 0.0f, {}, true) != Impl::Stop::FirstHit || d.rawCount == 0)
        return false;
    hit = d.raw[0];
    return true;
}

std::span<const Rect> FaceDetector::faces() const noexcept
{
    const Impl& d = *impl_;
    return {d.faces.data(), static_cast<std::size_t>(d.faceCount)};
}

std::span<const Rect> FaceDetector::rawHits() const noexcept
{
    return {impl_->raw.data(), static_cast<std::size_t>(impl_->rawCount)};
}

bool FaceDetector::rawHitsOverflowed() const noexcept
{
    return impl_->rawOverflow;
}

long FaceDetector::windowsEvaluated() const noexcept
{
    return impl_->windows;
}

int FaceDetector::evaluateWindow(const ConstImageView& gray, int x, int y) noexcept
{
    Impl& d = *impl_;
    if (!d.checkImage(gray))
        return -1;
    if (x < 0 || y < 0 || x + d.winW > gray.width || y + d.winH > gray.height)
        return -1;
    d.prepare(gray, gray.width, gray.height);
    return d.runAt(d.sum.data() + static_cast<std::ptrdiff_t>(y) * d.stride + x,
                   d.sqsum.data() + static_cast<std::ptrdiff_t>(y) * d.stride + x);
}

int FaceDetector::groupRectangles(std::span<const Rect> rects, int minNeighbors, double eps,
                                  std::span<Rect> out) noexcept
{
    return impl_->group(rects, minNeighbors, eps, out);
}

const std::int32_t* FaceDetector::sumTable() const noexcept
{
    return impl_->sum.data();
}

const std::uint32_t* FaceDetector::squaredSumTable() const noexcept
{
    return impl_->sqsum.data();
}

int FaceDetector::tableStride() const noexcept
{
    return impl_->stride;
}

Size FaceDetector::windowSize() const noexcept
{
    return {impl_->winW, impl_->winH};
}

const char* FaceDetector::lastError() const noexcept
{
    return impl_->error;
}

}  // namespace vision
