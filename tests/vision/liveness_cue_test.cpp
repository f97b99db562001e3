// LivenessCue on synthetic corner flows, each step fitted as the tracker fits them: a calm head's
// sub-pixel sway is seen within a few steps; a print's noise, the light's slow drift of a print,
// a passer-by dragging one side's corners and a camera at rest are not; the history keeps only
// its last steps; nothing allocates.
#include "vision/liveness_cue.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

using vision::LivenessCue;
using vision::MotionFitOptions;
using vision::MotionModel;
using vision::Point2f;
using vision::SwayHistory;

namespace {

/// Deterministic Gaussian-ish noise (sum of 4 uniforms), standard deviation `sigma`.
class Noise {
public:
    float next(float sigma)
    {
        float s = 0.f;
        for (int i = 0; i < 4; ++i) {
            seed_ = seed_ * 1664525u + 1013904223u;
            s += static_cast<float>(seed_ >> 8) / static_cast<float>(1u << 24) - 0.5f;
        }
        return s * sigma * 1.732f;  // 4 uniforms of variance 1/12: sum has variance 1/3
    }

private:
    std::uint32_t seed_ = 2024;
};

/// A face's corners (30, in a 60-px box about (100, 100)) and one flow step of them at a time.
class Face {
public:
    Face()
    {
        for (int i = 0; i < 30; ++i)
            corners_.push_back({75.f + static_cast<float>((i * 37) % 50),
                                75.f + static_cast<float>((i * 23) % 50)});
    }

    /// Moves every corner by `common`, the corners right of the centre also by `right`, each
    /// with flow noise `sigma`; fits the step as the tracker does and gives it to the cue.
    void step(LivenessCue& cue, SwayHistory& h, Point2f common, float sigma, Point2f right = {})
    {
        std::vector<Point2f> to(corners_.size());
        for (std::size_t i = 0; i < corners_.size(); ++i) {
            const bool isRight = corners_[i].x >= 100.f;
            to[i] = {corners_[i].x + common.x + (isRight ? right.x : 0.f) + noise_.next(sigma),
                     corners_[i].y + common.y + (isRight ? right.y : 0.f) + noise_.next(sigma)};
        }
        MotionModel model;
        std::vector<std::uint8_t> inliers(corners_.size());
        vision::fitMotionRobust(corners_.data(), to.data(), static_cast<int>(corners_.size()),
                                {100.f, 100.f}, MotionFitOptions{}, model, inliers.data());
        cue.addFlowStep(h, corners_, to, inliers, model);
        corners_ = to;
    }

private:
    std::vector<Point2f> corners_;
    Noise noise_;
};

/// The step (1..) at which the cue first said the face swayed, 0: never within `steps`.
template <typename Step>
int firstSway(int steps, Step&& step)
{
    LivenessCue cue;
    SwayHistory h;
    Face face;
    for (int k = 1; k <= steps; ++k) {
        step(cue, h, face, k);
        if (LivenessCue::swayed(h))
            return k;
    }
    return 0;
}

}  // namespace

TEST(LivenessCue, ACalmHeadSwaysWithinAFewSteps)
{
    // 0.04 px a step, one way, under FGNet-like flow noise (0.05 px a corner): 25% of FGNet's
    // windows move this little or less.
    const int k = firstSway(12, [](LivenessCue& c, SwayHistory& h, Face& f, int) {
        f.step(c, h, {0.03f, 0.027f}, 0.05f);
    });
    EXPECT_GE(k, 1);
    EXPECT_LE(k, 3);
}

TEST(LivenessCue, AHeadMovingBackAndForthSways)
{
    const int k = firstSway(12, [](LivenessCue& c, SwayHistory& h, Face& f, int i) {
        f.step(c, h, {(i % 4 < 2 ? 0.12f : -0.12f), 0.f}, 0.05f);
    });
    EXPECT_EQ(k, 1);
}

TEST(LivenessCue, APrintsNoiseNeverSways)
{
    // Camera noise on a still print: flow noise of 0.02-0.1 px a corner, no common motion.
    for (const float sigma : {0.02f, 0.05f, 0.1f}) {
        const int k = firstSway(200, [sigma](LivenessCue& c, SwayHistory& h, Face& f, int) {
            f.step(c, h, {}, sigma);
        });
        EXPECT_EQ(k, 0) << sigma;
    }
}

TEST(LivenessCue, APrintDriftingAsTheLightChangesNeverSways)
{
    // The light changing biases the flow of a print's edges the same way frame after frame:
    // measured up to 0.01 px a step (facegen's static faces).
    const int k = firstSway(200, [](LivenessCue& c, SwayHistory& h, Face& f, int) {
        f.step(c, h, {0.008f, 0.006f}, 0.005f);
    });
    EXPECT_EQ(k, 0);
}

TEST(LivenessCue, APasserByDraggingOneSideIsNoSway)
{
    // A head passing on the print's right drags the corners on that side by a pixel a step: the
    // median of all of them may follow, the left half's does not.
    const int k = firstSway(30, [](LivenessCue& c, SwayHistory& h, Face& f, int) {
        f.step(c, h, {}, 0.02f, {1.f, 0.2f});
    });
    EXPECT_EQ(k, 0);
}

TEST(LivenessCue, StirredIsTheLatestStepsMedianBeyondAPrintsMove)
{
    LivenessCue cue;
    SwayHistory h;
    Face face;
    EXPECT_FALSE(LivenessCue::stirred(h));
    face.step(cue, h, {0.01f, 0.f}, 0.005f);
    EXPECT_FALSE(LivenessCue::stirred(h));
    face.step(cue, h, {0.2f, 0.f}, 0.005f);
    EXPECT_TRUE(LivenessCue::stirred(h));
    face.step(cue, h, {}, 0.005f);
    EXPECT_FALSE(LivenessCue::stirred(h));
}

TEST(LivenessCue, TheHistoryKeepsItsLastSteps)
{
    SwayHistory h;
    for (int i = 0; i < SwayHistory::kSteps + 5; ++i) {
        SwayHistory::Step s;
        s.common = {static_cast<float>(i), 0.f};
        h.push(s);
    }
    ASSERT_EQ(h.size(), SwayHistory::kSteps);
    EXPECT_EQ(h.latest(0).common.x, static_cast<float>(SwayHistory::kSteps + 4));
    EXPECT_EQ(h.latest(SwayHistory::kSteps - 1).common.x, 5.f);
    h.clear();
    EXPECT_EQ(h.size(), 0);
    EXPECT_FALSE(LivenessCue::swayed(h));
}

TEST(LivenessCue, FewerThanThreeInliersAddNoStep)
{
    LivenessCue cue;
    SwayHistory h;
    const std::vector<Point2f> from = {{1.f, 1.f}, {5.f, 5.f}, {9.f, 1.f}};
    const std::vector<Point2f> to = {{2.f, 1.f}, {6.f, 5.f}, {10.f, 1.f}};
    const std::vector<std::uint8_t> inliers = {1, 0, 1};
    MotionModel model;
    model.centre = {5.f, 3.f};
    cue.addFlowStep(h, from, to, inliers, model);
    EXPECT_EQ(h.size(), 0);
}

TEST(LivenessCue, NothingAllocates)
{
    LivenessCue cue;
    SwayHistory h;
    std::vector<Point2f> from, to;
    for (int i = 0; i < 40; ++i) {
        from.push_back({static_cast<float>(i % 8) * 7.f, static_cast<float>(i / 8) * 9.f});
        to.push_back({from.back().x + 0.2f, from.back().y});
    }
    const std::vector<std::uint8_t> inliers(from.size(), 1);
    MotionModel model;
    model.centre = {25.f, 20.f};
    model.b1 = 0.2f;
    testing_support::AllocationScope scope;
    for (int k = 0; k < 20; ++k) {
        cue.addFlowStep(h, from, to, inliers, model);
        (void)LivenessCue::swayed(h);
        (void)LivenessCue::stirred(h);
    }
    if (testing_support::allocationCountingAvailable()) {
        EXPECT_EQ(scope.counts().cxxNew, 0);
        EXPECT_EQ(scope.counts().ownMalloc, 0);
    }
}
