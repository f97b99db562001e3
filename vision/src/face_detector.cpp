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
constexpr int kLeafShift = 40;  // Q of leaf values and stage thresholds
constexpr float kStageThresholdEps = 1e-5f;  // OpenCV's THRESHOLD_EPS
constexpr int kResizeShift = 8;              // INTER_LINEAR_EXACT weights for 8-bit images

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
};

struct TreeNode {
    FixedFeature feature;
    std::int64_t threshold;
    int left;
    int right;
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

    // Per-frame buffers, sized for maxFrameSize.
    std::vector<std::uint8_t> scaled;
    std::vector<std::int32_t> sum;
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

    // The inverse of OpenCV's runAt: 1 = pass, -s = rejected at stage s, -1 = flat window.
    int runAt(const std::int32_t* p, const std::uint32_t* q) const noexcept
    {
        const std::int32_t valsum = rectSum(p, normOfs);
        const std::uint32_t valsq = q[normOfs[0]] - q[normOfs[1]] - q[normOfs[2]] + q[normOfs[3]];
        const std::int64_t nfi = static_cast<std::int64_t>(normArea) * valsq -
                                 static_cast<std::int64_t>(valsum) * valsum;
        if (nfi < nfRejectBelow)
            return -1;
        // As OpenCV: vnf = float(1 / sqrt(nf)); flat when area * vnf >= 0.1.
        const float vnf = static_cast<float>(1.0 / std::sqrt(static_cast<double>(nfi)));
        if (!(normArea * static_cast<double>(vnf) < 1e-1))
            return -1;
        const auto k = static_cast<std::int64_t>(std::ldexp(static_cast<double>(vnf), kNormShift));

        const int nstages = static_cast<int>(stages.size());
        if (stumps) {
            const Stump* s = stumpList.data();
            for (int si = 0; si < nstages; ++si) {
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
        for (int si = 0; si < nstages; ++si) {
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
    void prepare(const ConstImageView& gray, int dw, int dh) noexcept
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
    }

    enum class Mode { Full, Masked, First };

    // The scan of cv::CascadeClassifier::detectMultiScaleNoGrouping. Returns true when `First`
    // found a hit (in raw[0]).
    bool scan(const ConstImageView& gray, Mode mode, const IntegralImage* mask, float minFraction,
              std::span<const Rect> exclude) noexcept
    {
        rawCount = 0;
        rawOverflow = false;
        windows = 0;
        const int imgW = gray.width;
        const int imgH = gray.height;
        const int maxW = options.maxSize.width > 0 ? options.maxSize.width : imgW;
        const int maxH = options.maxSize.height > 0 ? options.maxSize.height : imgH;
        if (imgW < winW || imgH < winH)
            return false;
        const Size maskSize = mask != nullptr ? mask->size() : Size{};
        int nstripes = 0;
        for (double factor = 1.0;; factor *= options.scaleFactor) {
            if (std::lrint(winW * factor) > imgW || std::lrint(winH * factor) > imgH)
                break;
            const auto sc = static_cast<float>(factor);
            const long ww = std::lrint(static_cast<float>(winW) * sc);
            const long wh = std::lrint(static_cast<float>(winH) * sc);
            if (ww > maxW || wh > maxH)
                break;
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
            if (nstripes == 0)
                nstripes = std::max((xEnd + 31) / 32, 1);
            const int stripe = std::max((rows / step + nstripes - 1) / nstripes, 1) * step;
            const int yEnd = std::min(nstripes * stripe, rows);
            if (xEnd == 0 || yEnd == 0)
                continue;
            prepare(gray, dw, dh);
            const int boxW = static_cast<int>(ww);
            const int boxH = static_cast<int>(wh);
            for (int y = 0; y < yEnd; y += step) {
                const std::int32_t* prow = sum.data() + static_cast<std::ptrdiff_t>(y) * stride;
                const std::uint32_t* qrow = sqsum.data() + static_cast<std::ptrdiff_t>(y) * stride;
                const int by = static_cast<int>(std::lrint(static_cast<float>(y) * sc));
                for (int x = 0; x < xEnd; x += step) {
                    const int bx = static_cast<int>(std::lrint(static_cast<float>(x) * sc));
                    if (mode == Mode::Masked) {
                        const int cx = bx + boxW / 2;
                        const int cy = by + boxH / 2;
                        bool excluded = false;
                        for (const Rect& e : exclude) {
                            if (cx >= e.x && cx < e.x + e.width && cy >= e.y &&
                                cy < e.y + e.height) {
                                excluded = true;
                                break;
                            }
                        }
                        if (excluded)
                            continue;
                        const int mx0 = bx * maskSize.width / imgW;
                        const int my0 = by * maskSize.height / imgH;
                        const int mx1 = ((bx + boxW) * maskSize.width + imgW - 1) / imgW;
                        const int my1 = ((by + boxH) * maskSize.height + imgH - 1) / imgH;
                        if (mask->maskFraction({mx0, my0, mx1 - mx0, my1 - my0}) < minFraction) {
                            continue;
                        }
                    }
                    ++windows;
                    const int result = runAt(prow + x, qrow + x);
                    if (result > 0) {
                        if (rawCount < static_cast<int>(raw.size())) {
                            raw[static_cast<std::size_t>(rawCount++)] = {bx, by, boxW, boxH};
                        } else {
                            rawOverflow = true;
                        }
                        if (mode == Mode::First)
                            return true;
                    }
                    if (result == 0)
                        x += step;  // OpenCV skips past a first-stage rejection
                }
            }
        }
        return false;
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
                                       leafFixed(rightLeaf), 0, 0});
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
                               nodeThreshold(n.threshold), n.left, n.right});
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
    d.scaled.assign(maxW * maxH, 0);
    d.sum.assign((maxW + 1) * (maxH + 1), 0);
    d.sqsum.assign((maxW + 1) * (maxH + 1), 0);
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
    d.scan(gray, Impl::Mode::Full, nullptr, 0.0f, {});
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
    d.scan(gray, Impl::Mode::Masked, &mask, minFraction, exclude);
    return d.finish(gray.size());
}

bool FaceDetector::detectFirst(const ConstImageView& gray, Rect& hit) noexcept
{
    Impl& d = *impl_;
    d.faceCount = 0;
    if (!d.checkImage(gray))
        return false;
    if (!d.scan(gray, Impl::Mode::First, nullptr, 0.0f, {}))
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
