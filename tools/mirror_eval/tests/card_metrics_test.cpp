// Card metrics on made-up tracker output: corner errors, within-3-px, lost frames, recovery,
// frames partly out of view, jitter at rest, and the summary line's format.

#include "card_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using mirror_eval::CardEvalSettings;
using mirror_eval::computeCardMetrics;
using mirror_eval::TrackedFrame;
using mirror_eval::TruthRow;

const vision::Quad kQuad = {vision::Point2f{100, 100}, vision::Point2f{300, 100},
                            vision::Point2f{300, 250}, vision::Point2f{100, 250}};

vision::Quad shifted(const vision::Quad& q, float dx, float dy)
{
    vision::Quad out = q;
    for (auto& p : out) {
        p.x += dx;
        p.y += dy;
    }
    return out;
}

TruthRow card(int frame, const vision::Quad& q = kQuad)
{
    return {frame, true, q};
}
TruthRow none(int frame)
{
    return {frame, false, {}};
}
TrackedFrame at(const vision::Quad& q)
{
    return {true, q};
}
TrackedFrame nothing()
{
    return {};
}

CardEvalSettings settings()
{
    CardEvalSettings s;
    s.frameSize = {720, 480};
    return s;
}

TEST(CardMetrics, CornerErrorsPercentileAndWithin3px)
{
    // Frame 0 trains and is ignored, whatever the tracker says.
    const std::vector<TruthRow> truth = {card(0), card(1), card(2), card(3), card(4)};
    const std::vector<TrackedFrame> tracked = {nothing(), at(shifted(kQuad, 1, 0)),
                                               at(shifted(kQuad, 0, 2)), at(shifted(kQuad, 3, 4)),
                                               at(kQuad)};
    const auto m = computeCardMetrics(truth, tracked, settings());
    EXPECT_EQ(m.frames, 5);
    EXPECT_EQ(m.scoredFrames, 4);
    EXPECT_EQ(m.measuredFrames, 4);
    EXPECT_DOUBLE_EQ(m.meanErrPx, 2.0);  // (1 + 2 + 5 + 0) / 4
    EXPECT_DOUBLE_EQ(m.p95ErrPx, 5.0);
    EXPECT_DOUBLE_EQ(m.maxErrPx, 5.0);
    EXPECT_EQ(m.withinFrames, 3);
    EXPECT_DOUBLE_EQ(m.withinFraction, 0.75);
    EXPECT_EQ(m.lostFrames, 0);
    EXPECT_EQ(m.recoveries, 0);
    const std::string head =
        "card: mean_err_px=2.00 p95_err_px=5.00 within3px=0.750 lost_frames=0 ";
    EXPECT_EQ(mirror_eval::cardSummaryLine(m).substr(0, head.size()), head);
}

TEST(CardMetrics, OneBadCornerFailsWithin3pxForTheFrame)
{
    vision::Quad q = kQuad;
    q[2].x += 3.5f;
    const auto m = computeCardMetrics({card(0), card(1)}, {nothing(), at(q)}, settings());
    EXPECT_EQ(m.withinFrames, 0);
    EXPECT_NEAR(m.meanErrPx, 3.5 / 4, 1e-6);
}

TEST(CardMetrics, LostFramesAndRecoveryAfterTheCardComesBack)
{
    // 1-3 card, 4-6 no card, 7-12 card; the tracker finds it again at 9: 2 frames to recover.
    std::vector<TruthRow> truth;
    std::vector<TrackedFrame> tracked;
    for (int i = 0; i <= 12; ++i) {
        const bool present = i < 4 || i > 6;
        truth.push_back(present ? card(i) : none(i));
        tracked.push_back((i >= 1 && i <= 3) || i >= 9 ? at(kQuad) : nothing());
    }
    const auto m = computeCardMetrics(truth, tracked, settings());
    EXPECT_EQ(m.absentFrames, 3);
    EXPECT_EQ(m.scoredFrames, 9);
    EXPECT_EQ(m.lostFrames, 2);  // 7 and 8
    EXPECT_DOUBLE_EQ(m.withinFraction, 7.0 / 9.0);
    EXPECT_EQ(m.recoveries, 1);
    EXPECT_EQ(m.maxRecoverFrames, 2);
    EXPECT_DOUBLE_EQ(m.meanRecoverFrames, 2.0);
    EXPECT_EQ(m.unrecovered, 0);
    EXPECT_EQ(m.falseTrackingFrames, 0);
}

TEST(CardMetrics, TrackLostWhileInViewAndNeverRecovered)
{
    // Lost at 3 with the card in view all along (recovers at 6: 3 frames); lost again at 8 for
    // good (unrecovered, 3 frames so far); tracking at 1 with no card is false tracking.
    std::vector<TruthRow> truth = {card(0), none(1)};
    std::vector<TrackedFrame> tracked = {nothing(), at(kQuad)};
    for (int i = 2; i <= 10; ++i) {
        truth.push_back(card(i));
        tracked.push_back((i >= 3 && i <= 5) || i >= 8 ? nothing() : at(kQuad));
    }
    const auto m = computeCardMetrics(truth, tracked, settings());
    EXPECT_EQ(m.falseTrackingFrames, 1);
    EXPECT_EQ(m.lostFrames, 6);
    EXPECT_EQ(m.lostStretches, 2);  // 3..5 and 8..10
    EXPECT_EQ(m.recoveries, 2);     // frame 1's stretch (recovered at 2, 0 frames) and 3..5
    EXPECT_EQ(m.maxRecoverFrames, 3);
    EXPECT_DOUBLE_EQ(m.meanRecoverFrames, 1.5);
    EXPECT_EQ(m.unrecovered, 1);
}

TEST(CardMetrics, CardMostlyOutOfViewIsNotScored)
{
    // One corner out: scored (the two edges through it are visible). Two out: not scored, and the
    // tracker reporting nothing then is not a lost frame; recovery is timed from full view.
    const vision::Quad oneOut = shifted(kQuad, -120, 0);  // x0, x3 = -20: two out
    vision::Quad cornerOut = kQuad;
    cornerOut[0] = {-10, -5};
    const std::vector<TruthRow> truth = {
        card(0), card(1, cornerOut), card(2, oneOut), card(3, oneOut), card(4), card(5)};
    const std::vector<TrackedFrame> tracked = {nothing(), at(cornerOut), nothing(),
                                               nothing(), nothing(),     at(kQuad)};
    const auto m = computeCardMetrics(truth, tracked, settings());
    EXPECT_EQ(m.scoredFrames, 3);  // 1, 4, 5
    EXPECT_EQ(m.partialFrames, 2);
    EXPECT_EQ(m.lostFrames, 1);     // 4
    EXPECT_EQ(m.lostStretches, 1);  // 4 (2 and 3 are not scored)
    EXPECT_EQ(m.recoveries, 1);
    EXPECT_EQ(m.maxRecoverFrames, 1);  // fully visible at 4, tracking at 5
    EXPECT_DOUBLE_EQ(m.meanErrPx, 0.0);
}

TEST(CardMetrics, JitterAtRestIsTheRmsCornerDeviationAfterSettling)
{
    std::vector<TruthRow> truth = {card(0)};
    std::vector<TrackedFrame> tracked = {nothing()};
    for (int i = 1; i <= 20; ++i) {
        truth.push_back(card(i));
        // The first frames settle (large offsets, not counted), then +-0.1 px in x.
        const float dx = i <= 5 ? 2.0f : (i % 2 == 0 ? 0.1f : -0.1f);
        tracked.push_back(at(shifted(kQuad, dx, 0)));
    }
    // Then motion: no static stretch.
    for (int i = 21; i <= 25; ++i) {
        truth.push_back(card(i, shifted(kQuad, static_cast<float>(i), 0)));
        tracked.push_back(at(truth.back().quad));
    }
    const auto m = computeCardMetrics(truth, tracked, settings());
    EXPECT_EQ(m.restRuns, 1);
    EXPECT_NEAR(m.jitterPx, 0.1, 0.002);
    EXPECT_NEAR(m.maxJitterPx, 0.1, 0.002);
}

TEST(CardMetrics, NothingMeasuredGivesNan)
{
    const auto m = computeCardMetrics({card(0), card(1)}, {nothing(), nothing()}, settings());
    EXPECT_TRUE(std::isnan(m.meanErrPx));
    EXPECT_EQ(m.lostFrames, 1);
    EXPECT_DOUBLE_EQ(m.withinFraction, 0.0);
    EXPECT_EQ(m.unrecovered, 1);
}

TEST(CardMetrics, LengthsMustAgree)
{
    EXPECT_THROW(computeCardMetrics({card(0)}, {}, settings()), std::invalid_argument);
}

}  // namespace

TEST(CardMetrics, ACardTurned45DegreesMayBeLabelledFromEitherTiedCorner)
{
    // A diamond: the top and left corners have the same x + y, so "clockwise from the top-left"
    // may start at either. The tracker starting at the other one is not 200 px off.
    const vision::Quad diamond = {vision::Point2f{300, 100}, vision::Point2f{400, 200},
                                  vision::Point2f{300, 300}, vision::Point2f{200, 200}};
    const vision::Quad fromLeft = {diamond[3], diamond[0], diamond[1], diamond[2]};
    double e[4];
    mirror_eval::matchedCornerErrors(shifted(fromLeft, 1.f, 0.f), diamond, 6.f, e);
    for (double ek : e)
        EXPECT_NEAR(ek, 1.0, 1e-9);
    const auto m = computeCardMetrics({card(0, diamond), card(1, diamond)},
                                      {nothing(), at(fromLeft)}, settings());
    EXPECT_EQ(m.withinFrames, 1);

    // Without a tie the truth's labelling stands: a quad labelled from another corner is wrong.
    const vision::Quad rotated = {kQuad[1], kQuad[2], kQuad[3], kQuad[0]};
    mirror_eval::matchedCornerErrors(rotated, kQuad, 6.f, e);
    EXPECT_NEAR(e[0], 200.0, 1e-9);
}
