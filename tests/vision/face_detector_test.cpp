// FaceDetector on synthetic images: integral tables against brute force, window decisions of
// the fixed-point cascade against a float reference written like OpenCV's, the row prefilter
// against the exact path, the grouping, and the scan modes (full, masked with exclusions,
// incremental under a window budget, first hit) without heap allocation per frame. The parts of
// the detector are reached through their private headers (vision/src).
#include "vision/face_detector.hpp"

#include "alloc_counter.hpp"
#include "detection_grouping.hpp"
#include "fixed_cascade.hpp"
#include "row_prefilter.hpp"
#include "scaled_integrals.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/integral_image.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <random>
#include <span>
#include <stdexcept>
#include <vector>

using namespace vision;

namespace {

const char* const kDefault = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";
const char* const kAlt2 = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_alt2.xml";

// One stage, one stump on a 6x6 window: left half minus right half (whole -1, left 2), value
// (normalised) below 0.05 -> leaf -1, else +1; the stage needs 0.5. So windows with a bright left
// half pass.
const char* const kEdgeCascade = R"(<?xml version="1.0"?>
<opencv_storage>
<cascade type_id="opencv-cascade-classifier"><stageType>BOOST</stageType>
  <featureType>HAAR</featureType>
  <height>6</height>
  <width>6</width>
  <stages>
    <_>
      <maxWeakCount>1</maxWeakCount>
      <stageThreshold>0.5</stageThreshold>
      <weakClassifiers>
        <_>
          <internalNodes>0 -1 0 0.05</internalNodes>
          <leafValues>-1. 1.</leafValues></_></weakClassifiers></_></stages>
  <features>
    <_>
      <rects>
        <_>0 0 6 6 -1.</_>
        <_>0 0 3 6 2.</_></rects></_></features></cascade>
</opencv_storage>
)";

struct Gray {
    int width, height;
    std::vector<std::uint8_t> pixels;
    Gray(int w, int h, std::uint8_t v = 0)
        : width(w), height(h), pixels(static_cast<std::size_t>(w * h), v)
    {
    }
    std::uint8_t& at(int x, int y) { return pixels[static_cast<std::size_t>(y * width + x)]; }
    std::uint8_t at(int x, int y) const { return pixels[static_cast<std::size_t>(y * width + x)]; }
    ConstImageView view() const
    {
        return {pixels.data(), width, height, width, PixelFormat::Gray8};
    }
};

// A blocky random image: textures rich enough that windows go past the first stages.
Gray randomImage(int w, int h, unsigned seed)
{
    Gray g(w, h);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> v(0, 255);
    std::vector<int> blocks(static_cast<std::size_t>((w / 4 + 1) * (h / 4 + 1)));
    for (int& b : blocks)
        b = v(rng);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int b = blocks[static_cast<std::size_t>((y / 4) * (w / 4 + 1) + x / 4)];
            g.at(x, y) = static_cast<std::uint8_t>(std::clamp(b + v(rng) / 8 - 16, 0, 255));
        }
    }
    return g;
}

// OpenCV's evaluation (cascadedetect.cpp) in float and double, on brute-force integrals.
int referenceEvaluate(const HaarCascade& c, const Gray& g, int x0, int y0)
{
    auto rectSum = [&](int x, int y, int w, int h) {
        long long s = 0;
        for (int yy = y0 + y; yy < y0 + y + h; ++yy) {
            for (int xx = x0 + x; xx < x0 + x + w; ++xx)
                s += g.at(xx, yy);
        }
        return s;
    };
    auto rectSq = [&](int x, int y, int w, int h) {
        long long s = 0;
        for (int yy = y0 + y; yy < y0 + y + h; ++yy) {
            for (int xx = x0 + x; xx < x0 + x + w; ++xx) {
                const long long v = g.at(xx, yy);
                s += v * v;
            }
        }
        return s;
    };
    const int nw = c.windowWidth - 2;
    const int nh = c.windowHeight - 2;
    const double area = double(nw) * nh;
    const double nf = area * double(rectSq(1, 1, nw, nh)) -
                      double(rectSum(1, 1, nw, nh)) * double(rectSum(1, 1, nw, nh));
    if (!(nf > 0))
        return -1;
    const float vnf = float(1.0 / std::sqrt(nf));
    if (!(area * vnf < 0.1))
        return -1;
    auto feature = [&](int fi) {
        const HaarFeature& f = c.features[static_cast<std::size_t>(fi)];
        float r = 0.0f;
        for (int i = 0; i < f.rectCount; ++i) {
            const HaarRect& hr = f.rects[static_cast<std::size_t>(i)];
            r += hr.weight * float(rectSum(hr.x, hr.y, hr.width, hr.height));
        }
        return r * vnf;
    };
    for (std::size_t si = 0; si < c.stages.size(); ++si) {
        const HaarStage& st = c.stages[si];
        double sum = 0;
        for (int i = 0; i < st.weakCount; ++i) {
            const HaarWeakClassifier& w = c.weak[static_cast<std::size_t>(st.firstWeak + i)];
            int idx = 0;
            do {
                const HaarNode& n = c.nodes[static_cast<std::size_t>(w.firstNode + idx)];
                idx = double(feature(n.featureIndex)) < n.threshold ? n.left : n.right;
            } while (idx > 0);
            sum += c.leaves[static_cast<std::size_t>(w.firstLeaf - idx)];
        }
        if (sum < st.threshold - 1e-5f)
            return -static_cast<int>(si);
    }
    return 1;
}

std::vector<Rect> copyOf(std::span<const Rect> r)
{
    return {r.begin(), r.end()};
}

FaceDetectorOptions smallOptions(int minNeighbors)
{
    FaceDetectorOptions o;
    o.maxFrameSize = {64, 48};
    o.scaleFactor = 1.25;
    o.minNeighbors = minNeighbors;
    return o;
}

// A 64x48 image with one left-bright/right-dark square (the edge cascade fires around it).
Gray edgeImage()
{
    Gray g(64, 48, 100);
    for (int y = 20; y < 32; ++y) {
        for (int x = 30; x < 42; ++x)
            g.at(x, y) = x < 36 ? 230 : 20;
    }
    return g;
}

// One window at scale 1 of an image, decided as the scans decide it.
struct WindowEvaluator {
    FixedCascade cascade;
    ScaledIntegrals tables;

    WindowEvaluator(const HaarCascade& c, Size maxFrameSize)
        : cascade(c, maxFrameSize.width + 1, false), tables(maxFrameSize, false)
    {
    }
    // 1 when it passes, -s when stage s rejects it, -1 also when it is flat or outside.
    int operator()(const Gray& g, int x, int y)
    {
        if (x < 0 || y < 0 || x + cascade.windowWidth() > g.width ||
            y + cascade.windowHeight() > g.height)
            return -1;
        tables.prepare(g.view(), g.width, g.height, false);
        const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(y) * tables.stride() + x;
        return cascade.evaluate(tables.sum() + at, tables.squaredSum() + at);
    }
};

TEST(FaceDetector, IntegralTablesMatchBruteForce)
{
    ScaledIntegrals t({64, 48}, false);
    const Gray g = randomImage(61, 47, 7);
    t.prepare(g.view(), g.width, g.height, false);
    const int stride = t.stride();
    for (int y = 0; y <= g.height; y += 3) {
        for (int x = 0; x <= g.width; x += 2) {
            long long s = 0;
            unsigned long long q = 0;
            for (int yy = 0; yy < y; ++yy) {
                for (int xx = 0; xx < x; ++xx) {
                    const unsigned v = g.at(xx, yy);
                    s += v;
                    q += v * v;
                }
            }
            ASSERT_EQ(t.sum()[y * stride + x], s) << x << "," << y;
            ASSERT_EQ(t.squaredSum()[y * stride + x], static_cast<std::uint32_t>(q));
        }
    }
}

TEST(FaceDetector, IntegralTablesOfABandGiveTheWholeTablesWindowSums)
{
    // The scan prepares only the rows of the windows it evaluates, counting from the band's
    // first row: every rectangle within the band sums as in the whole tables (plain, squared
    // and column-split), for a copy and a shrunk scale.
    const Gray g = randomImage(61, 47, 11);
    for (const Size scaled : {Size{61, 47}, Size{50, 39}}) {
        ScaledIntegrals whole({64, 48}, true);
        ScaledIntegrals band({64, 48}, true);
        whole.prepare(g.view(), scaled.width, scaled.height, true);
        band.begin(g.view(), scaled.width, scaled.height, true);
        band.prepareRows(9, 20);
        band.prepareRows(11, 30);  // extends the band
        const int stride = whole.stride();
        const int half = (stride + 1) / 2;
        const auto split = [&](const ScaledIntegrals& t, int x, int y) {
            return t.splitSum()[y * stride + (x & 1 ? half : 0) + (x >> 1)];
        };
        for (int y0 = 9; y0 <= 30; y0 += 3) {
            for (int y1 = y0; y1 <= 30; y1 += 4) {
                for (int x0 = 0; x0 <= scaled.width; x0 += 5) {
                    for (int x1 = x0; x1 <= scaled.width; x1 += 7) {
                        const auto rect = [&](auto at) {
                            return static_cast<std::uint32_t>(at(x1, y1)) -
                                   static_cast<std::uint32_t>(at(x0, y1)) -
                                   static_cast<std::uint32_t>(at(x1, y0)) +
                                   static_cast<std::uint32_t>(at(x0, y0));
                        };
                        const auto of = [&](const ScaledIntegrals& t) {
                            return std::array<std::uint32_t, 3>{
                                rect([&](int x, int y) { return t.sum()[y * stride + x]; }),
                                rect([&](int x, int y) { return t.squaredSum()[y * stride + x]; }),
                                rect([&](int x, int y) { return split(t, x, y); })};
                        };
                        ASSERT_EQ(of(whole), of(band)) << x0 << "," << y0 << " " << x1 << "," << y1;
                    }
                }
            }
        }
    }
}

TEST(FaceDetector, TheTableSplitFourWaysHoldsTheSumTablesEntries)
{
    // Every entry of the sum table at its place in the table deinterleaved 4 ways (columns of
    // x mod 4 = m from m * quarter on), for shrunk widths of every residue mod 4, whole and by
    // a band of rows; and the 2-way table alongside.
    const Gray g = randomImage(61, 47, 13);
    for (const Size scaled : {Size{61, 47}, Size{60, 40}, Size{59, 39}, Size{58, 38}}) {
        for (const bool band : {false, true}) {
            ScaledIntegrals t({64, 48}, true);
            t.begin(g.view(), scaled.width, scaled.height, true, true);
            const int top = band ? 7 : 0;
            t.prepareRows(top, scaled.height);
            const int stride = t.stride();
            const int quarter = (stride + 3) / 4;
            ASSERT_EQ(t.split4Stride(), 4 * quarter);
            ASSERT_GE(t.split4Stride(), stride);
            const int half = (stride + 1) / 2;
            for (int y = top; y <= scaled.height; ++y) {
                for (int x = 0; x <= scaled.width; ++x) {
                    const std::int32_t plain = t.sum()[y * stride + x];
                    EXPECT_EQ(t.split4Sum()[y * t.split4Stride() + (x & 3) * quarter + (x >> 2)],
                              plain)
                        << scaled.width << " at " << x << "," << y;
                    EXPECT_EQ(t.splitSum()[y * stride + (x & 1 ? half : 0) + (x >> 1)], plain);
                }
            }
        }
    }
}

TEST(FaceDetector, IntegralTablesPastTwoToThe31AreExactModuloTwoToThe32)
{
    // A white 4096x2304 frame sums to 2.4e9 > 2^31: the tables wrap (in unsigned arithmetic,
    // UBSan proves it), and a window's sum taken from them is still exact.
    const int w = 4096;
    const int h = 2304;
    ScaledIntegrals t({w, h}, false);
    const Gray g(w, h, 255);
    t.prepare(g.view(), w, h, false);
    const int stride = t.stride();
    const auto corner = [&](int x, int y) {
        return static_cast<std::uint32_t>(t.sum()[static_cast<std::ptrdiff_t>(y) * stride + x]);
    };
    EXPECT_EQ(corner(w, h), static_cast<std::uint32_t>(255ull * w * h));
    // The last 24x24 window: 576 pixels of 255.
    const std::uint32_t window =
        corner(w, h) - corner(w - 24, h) - corner(w, h - 24) + corner(w - 24, h - 24);
    EXPECT_EQ(window, 255u * 576u);
}

TEST(FaceDetector, EdgeCascadeWindowDecisions)
{
    WindowEvaluator evaluate(parseHaarCascade(kEdgeCascade, "edge"), {64, 48});
    Gray g(12, 6, 0);
    for (int y = 0; y < 6; ++y) {
        for (int x = 0; x < 12; ++x)
            g.at(x, y) = x < 3 ? 200 : (x < 6 ? 50 : 120);
    }
    EXPECT_EQ(evaluate(g, 0, 0), 1);   // bright left half: passes
    EXPECT_EQ(evaluate(g, 3, 0), 0);   // dark | flat-ish grey: stage 0 rejects
    EXPECT_EQ(evaluate(g, 6, 0), -1);  // flat: rejected by the variance test
    EXPECT_EQ(evaluate(g, 7, 0), -1);  // outside the image
}

void compareWithReference(const char* path)
{
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "opencv-data not installed";
    const HaarCascade c = loadHaarCascade(path);
    WindowEvaluator evaluate(c, {64, 48});
    int compared = 0;
    int deep = 0;
    for (unsigned seed = 1; seed <= 3; ++seed) {
        const Gray g = randomImage(64, 48, seed);
        for (int y = 0; y + c.windowHeight <= g.height; y += 3) {
            for (int x = 0; x + c.windowWidth <= g.width; x += 3) {
                const int ours = evaluate(g, x, y);
                ASSERT_EQ(ours, referenceEvaluate(c, g, x, y)) << path << " " << x << "," << y;
                ++compared;
                deep += ours < -1 || ours == 1;
            }
        }
    }
    EXPECT_GT(compared, 300);
    EXPECT_GT(deep, 10);  // some windows got past the first stages
}

TEST(FaceDetector, WindowDecisionsMatchFloatReferenceDefault)
{
    compareWithReference(kDefault);
}
TEST(FaceDetector, WindowDecisionsMatchFloatReferenceAlt2)
{
    compareWithReference(kAlt2);
}

// The row prefilter (first stages over a whole row, float decisions), then the exact path from
// where it stopped, must decide every window as the exact path alone does. Every row of `g` at
// scale 1 with `step` (the split table for step 2), from window j0 on; `c` built for tables of
// maxFrameSize.
struct PrefilterCount {
    long passed = 0;  // windows that pass the cascade
    long parked = 0;  // windows the prefilter left to the exact path at an undecidable sum
};

// With `masked`, each row wants only some windows (a masked scan's): runs of wanted and unwanted
// windows of varying length, the row's ends unwanted too; only the wanted ones are compared.
PrefilterCount comparePrefilterRows(const FixedCascade& c, Size maxFrameSize, const Gray& g,
                                    int step, int j0, bool masked = false)
{
    ScaledIntegrals t(maxFrameSize, true);
    RowPrefilter prefilter(maxFrameSize.width + 1);
    t.prepare(g.view(), g.width, g.height, step == 2, step == 4);
    const int j1 = (g.width + 1 - c.windowWidth() + step - 1) / step;
    std::vector<std::uint8_t> wanted(static_cast<std::size_t>(maxFrameSize.width + 1), 1);
    PrefilterCount count;
    for (int y = 0; y + c.windowHeight() <= g.height; ++y) {
        if (masked)
            for (int j = 0; j < j1; ++j)
                wanted[static_cast<std::size_t>(j)] = ((j + y) / (3 + y % 5)) % 2 == 1 ? 1 : 0;
        const int done =
            prefilter.run(c, t, y, step, j0, j1, masked ? wanted.data() : nullptr);
        for (int j = j0; j < j1; ++j) {
            if (wanted[static_cast<std::size_t>(j)] == 0)
                continue;
            const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(y) * t.stride() + j * step;
            const int exact = c.evaluate(t.sum() + at, t.squaredSum() + at);
            const int pre = done > 0 ? prefilter.result(j) : 1;
            const int from = pre == 1 ? done : prefilter.from(j);
            const int ours = pre <= 0 ? pre : c.evaluate(t.sum() + at, t.squaredSum() + at, from);
            EXPECT_EQ(ours, exact) << g.width << " step " << step << " at " << j * step << "," << y;
            if (ours != exact)
                return count;
            count.passed += exact == 1;
            count.parked += pre == 2;
        }
    }
    return count;
}

void compareRowPrefilter(const char* path)
{
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "opencv-data not installed";
    const HaarCascade full = loadHaarCascade(path);
    long hits = 0;
    // Cut to its first stages, the cascade passes many windows of a random image: deep
    // decisions (prefiltered stages, then single windows) get compared too.
    for (const std::size_t stageCount : {std::size_t{4}, std::size_t{8}, full.stages.size()}) {
        HaarCascade c = full;
        c.stages.resize(stageCount);
        const Size maxFrameSize{160, 120};
        const FixedCascade cascade(c, maxFrameSize.width + 1, true);
        ASSERT_TRUE(cascade.rowForm());
        // An even and an odd size (the deinterleaved table's last column), the steps 1 and 2
        // and 4 (a coarse scan's windows at a step-2 scale), and a row taken up after its
        // first windows (an incremental scan resuming).
        const Gray images[] = {randomImage(160, 120, 11), randomImage(131, 97, 12)};
        for (const Gray& g : images) {
            for (const int step : {1, 2, 4})
                hits += comparePrefilterRows(cascade, maxFrameSize, g, step, 0).passed;
            hits += comparePrefilterRows(cascade, maxFrameSize, g, 2, 5).passed;
            for (const int step : {1, 2, 4})
                hits += comparePrefilterRows(cascade, maxFrameSize, g, step, 0, true).passed;
        }
    }
    EXPECT_GT(hits, 100);
    std::printf("[ info ] %s: %ld passing windows compared\n", path, hits);
}

TEST(FaceDetector, RowPrefilterDecidesLikeSingleWindowsDefault)
{
    compareRowPrefilter(kDefault);
}
TEST(FaceDetector, RowPrefilterDecidesLikeSingleWindowsAlt2)
{
    compareRowPrefilter(kAlt2);
}

TEST(FaceDetector, RowPrefilterLeavesStageSumsOnTheThresholdToTheExactPath)
{
    // The passing leaf equals the stage threshold (as lowered by 1e-5): the exact sum is not
    // below it, so those windows pass; the prefilter's Q20 sum cannot tell and must defer.
    HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    c.stages[0].threshold = 0.3f;
    c.leaves[static_cast<std::size_t>(c.weak[0].firstLeaf + 1)] = 0.3f - 1e-5f;
    const Size maxFrameSize{64, 48};
    const FixedCascade cascade(c, maxFrameSize.width + 1, true);
    ASSERT_TRUE(cascade.rowForm());
    for (const int step : {1, 2}) {
        const PrefilterCount n = comparePrefilterRows(cascade, maxFrameSize, edgeImage(), step, 0);
        EXPECT_GT(n.passed, 3);
        EXPECT_EQ(n.parked, n.passed) << step;
    }
}

TEST(FaceDetector, AStageLimitDecidesTheStagesBeforeIt)
{
    // evaluate(.., first, end) and the prefilter's run(.., end): a window rejected before the
    // limit as without it, one that passes the stages before it passes (1).
    if (!std::filesystem::exists(kDefault))
        GTEST_SKIP() << "opencv-data not installed";
    const HaarCascade c = loadHaarCascade(kDefault);
    const Size maxFrameSize{160, 120};
    const FixedCascade cascade(c, maxFrameSize.width + 1, true);
    ScaledIntegrals t(maxFrameSize, true);
    RowPrefilter prefilter(maxFrameSize.width + 1);
    const Gray g = randomImage(160, 120, 21);
    t.prepare(g.view(), g.width, g.height, true);
    const int j1 = (g.width + 1 - cascade.windowWidth() + 1) / 2;
    long limited = 0, beyond = 0;
    for (const int end : {1, 3, 6}) {
        for (int y = 0; y + cascade.windowHeight() <= g.height; ++y) {
            const int done = prefilter.run(cascade, t, y, 2, 0, j1, nullptr, end);
            EXPECT_LE(done, end);
            for (int j = 0; j < j1; ++j) {
                const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(y) * t.stride() + 2 * j;
                const int full = cascade.evaluate(t.sum() + at, t.squaredSum() + at);
                const int expected = full == 1 || full <= -end ? 1 : full;
                EXPECT_EQ(cascade.evaluate(t.sum() + at, t.squaredSum() + at, 0, end), expected);
                const int pre = done > 0 ? prefilter.result(j) : 1;
                const int from = pre == 1 ? done : prefilter.from(j);
                const int ours =
                    pre <= 0 ? pre
                             : cascade.evaluate(t.sum() + at, t.squaredSum() + at, from, end);
                EXPECT_EQ(ours, expected) << end << " at " << 2 * j << "," << y;
                limited += expected == 1;
                beyond += expected == 1 && full != 1;
            }
        }
    }
    EXPECT_GT(beyond, 100);  // windows the limit lets through that the cascade rejects later
    std::printf("[ info ] %ld windows passed the limited stages, %ld of them rejected later\n",
                limited, beyond);
}

// A coarse-to-fine scan's raw hits are among the full scan's, in its order (by scale, row,
// window); `full` and `coarse` the raw hits of the two scans.
void expectHitsOfTheFullScan(std::span<const Rect> full, std::span<const Rect> coarse)
{
    auto from = full.begin();
    for (const Rect& r : coarse) {
        const auto it = std::find(from, full.end(), r);
        ASSERT_NE(it, full.end()) << (std::find(full.begin(), full.end(), r) == full.end()
                                          ? "not a hit of the full scan: "
                                          : "out of order: ")
                                  << r.x << "," << r.y << " " << r.width;
        from = it + 1;
    }
}

TEST(FaceDetector, CoarseToFineFindsTheFullScansFaces)
{
    const HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    const Gray g = edgeImage();
    FaceDetector full(c, smallOptions(1));
    FaceDetector coarse(c, smallOptions(1));
    full.detect(g.view());
    ASSERT_GE(coarse.detectCoarseToFine(g.view(), nullptr, 0.f, {}), 1);
    EXPECT_EQ(copyOf(coarse.faces()), copyOf(full.faces()));
    EXPECT_LT(coarse.windowsEvaluated(), full.windowsEvaluated());
    for (const Rect& r : coarse.rawHits()) {
        EXPECT_LT(r.x, 36);
        EXPECT_GT(r.x + r.width, 36);
    }
}

TEST(FaceDetector, CoarseToFineOnARealCascadeGivesHitsOfTheFullScanInItsOrder)
{
    // The default cascade cut to 8 stages passes many windows of a textured image, deep past
    // the coarse grid's 6 stages. The coarse scan's hits are among the full scan's (it skips
    // the windows OpenCV's scan skips after a first-stage rejection), in its order. (Random texture is not a face: its hits do not cluster
    // as a face's do, so how many the coarse scan keeps says nothing of faces; the cold-start
    // tests of the tracker and mirror-eval track measure that, docs/ARM.md.)
    if (!std::filesystem::exists(kDefault))
        GTEST_SKIP() << "opencv-data not installed";
    HaarCascade c = loadHaarCascade(kDefault);
    c.stages.resize(8);
    FaceDetectorOptions o;
    o.maxFrameSize = {160, 120};
    o.minNeighbors = 0;
    o.maxRawHits = 100000;
    o.maxFaces = 100000;
    FaceDetector full(c, o);
    FaceDetector coarse(c, o);
    long fullHits = 0, coarseHits = 0;
    for (const unsigned seed : {31u, 32u, 33u}) {
        const Gray g = randomImage(160, 120, seed);
        full.detect(g.view());
        ASSERT_GE(coarse.detectCoarseToFine(g.view(), nullptr, 0.f, {}), 0);
        expectHitsOfTheFullScan(full.rawHits(), coarse.rawHits());
        fullHits += static_cast<long>(full.rawHits().size());
        coarseHits += static_cast<long>(coarse.rawHits().size());
    }
    EXPECT_GT(coarseHits, 50);
    std::printf("[ info ] raw hits: full scans %ld, coarse to fine %ld\n", fullHits, coarseHits);
}

TEST(FaceDetector, CoarseToFineSkipsUnmaskedAndExcludedWindows)
{
    const HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    Gray g(64, 48, 100);
    // Two edges: one on the left half (masked out), one on the right.
    for (int y = 16; y < 28; ++y) {
        for (int x = 8; x < 20; ++x)
            g.at(x, y) = x < 14 ? 230 : 20;
        for (int x = 40; x < 52; ++x)
            g.at(x, y) = x < 46 ? 230 : 20;
    }
    Gray right(32, 24, 0);
    for (int y = 0; y < 24; ++y) {
        for (int x = 16; x < 32; ++x)
            right.at(x, y) = 255;
    }
    IntegralImage mask(Size{32, 24});
    ASSERT_TRUE(mask.compute(right.view()));
    FaceDetector d(c, smallOptions(0));
    ASSERT_GT(d.detectCoarseToFine(g.view(), &mask, 0.9f, {}), 0);
    for (const Rect& r : d.rawHits())
        EXPECT_GE(r.x, 28) << r.x;
    const Rect exclude[] = {{0, 0, 64, 48}};
    EXPECT_EQ(d.detectCoarseToFine(g.view(), &mask, 0.9f, exclude), 0);
    EXPECT_EQ(d.windowsEvaluated(), 0);
}

TEST(FaceDetector, FullScanFindsTheEdgeAndGroupsIt)
{
    const HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    const Gray g = edgeImage();
    FaceDetector raw(c, smallOptions(0));
    const int n = raw.detect(g.view());
    ASSERT_GT(n, 3);
    for (const Rect& r : raw.rawHits()) {
        // Every hit straddles the edge at x = 36.
        EXPECT_LT(r.x, 36);
        EXPECT_GT(r.x + r.width, 36);
    }
    FaceDetector grouped(c, smallOptions(1));
    const int m = grouped.detect(g.view());
    ASSERT_GE(m, 1);
    EXPECT_LT(m, n);
}

TEST(FaceDetector, GroupRectanglesLikeOpenCv)
{
    DetectionGrouping d(16);
    const Rect in[] = {{10, 10, 20, 20}, {11, 10, 20, 20}, {10, 11, 21, 21}, {50, 50, 20, 20},
                       {90, 90, 10, 10}, {91, 90, 10, 10}, {90, 91, 10, 10}, {11, 11, 20, 20}};
    Rect out[8];
    const int n = d.group(in, 2, 0.2, out);
    ASSERT_EQ(n, 2);
    // Means rounded: (10+11+10+11)/4 = 10.5 -> 10 (to even), widths (20+20+21+20)/4 = 20.25.
    EXPECT_EQ(out[0], (Rect{10, 10, 20, 20}));
    EXPECT_EQ(out[1], (Rect{90, 90, 10, 10}));
    // A lone rectangle does not survive minNeighbors 2; with 0 everything is returned.
    EXPECT_EQ(d.group(in, 0, 0.2, out), 8);
}

TEST(FaceDetector, MaskedScanSkipsUnmaskedAndExcludedWindows)
{
    const HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    const Gray g = edgeImage();
    FaceDetector d(c, smallOptions(0));
    const int full = d.detect(g.view());
    const long fullWindows = d.windowsEvaluated();

    // Mask at half resolution: all set -> the same hits as the full scan.
    Gray mask(32, 24, 255);
    IntegralImage integral(Size{32, 24});
    ASSERT_TRUE(integral.compute(mask.view()));
    EXPECT_EQ(d.detectMasked(g.view(), integral, 0.5f, {}), full);
    EXPECT_EQ(d.windowsEvaluated(), fullWindows);

    // Empty mask: nothing evaluated.
    Gray none(32, 24, 0);
    ASSERT_TRUE(integral.compute(none.view()));
    EXPECT_EQ(d.detectMasked(g.view(), integral, 0.5f, {}), 0);
    EXPECT_EQ(d.windowsEvaluated(), 0);

    // Mask only the left half: windows there only; none of the hits (at x 30..41) survive.
    Gray left(32, 24, 0);
    for (int y = 0; y < 24; ++y) {
        for (int x = 0; x < 12; ++x)
            left.at(x, y) = 255;
    }
    ASSERT_TRUE(integral.compute(left.view()));
    EXPECT_EQ(d.detectMasked(g.view(), integral, 0.9f, {}), 0);
    EXPECT_GT(d.windowsEvaluated(), 0);
    EXPECT_LT(d.windowsEvaluated(), fullWindows / 2);

    // Full mask, the tracked face's box excluded: no hit has its centre there.
    ASSERT_TRUE(integral.compute(mask.view()));
    const Rect tracked[] = {{24, 14, 24, 24}};
    d.detectMasked(g.view(), integral, 0.5f, tracked);
    for (const Rect& r : d.rawHits()) {
        const int cx = r.x + r.width / 2;
        const int cy = r.y + r.height / 2;
        EXPECT_FALSE(cx >= 24 && cx < 48 && cy >= 14 && cy < 38);
    }
}

// Runs incremental calls on `g` until the scan completes; returns the number of calls and
// checks the per-call budget guarantee.
int scanIncrementally(FaceDetector& d, const Gray& g, const IntegralImage* mask, float minFraction,
                      std::span<const Rect> exclude, long budget, long& windows)
{
    windows = 0;
    for (int calls = 1; calls < 100000; ++calls) {
        const bool done = d.detectMaskedIncremental(g.view(), mask, minFraction, exclude, budget);
        EXPECT_LE(d.windowsEvaluated(), budget > 0 ? budget : windows + d.windowsEvaluated());
        windows += d.windowsEvaluated();
        if (done) {
            EXPECT_FALSE(d.incrementalScanActive());
            return calls;
        }
        EXPECT_TRUE(d.incrementalScanActive());
    }
    ADD_FAILURE() << "incremental scan never completed";
    return -1;
}

TEST(FaceDetector, IncrementalWithoutBudgetEqualsTheWholeScan)
{
    const HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    const Gray g = edgeImage();
    FaceDetector whole(c, smallOptions(1));
    FaceDetector inc(c, smallOptions(1));
    Gray left(32, 24, 0);
    for (int y = 0; y < 24; ++y) {
        for (int x = 0; x < 20; ++x)
            left.at(x, y) = 255;
    }
    IntegralImage mask(Size{32, 24});
    ASSERT_TRUE(mask.compute(left.view()));
    const Rect exclude[] = {{0, 0, 12, 12}};

    // No mask: detect().
    whole.detect(g.view());
    ASSERT_TRUE(inc.detectMaskedIncremental(g.view(), nullptr, 0.f, {}, 0));
    EXPECT_EQ(copyOf(inc.faces()), copyOf(whole.faces()));
    EXPECT_EQ(copyOf(inc.rawHits()), copyOf(whole.rawHits()));
    EXPECT_EQ(inc.windowsEvaluated(), whole.windowsEvaluated());
    ASSERT_FALSE(whole.faces().empty());

    // Mask and exclusion: detectMasked().
    whole.detectMasked(g.view(), mask, 0.3f, exclude);
    ASSERT_TRUE(inc.detectMaskedIncremental(g.view(), &mask, 0.3f, exclude, 0));
    EXPECT_EQ(copyOf(inc.faces()), copyOf(whole.faces()));
    EXPECT_EQ(copyOf(inc.rawHits()), copyOf(whole.rawHits()));
    EXPECT_EQ(inc.windowsEvaluated(), whole.windowsEvaluated());
}

TEST(FaceDetector, SmallBudgetCompletesOverSeveralCallsWithTheSameFaces)
{
    const HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    const Gray g = edgeImage();
    FaceDetector whole(c, smallOptions(1));
    whole.detect(g.view());
    const long fullWindows = whole.windowsEvaluated();
    ASSERT_GT(fullWindows, 500);
    for (const long budget : {1L, 7L, 100L, fullWindows - 1}) {
        FaceDetector inc(c, smallOptions(1));
        long windows = 0;
        const int calls = scanIncrementally(inc, g, nullptr, 0.f, {}, budget, windows);
        EXPECT_EQ(calls, static_cast<int>((fullWindows + budget - 1) / budget)) << budget;
        EXPECT_EQ(windows, fullWindows) << budget;
        EXPECT_EQ(copyOf(inc.faces()), copyOf(whole.faces())) << budget;
        EXPECT_EQ(copyOf(inc.rawHits()), copyOf(whole.rawHits())) << budget;
        // The next call starts a new scan with the same result.
        const int again = scanIncrementally(inc, g, nullptr, 0.f, {}, budget, windows);
        EXPECT_EQ(again, calls);
        EXPECT_EQ(copyOf(inc.faces()), copyOf(whole.faces()));
    }
}

TEST(FaceDetector, SmallBudgetOnARealCascadeGivesTheWholeScansHits)
{
    if (!std::filesystem::exists(kDefault))
        GTEST_SKIP() << "opencv-data not installed";
    FaceDetectorOptions o;
    o.maxFrameSize = {64, 48};
    o.minNeighbors = 0;
    const HaarCascade c = loadHaarCascade(kDefault);
    FaceDetector whole(c, o);
    FaceDetector inc(c, o);
    const Gray g = randomImage(64, 48, 2);
    Gray half(16, 12, 0);
    for (int y = 0; y < 12; ++y) {
        for (int x = 0; x < 9; ++x)
            half.at(x, y) = 255;
    }
    IntegralImage mask(Size{16, 12});
    ASSERT_TRUE(mask.compute(half.view()));
    whole.detectMasked(g.view(), mask, 0.5f, {});
    long windows = 0;
    const int calls = scanIncrementally(inc, g, &mask, 0.5f, {}, 50, windows);
    EXPECT_GT(calls, 3);
    EXPECT_EQ(windows, whole.windowsEvaluated());
    EXPECT_EQ(copyOf(inc.rawHits()), copyOf(whole.rawHits()));
    EXPECT_EQ(copyOf(inc.faces()), copyOf(whole.faces()));
}

TEST(FaceDetector, IncrementalScanRestartsOnResetSizeChangeAndWholeScans)
{
    const HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    const Gray g = edgeImage();
    FaceDetector d(c, smallOptions(1));
    d.detect(g.view());
    const std::vector<Rect> expected = copyOf(d.faces());
    const long fullWindows = d.windowsEvaluated();

    // Half a scan, then reset: the next scan starts from the beginning and takes every window.
    EXPECT_FALSE(d.detectMaskedIncremental(g.view(), nullptr, 0.f, {}, fullWindows / 2));
    d.resetIncremental();
    EXPECT_FALSE(d.incrementalScanActive());
    long windows = 0;
    scanIncrementally(d, g, nullptr, 0.f, {}, 64, windows);
    EXPECT_EQ(windows, fullWindows);
    EXPECT_EQ(copyOf(d.faces()), expected);

    // A whole scan in between abandons the incremental one.
    EXPECT_FALSE(d.detectMaskedIncremental(g.view(), nullptr, 0.f, {}, fullWindows / 2));
    d.detect(g.view());
    EXPECT_FALSE(d.incrementalScanActive());

    // Another image size starts a new scan.
    EXPECT_FALSE(d.detectMaskedIncremental(g.view(), nullptr, 0.f, {}, fullWindows / 2));
    Gray small(40, 30, 100);
    for (int y = 8; y < 20; ++y) {
        for (int x = 10; x < 22; ++x)
            small.at(x, y) = x < 16 ? 230 : 20;
    }
    FaceDetector ref(c, smallOptions(1));
    ref.detect(small.view());
    scanIncrementally(d, small, nullptr, 0.f, {}, 0, windows);
    EXPECT_EQ(windows, ref.windowsEvaluated());
    EXPECT_EQ(copyOf(d.faces()), copyOf(ref.faces()));

    // Bad image: false, error, scan abandoned.
    const Gray big(65, 48, 0);
    EXPECT_FALSE(d.detectMaskedIncremental(big.view(), nullptr, 0.f, {}, 10));
    EXPECT_STRNE(d.lastError(), "");
    EXPECT_FALSE(d.incrementalScanActive());
}

TEST(FaceDetector, FirstHitStopsAtTheFirstWindow)
{
    const HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    FaceDetector d(c, smallOptions(0));
    const Gray g = edgeImage();
    d.detect(g.view());
    const Rect first = d.rawHits()[0];
    Rect hit;
    ASSERT_TRUE(d.detectFirst(g.view(), hit));
    EXPECT_EQ(hit, first);
    EXPECT_LT(d.windowsEvaluated(), 1000);
    const Gray flat(64, 48, 90);
    EXPECT_FALSE(d.detectFirst(flat.view(), hit));
}

TEST(FaceDetector, RejectsWrongImagesAndUnsupportedCascades)
{
    FaceDetector d(parseHaarCascade(kEdgeCascade, "edge"), smallOptions(0));
    const Gray big(65, 48, 0);
    EXPECT_EQ(d.detect(big.view()), -1);
    EXPECT_STRNE(d.lastError(), "");
    HaarCascade c = parseHaarCascade(kEdgeCascade, "edge");
    c.features[0].rects[1].weight = 2.5f;
    EXPECT_THROW((void)FaceDetector(c, smallOptions(0)), std::runtime_error);
}

TEST(FaceDetector, NoHeapAllocationPerFrame)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting unavailable";
    if (!std::filesystem::exists(kDefault))
        GTEST_SKIP() << "opencv-data not installed";
    FaceDetectorOptions o;
    o.maxFrameSize = {64, 48};
    FaceDetector d(loadHaarCascade(kDefault), o);
    const Gray g = randomImage(64, 48, 3);
    IntegralImage integral(Size{64, 48});
    ASSERT_TRUE(integral.compute(g.view()));
    const Rect exclude[] = {{0, 0, 10, 10}};
    Rect hit;
    testing_support::AllocationScope scope;
    d.detect(g.view());
    d.detectMasked(g.view(), integral, 0.1f, exclude);
    d.detectFirst(g.view(), hit);
    d.detectCoarseToFine(g.view(), &integral, 0.1f, exclude);
    while (!d.detectMaskedIncremental(g.view(), &integral, 0.1f, exclude, 100)) {
    }
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}

}  // namespace
