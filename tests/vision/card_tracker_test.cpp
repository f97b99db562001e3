// The card tracker on a small deterministic sequence generated here: a perspective quad of a solid
// colour with mild noise over a textured background, moving (rest, slow and fast motion, rotation,
// perspective), an occluder strip passing over an edge, and the card leaving and coming back.

#include "vision/card_tracker.hpp"

#include "alloc_counter.hpp"
#include "vision/card_stage.hpp"
#include "vision/chromaticity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

using namespace vision;

namespace {

constexpr int kW = 320, kH = 240;
constexpr int kFrames = 150;
constexpr int kAbsentFrom = 100, kAbsentTo = 110;  // the card is out of view in [from, to)

std::uint32_t hash(std::uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

float noise(std::uint32_t a, std::uint32_t b)  // -1..1
{
    return float(hash(a * 0x9e3779b9u ^ hash(b)) & 0xffff) / 32767.5f - 1.f;
}

/// Smallest signed distance of (x, y) to the quad's edges (positive inside).
float edgeDistance(const Quad& q, float x, float y)
{
    float d = 1e9f;
    for (int i = 0; i < 4; ++i) {
        const Point2f a = q[i], b = q[(i + 1) % 4];
        const float len = std::hypot(b.x - a.x, b.y - a.y);
        d = std::fmin(d, ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x)) / len);
    }
    return d;
}

bool inside(const Quad& q, float x, float y)
{
    for (int i = 0; i < 4; ++i) {
        const Point2f a = q[i], b = q[(i + 1) % 4];
        if ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x) < 0)
            return false;
    }
    return true;
}

/// The card's true corners at frame f: rest for 10 frames, then a slow tour, a fast sweep,
/// rotation and a perspective tilt; frame 0 fills the centre (training).
Quad truthAt(int f)
{
    float cx = 160, cy = 120, hw = 70, hh = 48, rot = 0, tilt = 0;
    if (f >= 10) {
        const float t = float(f - 10);
        cx += 50.f * std::sin(t * 0.045f);
        cy += 25.f * std::sin(t * 0.07f);
        rot = 0.35f * std::sin(t * 0.05f);
        tilt = 0.12f * std::sin(t * 0.06f);
    }
    if (f >= 60 && f < 80)  // fast sweep: up to ~8 px per frame
        cx += 60.f * std::sin(float(f - 60) * 3.14159f / 20.f);
    const float dx[4] = {-hw, hw, hw, -hw}, dy[4] = {-hh, -hh, hh, hh};
    Quad q;
    for (int i = 0; i < 4; ++i) {
        const float persp = 1.f + (i == 0 || i == 3 ? -tilt : tilt);  // left side shorter
        const float x = dx[i], y = dy[i] * persp;
        q[i] = {cx + x * std::cos(rot) - y * std::sin(rot),
                cy + x * std::sin(rot) + y * std::cos(rot)};
    }
    return q;
}

bool occluderAt(int f, int& x0, int& x1)
{
    if (f < 30 || f >= 50)
        return false;
    x0 = 200 + 2 * (f - 30);  // a skin-coloured strip over the right edge
    x1 = x0 + 16;
    return true;
}

void renderQuad(int f, const Quad& q, bool present, ImageBuffer& img)
{
    int ox0 = 0, ox1 = 0;
    const bool occ = occluderAt(f, ox0, ox1);
    for (int y = 0; y < kH; ++y) {
        std::uint8_t* row = img.view().row(y);
        for (int x = 0; x < kW; ++x) {
            // Textured, mostly unsaturated background (wood/wall-like) with a few coloured blobs.
            const float tex = 30.f * std::sin(float(x) * 0.11f + 2.f * std::sin(float(y) * 0.05f)) +
                              12.f * noise(std::uint32_t(x / 3), std::uint32_t(y / 3));
            float bg[3] = {140.f + tex, 125.f + tex, 105.f + tex};
            if ((x / 40 + y / 40) % 5 == 0) {
                bg[0] = 90.f + tex;
                bg[1] = 140.f + tex;
                bg[2] = 80.f + tex;
            }
            float cover = 0.f;
            const float dist = present ? edgeDistance(q, float(x), float(y)) : -1e9f;
            if (dist >= 1.f) {
                cover = 1.f;
            } else if (dist > -1.f) {  // anti-aliased edge: 4x4 supersampling
                int n = 0;
                for (int sy = 0; sy < 4; ++sy)
                    for (int sx = 0; sx < 4; ++sx)
                        n += inside(q, float(x) - 0.375f + 0.25f * float(sx),
                                    float(y) - 0.375f + 0.25f * float(sy));
                cover = float(n) / 16.f;
            }
            const float card[3] = {30.f, 70.f, 190.f};
            float px[3];
            for (int c = 0; c < 3; ++c)
                px[c] = bg[c] + cover * (card[c] - bg[c]);
            if (occ && x >= ox0 && x < ox1) {
                px[0] = 205.f;
                px[1] = 150.f;
                px[2] = 125.f;
            }
            for (int c = 0; c < 3; ++c) {
                const float v =
                    px[c] + 4.f * noise(std::uint32_t(f * 7919 + c), std::uint32_t(y * kW + x));
                row[3 * x + c] = std::uint8_t(std::lround(std::fmin(255.f, std::fmax(0.f, v))));
            }
        }
    }
}

void render(int f, ImageBuffer& img)
{
    renderQuad(f, truthAt(f), f < kAbsentFrom || f >= kAbsentTo, img);
}

/// Corner error with the best cyclic correspondence (the tracker names the top-left corner by
/// x + y, the generator by construction).
float maxCornerError(const Quad& a, const Quad& b, float* mean)
{
    float best = 1e9f, bestMean = 1e9f;
    for (int s = 0; s < 4; ++s) {
        float worst = 0.f, sum = 0.f;
        for (int i = 0; i < 4; ++i) {
            const float e = std::hypot(a[(i + s) % 4].x - b[i].x, a[(i + s) % 4].y - b[i].y);
            worst = std::fmax(worst, e);
            sum += e;
        }
        if (sum < bestMean * 4.f) {
            bestMean = sum / 4.f;
            best = worst;
        }
    }
    *mean = bestMean;
    return best;
}

struct Sequence {
    ChromaticityTable table;
    ImageBuffer rgb{kW, kH, PixelFormat::RGB24};
    ImageBuffer r{kW, kH, PixelFormat::Gray8}, g{kW, kH, PixelFormat::Gray8},
        b{kW, kH, PixelFormat::Gray8};
    ChromaticityPlanes planes() { return {r.view(), g.view(), b.view()}; }
    void frame(int f)
    {
        render(f, rgb);
        convertChromaticity(table, rgb.view(), planes());
    }
    void frame(int f, const Quad& q)
    {
        renderQuad(f, q, true, rgb);
        convertChromaticity(table, rgb.view(), planes());
    }
};

}  // namespace

TEST(CardTracker, UntrainedDoesNothing)
{
    auto seq = std::make_unique<Sequence>();
    seq->frame(0);
    CardTracker tracker({kW, kH});
    EXPECT_EQ(tracker.process(seq->rgb.view(), seq->planes()).state, CardState::Untrained);
    EXPECT_FALSE(tracker.observation().hasQuad);
    EXPECT_STREQ(cardStateName(CardState::Lost), "lost");
    EXPECT_FALSE(tracker.train(seq->rgb.view(), seq->planes(), {400, 400, 10, 10}));
}

TEST(CardTracker, TracksTheGeneratedSequenceAccurately)
{
    auto seq = std::make_unique<Sequence>();
    CardTracker tracker({kW, kH});
    seq->frame(0);
    ASSERT_TRUE(tracker.train(seq->rgb.view(), seq->planes(), centralRegion({kW, kH}, 0.2f)));
    EXPECT_EQ(tracker.observation().state, CardState::Searching);

    double sum = 0;
    int scored = 0, within3 = 0, lostWhileVisible = 0, recoveredAt = -1;
    float restMin[8], restMax[8];
    for (int i = 0; i < 8; ++i) {
        restMin[i] = 1e9f;
        restMax[i] = -1e9f;
    }
    for (int f = 0; f < kFrames; ++f) {
        seq->frame(f);
        const CardObservation& o = tracker.process(seq->rgb.view(), seq->planes());
        const bool visible = f < kAbsentFrom || f >= kAbsentTo;
        if (!visible) {
            EXPECT_NE(o.state, CardState::Tracking) << "frame " << f;
            continue;
        }
        if (f >= kAbsentTo && recoveredAt < 0 && o.state == CardState::Tracking)
            recoveredAt = f;
        ++scored;
        if (o.state != CardState::Tracking) {
            ++lostWhileVisible;
            continue;
        }
        float mean;
        const float worst = maxCornerError(o.quad, truthAt(f), &mean);
        sum += mean;
        within3 += worst <= 3.f;
        EXPECT_GT(o.confidence, 0.3f) << "frame " << f;
        if (worst > 3.f)
            std::printf("frame %d: worst corner error %.2f px (mean %.2f)\n", f, worst, mean);
        if (f >= 3 && f < 10)
            for (int i = 0; i < 4; ++i) {
                restMin[2 * i] = std::fmin(restMin[2 * i], o.quad[i].x);
                restMax[2 * i] = std::fmax(restMax[2 * i], o.quad[i].x);
                restMin[2 * i + 1] = std::fmin(restMin[2 * i + 1], o.quad[i].y);
                restMax[2 * i + 1] = std::fmax(restMax[2 * i + 1], o.quad[i].y);
            }
    }
    const double meanErr = sum / std::max(1, scored - lostWhileVisible);
    const double share = double(within3) / double(scored);
    std::printf(
        "mean corner error %.3f px, within 3 px %.1f%%, lost while visible %d, recovered "
        "at frame %d\n",
        meanErr, 100.0 * share, lostWhileVisible, recoveredAt);
    EXPECT_LE(meanErr, 1.5);
    EXPECT_GE(share, 0.95);
    ASSERT_GE(recoveredAt, kAbsentTo);
    EXPECT_LE(recoveredAt - kAbsentTo, 15);
    for (int i = 0; i < 8; ++i)
        EXPECT_LT(restMax[i] - restMin[i], 0.5f) << "jitter at rest, coordinate " << i;
}

TEST(CardTracker, ExtrapolatesACornerOutOfViewAndLosesAWholeEdge)
{
    auto seq = std::make_unique<Sequence>();
    CardTracker tracker({kW, kH});
    seq->frame(0);
    ASSERT_TRUE(tracker.train(seq->rgb.view(), seq->planes(), centralRegion({kW, kH}, 0.2f)));
    // A rolled card slides up until its top corner is 20 px above the frame.
    auto quadAt = [](float up) {
        return Quad{
            {{140.f, 60.f - up}, {250.f, 95.f - up}, {225.f, 175.f - up}, {115.f, 140.f - up}}};
    };
    float mean = 0.f;
    for (int i = 0; i <= 20; ++i) {
        const Quad q = quadAt(4.f * float(i));
        seq->frame(5, q);  // frame 5: no occluder, no motion-dependent noise pattern
        const CardObservation& o = tracker.process(seq->rgb.view(), seq->planes());
        ASSERT_EQ(o.state, CardState::Tracking) << "step " << i << ": " << tracker.lastProblem();
        if (i == 20) {
            EXPECT_LT(q[0].y, -15.f);
            EXPECT_LT(maxCornerError(o.rawQuad, q, &mean), 2.f);
        }
    }
    // Further up a whole edge leaves the view: that edge is unknowable -> not tracked.
    for (int i = 0; i < 30 && tracker.observation().state == CardState::Tracking; ++i) {
        seq->frame(5, quadAt(80.f + 4.f * float(i)));
        tracker.process(seq->rgb.view(), seq->planes());
    }
    EXPECT_EQ(tracker.observation().state, CardState::Lost);
    EXPECT_STRNE(tracker.lastProblem(), "");
}

TEST(CardTracker, LosesTheTrackWhenTheModelWouldRunAway)
{
    // A frame that is all card colour: the component covers (nearly) the whole frame.
    auto seq = std::make_unique<Sequence>();
    CardTracker tracker({kW, kH});
    seq->frame(0);
    ASSERT_TRUE(tracker.train(seq->rgb.view(), seq->planes(), centralRegion({kW, kH}, 0.2f)));
    for (int f = 0; f < 3; ++f)
        tracker.process(seq->rgb.view(), seq->planes());
    ASSERT_EQ(tracker.observation().state, CardState::Tracking);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            std::uint8_t* p = seq->rgb.view().row(y) + 3 * x;
            p[0] = 30;
            p[1] = 70;
            p[2] = 190;
        }
    convertChromaticity(seq->table, seq->rgb.view(), seq->planes());
    const CardObservation& o = tracker.process(seq->rgb.view(), seq->planes());
    EXPECT_EQ(o.state, CardState::Lost);
    EXPECT_TRUE(o.hasQuad);  // the last good shape
    EXPECT_EQ(o.framesSinceGood, 1u);
    // The current model went back to the trained one for the search.
    EXPECT_EQ(tracker.currentModel().mean[0], tracker.trainedModel().mean[0]);
}

TEST(CardTracker, SavedModelAndXrgbInput)
{
    auto seq = std::make_unique<Sequence>();
    seq->frame(20);
    CardTracker trainer({kW, kH});
    seq->frame(0);
    ASSERT_TRUE(trainer.train(seq->rgb.view(), seq->planes(), centralRegion({kW, kH}, 0.2f)));
    // Same frame as XRGB8888 into a tracker given the saved model.
    ImageBuffer x(kW, kH, PixelFormat::XRGB8888);
    seq->frame(20);
    for (int y = 0; y < kH; ++y)
        for (int i = 0; i < kW; ++i) {
            const std::uint8_t* p = seq->rgb.view().row(y) + 3 * i;
            std::uint8_t* q = x.view().row(y) + 4 * i;
            q[0] = p[2];
            q[1] = p[1];
            q[2] = p[0];
            q[3] = 0;
        }
    CardTracker tracker({kW, kH});
    tracker.setModel(trainer.trainedModel());
    const CardObservation& o = tracker.process(x.view(), seq->planes());
    ASSERT_EQ(o.state, CardState::Tracking);
    float mean;
    EXPECT_LT(maxCornerError(o.quad, truthAt(20), &mean), 3.f);
    // Mask: card pixels set, background clear.
    const Quad t = truthAt(20);
    const Point2f c{(t[0].x + t[2].x) / 2, (t[0].y + t[2].y) / 2};
    EXPECT_EQ(o.mask.row(int(c.y))[int(c.x)], 255);
    EXPECT_EQ(o.mask.row(2)[2], 0);
}

TEST(CardTracker, StageTrainsOnTheNextFrame)
{
    auto seq = std::make_unique<Sequence>();
    CardStage stage({kW, kH});
    EXPECT_STREQ(stage.name(), "card");
    seq->frame(0);
    FrameState state;
    state.frame.image = seq->rgb.view();
    stage.process(state);  // no chroma: skipped
    EXPECT_EQ(state.card, nullptr);
    state.chroma = seq->planes();
    stage.process(state);
    ASSERT_NE(state.card, nullptr);
    EXPECT_EQ(state.card->state, CardState::Untrained);
    stage.requestTraining(0.2f);
    EXPECT_TRUE(stage.trainingPending());
    stage.process(state);
    EXPECT_FALSE(stage.trainingPending());
    EXPECT_TRUE(stage.lastTrainingSucceeded());
    EXPECT_TRUE(stage.tracker().trainedModel().valid);
    EXPECT_EQ(state.card->state, CardState::Tracking);
    EXPECT_EQ(centralRegion({100, 50}, 0.5f), (Rect{25, 12, 50, 25}));
}

TEST(CardTracker, ProcessDoesNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting not available in this build";
    auto seq = std::make_unique<Sequence>();
    CardTracker tracker({kW, kH});
    seq->frame(0);
    ASSERT_TRUE(tracker.train(seq->rgb.view(), seq->planes(), centralRegion({kW, kH}, 0.2f)));
    std::vector<std::unique_ptr<Sequence>> frames;
    const int which[] = {1, 35, 65, 104, 112};  // tracking, occluded, fast, absent, recovering
    for (int f : which) {
        frames.push_back(std::make_unique<Sequence>());
        frames.back()->frame(f);
    }
    testing_support::AllocationScope scope;
    for (auto& s : frames)
        tracker.process(s->rgb.view(), s->planes());
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}
