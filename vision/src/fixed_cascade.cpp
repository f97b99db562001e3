// The cascade in fixed point (METHOD.md §3, Viola-Jones with OpenCV's trained cascade), built to
// decide every window as OpenCV 4.6's cascadedetect.cpp does:
//  - a window is rejected when the standard deviation over its inner (w-2)x(h-2) area is <= 10;
//  - features are normalised by 1/sqrt(area * sqsum - sum^2) rounded to float, and stage
//    thresholds are lowered by 1e-5 (THRESHOLD_EPS).
// The decisions are exact integer comparisons equivalent to OpenCV's float ones: the float
// normalisation factor is an integer in Q48, node thresholds are placed half a float step below
// (so a product OpenCV rounds onto the threshold counts as not below it), leaves are Q40. Within
// a stage, the weak classifiers are sorted by decisiveness and a stage stops as soon as the rest
// cannot change its outcome (integer sums are exact in any order).
//
// The row form (RowPrefilter) keeps OpenCV's float comparisons themselves (feature sums are exact
// in float below 2^24, the product is rounded once, as in OpenCV) and sums the leaves in Q20 in
// 32 bits: each leaf within half a unit of its Q40 value, so a stage decides only where that
// rounding cannot matter (rowReject / rowPass), else the exact path decides.

#include "fixed_cascade.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vision {
namespace {

constexpr int kNormShift = 48;  // Q of the per-window normalisation factor and node thresholds
constexpr double kNormScale = 281474976710656.0;  // 2^kNormShift
constexpr int kLeafShift = 40;                    // Q of leaf values and stage thresholds
constexpr int kRowLeafShift = 20;                 // Q of the row form's leaves and stage sums
constexpr float kStageThresholdEps = 1e-5f;       // OpenCV's THRESHOLD_EPS

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

// A Q40 leaf in the row form's Q20, rounded to nearest.
std::int32_t rowLeaf(std::int64_t q40)
{
    constexpr int shift = kLeafShift - kRowLeafShift;
    return static_cast<std::int32_t>((q40 + (std::int64_t{1} << (shift - 1))) >> shift);
}

inline std::int32_t rectSum(const std::int32_t* p, const std::int32_t* o) noexcept
{
    // Modulo 2^32, as the table wraps on big images (scaled_integrals.cpp): the sum is exact.
    const auto at = [p](std::int32_t i) { return static_cast<std::uint32_t>(p[i]); };
    return static_cast<std::int32_t>(at(o[0]) - at(o[1]) - at(o[2]) + at(o[3]));
}

inline std::int64_t featureValue(const FixedFeature& f, const std::int32_t* p) noexcept
{
    // A 2-rectangle feature has weight 0 and offsets 0 for the third: computing it anyway is
    // cheaper than a branch that mispredicts between the two kinds.
    return f.weight[0] * rectSum(p, f.ofs[0]) + f.weight[1] * rectSum(p, f.ofs[1]) +
           f.weight[2] * rectSum(p, f.ofs[2]);
}

// From the last weak classifier of a stage back to `first`: what those after each can still add
// at most and at least, from `high` / `low` of one.
template <typename It, typename High, typename Low>
void setRest(It first, It last, High high, Low low)
{
    std::int64_t restMax = 0;
    std::int64_t restMin = 0;
    for (auto it = last; it != first;) {
        --it;
        it->restMax = restMax;
        it->restMin = restMin;
        restMax += high(*it);
        restMin += low(*it);
    }
}

}  // namespace

FixedCascade::FixedCascade(const HaarCascade& cascade, int stride, bool rowForm)
{
    if (cascade.stages.empty() || cascade.windowWidth < 3 || cascade.windowHeight < 3)
        throw std::runtime_error("face detector: empty cascade");
    winW_ = cascade.windowWidth;
    winH_ = cascade.windowHeight;
    stride_ = stride;
    stumps_ = cascade.stumpsOnly();
    setNormalisation();
    std::vector<FixedFeature> features;
    const bool floatExact = fixFeatures(cascade, features);
    buildStages(cascade, features);
    if (!stumps_) {
        buildTrees(cascade, features);
        sortTrees(cascade);
    }
    if (rowForm && floatExact && (stumps_ || twoNodeTrees_))
        buildRowForm(cascade);
    // The Q20 sum of n leaves is within n / 2 units of the exact sum.
    for (FixedStage& st : stages_) {
        constexpr int shift = kLeafShift - kRowLeafShift;
        const std::int64_t slack = std::int64_t{st.count} << (shift - 1);
        auto ceilQ20 = [](std::int64_t v) { return -((-v) >> shift); };
        st.rowReject = static_cast<std::int32_t>(ceilQ20(st.threshold - slack));
        st.rowPass = static_cast<std::int32_t>(ceilQ20(st.threshold + slack));
    }
}

void FixedCascade::setNormalisation()
{
    // OpenCV normalises over the window minus a 1-pixel border.
    const int nw = winW_ - 2;
    const int nh = winH_ - 2;
    normOfs_[0] = stride_ + 1;
    normOfs_[1] = stride_ + 1 + nw;
    normOfs_[2] = (1 + nh) * stride_ + 1;
    normOfs_[3] = (1 + nh) * stride_ + 1 + nw;
    normArea_ = static_cast<double>(nw) * nh;
    // Std dev <= 10 <=> nf <= (10 * area)^2: below 99.9% of that, surely flat (the exact float
    // test decides the rest).
    nfRejectBelow_ = static_cast<std::int64_t>(0.999 * (10.0 * normArea_) * (10.0 * normArea_));
}

FixedFeature FixedCascade::fixFeature(const HaarFeature& f) const
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
        out.ofs[i][0] = r.y * stride_ + r.x;
        out.ofs[i][1] = r.y * stride_ + r.x + r.width;
        out.ofs[i][2] = (r.y + r.height) * stride_ + r.x;
        out.ofs[i][3] = (r.y + r.height) * stride_ + r.x + r.width;
    }
    return out;
}

RowFeature FixedCascade::rowFeature(const HaarFeature& f) const
{
    RowFeature out{};
    out.twoRects = f.rectCount <= 2;
    const int half = (stride_ + 1) / 2;
    // Column c of the deinterleaved table: even columns first, odd ones from `half` on.
    auto split = [&](int r, int c) { return r * stride_ + (c & 1 ? half : 0) + (c >> 1); };
    // Deinterleaved 4 ways: column c in part c mod 4, each part `quarter` entries long, rows
    // 4 * quarter entries apart (ScaledIntegrals::split4Stride()).
    const int quarter = (stride_ + 3) / 4;
    auto split4 = [&](int r, int c) { return r * 4 * quarter + (c & 3) * quarter + (c >> 2); };
    for (int i = 0; i < f.rectCount; ++i) {
        const HaarRect& r = f.rects[static_cast<std::size_t>(i)];
        out.weight[i] = static_cast<std::int32_t>(r.weight);
        const int xs[4] = {r.x, r.x + r.width, r.x, r.x + r.width};
        const int ys[4] = {r.y, r.y, r.y + r.height, r.y + r.height};
        for (int k = 0; k < 4; ++k) {
            out.plain[i][k] = ys[k] * stride_ + xs[k];
            out.split[i][k] = split(ys[k], xs[k]);
            out.split4[i][k] = split4(ys[k], xs[k]);
        }
    }
    return out;
}

// Every feature in fixed point; true when all of them are exact in float (the row form).
bool FixedCascade::fixFeatures(const HaarCascade& cascade, std::vector<FixedFeature>& out) const
{
    out.reserve(cascade.features.size());
    bool floatExact = true;
    for (const HaarFeature& f : cascade.features) {
        out.push_back(fixFeature(f));
        // |f * K| must fit: K <= 2^48 / (10 * area) for windows that are not flat.
        double bound = 0.0;
        for (int i = 0; i < f.rectCount; ++i) {
            const HaarRect& r = f.rects[static_cast<std::size_t>(i)];
            bound += std::fabs(r.weight) * r.width * r.height * 255.0;
        }
        if (bound * std::ldexp(1.0, kNormShift) / (10.0 * normArea_) > std::ldexp(1.0, 62)) {
            throw std::runtime_error("face detector: feature range too large for fixed point");
        }
        // The row form converts feature sums to float: exact below 2^24.
        floatExact = floatExact && bound < 16777216.0;
    }
    return floatExact;
}

// The stages and, for a stump cascade, the stumps: per stage the most decisive first, so the
// early exits come sooner.
void FixedCascade::buildStages(const HaarCascade& cascade,
                               const std::vector<FixedFeature>& features)
{
    for (const HaarStage& s : cascade.stages) {
        FixedStage st{};
        st.threshold = leafFixed(static_cast<double>(s.threshold - kStageThresholdEps));
        st.first = stumps_ ? static_cast<int>(stumpList_.size()) : s.firstWeak;
        st.count = s.weakCount;
        for (int i = 0; i < s.weakCount && stumps_; ++i) {
            const HaarWeakClassifier& w = cascade.weak[static_cast<std::size_t>(s.firstWeak + i)];
            const HaarNode& n = cascade.nodes[static_cast<std::size_t>(w.firstNode)];
            // A stump's children are leaves: left 0 -> leaf 0, right -1 -> leaf 1.
            const float leftLeaf = cascade.leaves[static_cast<std::size_t>(w.firstLeaf - n.left)];
            const float rightLeaf = cascade.leaves[static_cast<std::size_t>(w.firstLeaf - n.right)];
            stumpList_.push_back({features[static_cast<std::size_t>(n.featureIndex)],
                                  nodeThreshold(n.threshold), leafFixed(leftLeaf),
                                  leafFixed(rightLeaf), 0, 0, n.featureIndex, n.threshold});
        }
        if (stumps_) {
            const auto first = stumpList_.begin() + st.first;
            std::stable_sort(first, stumpList_.end(), [](const FixedStump& a, const FixedStump& b) {
                return std::abs(a.left - a.right) > std::abs(b.left - b.right);
            });
            setRest(
                first, stumpList_.end(),
                [](const FixedStump& t) { return std::max(t.left, t.right); },
                [](const FixedStump& t) { return std::min(t.left, t.right); });
        }
        stages_.push_back(st);
    }
}

// A tree cascade's nodes, leaves and trees, and whether every tree has the two-node shape.
void FixedCascade::buildTrees(const HaarCascade& cascade, const std::vector<FixedFeature>& features)
{
    twoNodeTrees_ = true;
    for (const HaarWeakClassifier& w : cascade.weak) {
        if (w.nodeCount != 2) {
            twoNodeTrees_ = false;
            break;
        }
        const HaarNode& n0 = cascade.nodes[static_cast<std::size_t>(w.firstNode)];
        const HaarNode& n1 = cascade.nodes[static_cast<std::size_t>(w.firstNode + 1)];
        if ((n0.left > 0) == (n0.right > 0) || n1.left > 0 || n1.right > 0)
            twoNodeTrees_ = false;
    }
    for (const HaarNode& n : cascade.nodes) {
        nodes_.push_back({features[static_cast<std::size_t>(n.featureIndex)],
                          nodeThreshold(n.threshold), n.left, n.right, n.featureIndex,
                          n.threshold});
    }
    for (const float leaf : cascade.leaves)
        leaves_.push_back(leafFixed(leaf));
    for (const HaarWeakClassifier& w : cascade.weak)
        trees_.push_back({w.firstNode, w.firstLeaf, 0, 0});
}

// Per stage: the trees with the widest leaf range first (exact in any order: integer sums), then
// what the remaining trees can still add, for the early exits.
void FixedCascade::sortTrees(const HaarCascade& cascade)
{
    auto spread = [&](const FixedTree& w, bool high) {
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
            const std::int64_t v = leaves_[static_cast<std::size_t>(w.firstLeaf + l)];
            hi = std::max(hi, v);
            lo = std::min(lo, v);
        }
        return high ? hi : lo;
    };
    for (const FixedStage& st : stages_) {
        const auto first = trees_.begin() + st.first;
        const auto last = first + st.count;
        std::stable_sort(first, last, [&](const FixedTree& a, const FixedTree& b) {
            return spread(a, true) - spread(a, false) > spread(b, true) - spread(b, false);
        });
        setRest(
            first, last, [&](const FixedTree& w) { return spread(w, true); },
            [&](const FixedTree& w) { return spread(w, false); });
    }
}

// The weak classifiers again in the row form, in the same (sorted) order.
void FixedCascade::buildRowForm(const HaarCascade& cascade)
{
    auto rowFeatureOf = [&](int featureIndex) {
        return rowFeature(cascade.features[static_cast<std::size_t>(featureIndex)]);
    };
    if (stumps_) {
        for (const FixedStump& st : stumpList_) {
            rowStumps_.push_back({rowFeatureOf(st.featureIndex), st.fileThreshold, rowLeaf(st.left),
                                  rowLeaf(st.right)});
        }
        rowForm_ = true;
        return;
    }
    for (const FixedTree& w : trees_) {
        const FixedNode& n0 = nodes_[static_cast<std::size_t>(w.firstNode)];
        const FixedNode& n1 = nodes_[static_cast<std::size_t>(w.firstNode + 1)];
        auto leaf = [&](int child) {
            return rowLeaf(leaves_[static_cast<std::size_t>(w.firstLeaf - child)]);
        };
        RowTree t{};
        t.feature0 = rowFeatureOf(n0.featureIndex);
        t.feature1 = rowFeatureOf(n1.featureIndex);
        t.threshold0 = n0.fileThreshold;
        t.threshold1 = n1.fileThreshold;
        t.node1OnBelow = n0.left > 0;
        t.direct = leaf(n0.left > 0 ? n0.right : n0.left);
        t.below1 = leaf(n1.left);
        t.above1 = leaf(n1.right);
        rowTrees_.push_back(t);
    }
    rowForm_ = true;
}

float FixedCascade::windowNorm(const std::int32_t* p, const std::uint32_t* q) const noexcept
{
    const std::int32_t valsum = rectSum(p, normOfs_);
    const std::uint32_t valsq = q[normOfs_[0]] - q[normOfs_[1]] - q[normOfs_[2]] + q[normOfs_[3]];
    const std::int64_t nfi =
        static_cast<std::int64_t>(normArea_) * valsq - static_cast<std::int64_t>(valsum) * valsum;
    if (nfi < nfRejectBelow_)
        return 0.0f;
    // As OpenCV: vnf = float(1 / sqrt(nf)); flat when area * vnf >= 0.1.
    const float vnf = static_cast<float>(1.0 / std::sqrt(static_cast<double>(nfi)));
    if (!(normArea_ * static_cast<double>(vnf) < 1e-1))
        return 0.0f;
    return vnf;
}

// The inverse of OpenCV's runAt.
int FixedCascade::evaluate(const std::int32_t* p, const std::uint32_t* q, int firstStage,
                           int endStage) const noexcept
{
    const int nstages = static_cast<int>(stages_.size());
    const int end = endStage >= 0 && endStage < nstages ? endStage : nstages;
    const float vnf = windowNorm(p, q);
    if (vnf == 0.0f)
        return -1;
    // vnf is a float >= 2^-25 here: vnf * 2^48 is an integer (exponent arithmetic only).
    const auto k = static_cast<std::int64_t>(static_cast<double>(vnf) * kNormScale);
    return stumps_ ? evaluateStumps(p, k, firstStage, end) : evaluateTrees(p, k, firstStage, end);
}

int FixedCascade::evaluateStumps(const std::int32_t* p, std::int64_t k, int firstStage,
                                 int endStage) const noexcept
{
    const int nstages = static_cast<int>(stages_.size());
    const FixedStump* s =
        stumpList_.data() +
        (firstStage < nstages ? stages_[static_cast<std::size_t>(firstStage)].first : 0);
    for (int si = firstStage; si < endStage; ++si) {
        const FixedStage& st = stages_[static_cast<std::size_t>(si)];
        std::int64_t acc = 0;
        const FixedStump* end = s + st.count;
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

int FixedCascade::evaluateTrees(const std::int32_t* p, std::int64_t k, int firstStage,
                                int endStage) const noexcept
{
    for (int si = firstStage; si < endStage; ++si) {
        const FixedStage& st = stages_[static_cast<std::size_t>(si)];
        std::int64_t acc = 0;
        for (int i = 0; i < st.count; ++i) {
            const FixedTree& w = trees_[static_cast<std::size_t>(st.first + i)];
            const FixedNode* tree = nodes_.data() + w.firstNode;
            int leaf = 0;
            if (twoNodeTrees_) {
                // Node 0 leads to a leaf or to node 1: evaluate both, pick without branches.
                const int b0 =
                    -static_cast<int>(featureValue(tree[0].feature, p) * k < tree[0].threshold);
                const int b1 =
                    -static_cast<int>(featureValue(tree[1].feature, p) * k < tree[1].threshold);
                const int i0 = tree[0].right + ((tree[0].left - tree[0].right) & b0);
                const int i1 = tree[1].right + ((tree[1].left - tree[1].right) & b1);
                leaf = i0 > 0 ? i1 : i0;
            } else {
                do {
                    const FixedNode& n = tree[leaf];
                    const int below =
                        -static_cast<int>(featureValue(n.feature, p) * k < n.threshold);
                    leaf = n.right + ((n.left - n.right) & below);
                } while (leaf > 0);
            }
            acc += leaves_[static_cast<std::size_t>(w.firstLeaf - leaf)];
            if (acc + w.restMax < st.threshold)
                return -si;
            if (acc + w.restMin >= st.threshold)
                break;
        }
    }
    return 1;
}

}  // namespace vision
