// The card tracker on the ways it used to let go of the card or follow something else, each on
// frames cardgen renders here (nothing is read from disk but the background photographs): the
// hard family's scenes (seeds chosen because the tracker failed on them) and scenes made for one
// cause.

#include "card_run.hpp"
#include "scene.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>

namespace {

using card_test::misses;
using card_test::runFrames;
using card_test::runScenario;
using card_test::TrackerRun;

/// Every scored frame within `maxErr` pixels of the card, none tracked without it.
void expectNearTheCard(const TrackerRun& run, double maxErr)
{
    EXPECT_LE(run.metrics.maxErrPx, maxErr) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

void expectHeld(const TrackerRun& run, double maxMeanErr, double minWithin)
{
    const mirror_eval::CardMetrics& m = run.metrics;
    EXPECT_EQ(m.lostFrames, 0) << misses(run);
    EXPECT_LE(m.meanErrPx, maxMeanErr) << misses(run);
    EXPECT_GE(m.withinFraction, minWithin) << misses(run);
    EXPECT_EQ(m.falseTrackingFrames, 0);
}

// Step 4's component while tracking: a patch of a nearby hue below the card joined it (its box
// met the grown box of the last quad), so every tracked frame fitted a quad over both and was
// lost, and the next search (largest component alone) found the card again.
TEST(CardFailureModes, APieceOfTheCardsColourBesideItIsNotPartOfIt)
{
    expectHeld(runScenario("hard", 9, 1, 24), 1.0, 0.95);
}

// The same, the patch joining only while the card passes near it: the quad stretched to it.
TEST(CardFailureModes, TheCardPassingNearAPatchOfItsColourDoesNotStretchToIt)
{
    expectHeld(runScenario("hard", 6, 200, 239), 1.0, 0.95);
}

// Over a part of the background of the card's own colour, brighter than the card, no colour cue
// of §2 shows its edges (saturation and chromaticity are the same on both sides): 20 frames
// were lost with "too few edge inliers". When the colour cues find fewer than three edges, the
// walks fall back on brightness, and that fit is taken with all four edges.
TEST(CardFailureModes, ACardDimmerThanABackgroundOfItsOwnColourIsFoundByItsBrightness)
{
    expectHeld(runScenario("hard", 8002, 60, 95, 150), 1.0, 0.95);
}

// Found afresh at rest (frame 0 trains with the card filling the view), the component of the
// card's colour had something joined at one edge: the hull's edge there lay outside the card,
// its walks found no edge, and the quad kept that edge from the colour (a corner 50 px off for
// the 16 frames the card rested). That edge is walked again from deep inside the card now.
TEST(CardFailureModes, AnEdgeTheColoursQuadMisplacedIsFoundWhenFindingTheCard)
{
    expectHeld(runScenario("hard", 6007, 1, 16, 150), 1.0, 0.95);
}

// Found again after a loss under a light ramp that clips, the card's colour covered only part of
// it: three edges were walked to, the fourth was the colour's hull across the card, and the
// quad was taken with a corner 130-150 px off for six frames. An edge in view found by no walk
// does not make a found card; it is lost until its edges are seen (a few frames longer).
TEST(CardFailureModes, ACardFoundAgainNeedsEveryEdgeInViewSeen)
{
    expectNearTheCard(runScenario("hard", 3012, 84, 99, 150), 6.0);
}

// An arm across the middle cut the card in two and the top piece was too thin to join: the
// quad of the bottom half (the arm's straight edge taken for the card's) was kept for 20 frames.
TEST(CardFailureModes, AnArmAcrossTheCardDoesNotHalveIt)
{
    expectHeld(runScenario("hard", 7, 95, 126), 1.5, 0.9);
}

// A hand over the bottom-right corner: the component's hull lost that corner, the minimum
// bounding quad put it 70 px away, the refined quad kept the wrong line for the hidden edge.
TEST(CardFailureModes, AHandOverACornerDoesNotPullTheQuadAway)
{
    expectHeld(runScenario("hard", 4, 95, 135), 1.0, 0.95);
}

// An arm over the card's left edge while the card slid right and turned: no evidence of that edge
// for frames, so it kept the line it had (the colour's hull's, joined by a red shirt behind the
// card, or the last frame's) and the corners under the arm fell 40 px behind the card. Carried
// now from the last quad measured on all four edges by the motion of the two measured corners.
TEST(CardFailureModes, AnEdgeUnderAnArmMovesWithTheCard)
{
    const TrackerRun run = runScenario("hard", 3, 110, 138);
    EXPECT_EQ(run.metrics.lostFrames, 0) << misses(run);
    EXPECT_LE(run.metrics.maxErrPx, 8.0) << misses(run);
    EXPECT_LE(run.metrics.meanErrPx, 1.5) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// A hand over the card's right edge (corners 12-14 px off under it before). The wide pass of
// step 5 can take the hand's outline for that edge; when the narrow pass does not find it again,
// the wide pass's quad was kept as if all four edges were fitted and won over a fit that carried
// the hidden edge. Only an edge both passes find counts as fitted now.
TEST(CardFailureModes, AHandsOutlineIsNotTakenForTheCardsEdge)
{
    const TrackerRun run = runScenario("hard", 11, 50, 100);
    EXPECT_EQ(run.metrics.lostFrames, 0) << misses(run);
    EXPECT_LE(run.metrics.maxErrPx, 8.0) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// A hand over the card's top-left corner: the colour's fit carried the top edge with the card,
// but the fit from the predicted quad took the hand's outline within its guide for that edge and
// won by the edge count; measured on four edges, that quad became the reference the next frames
// carried the edge from (a corner 18-25 px off for seven frames). A line found for an edge away
// from where the card carried it is not the card's edge.
TEST(CardFailureModes, AHandsOutlineDoesNotReplaceAnEdgeCarriedWithTheCard)
{
    const TrackerRun run = runScenario("hard", 6003, 38, 56, 150);
    EXPECT_EQ(run.metrics.lostFrames, 0) << misses(run);
    EXPECT_LE(run.metrics.maxErrPx, 6.0) << misses(run);
    EXPECT_LE(run.metrics.meanErrPx, 1.5) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// The same hand a little later: the top edge could not be carried, the colour's fit kept the
// colour's hull there (cut across the card by the hand), a quad 100 px from where the card was
// expected with a corner 200 px off, and it won over the fit from the predicted quad by inliers.
// A fit that kept a hull's edge far from the prediction is not the card when the predicted one
// fits as many edges, each fitted, carried, or in view.
TEST(CardFailureModes, AColoursHullCutByAHandIsNotTheCardFarFromWhereItIsExpected)
{
    const TrackerRun run = runScenario("hard", 6003, 38, 70, 150);
    EXPECT_EQ(run.metrics.lostFrames, 0) << misses(run);
    EXPECT_LE(run.metrics.maxErrPx, 40.0) << misses(run);
    EXPECT_LE(run.metrics.meanErrPx, 3.0) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// The same hand while the card turns in depth: the similarity cannot carry the hidden edge (the
// fitted neighbours turn otherwise than the measured edge), and the fit from the predicted quad
// kept the prediction's line for it, the last frame's (no velocity while an edge is hidden): it
// stood still while the card moved on, a corner 16-33 px off for three frames. The hidden corners
// lie on their fitted neighbour lines as far from the measured corners as the last frame's now.
TEST(CardFailureModes, AnEdgeUnderAHandWhileTheCardTurnsInDepthKeepsItsNeighboursLengths)
{
    const TrackerRun run = runScenario("hard", 6003, 38, 70, 150);
    EXPECT_EQ(run.metrics.lostFrames, 0) << misses(run);
    EXPECT_LE(run.metrics.maxErrPx, 10.0) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// A dark hand of nearly the card's colour over its right corner while the card turns in depth:
// the right edge was hidden for a few frames, then both passes fitted the hand's outline (a line
// across the card, 17 degrees off the card's edge) as that edge, a corner 45-50 px off for 18
// frames. A line for an edge hidden in the last frame, far from where its neighbours' lengths put
// it and turned from it by more than the card turns in a frame, is the outline, not the edge.
TEST(CardFailureModes, AHandsOutlineIsNotTakenForAnEdgeHiddenInTheLastFrame)
{
    const TrackerRun run = runScenario("hard", 3001, 40, 75, 150);
    EXPECT_EQ(run.metrics.lostFrames, 0) << misses(run);
    EXPECT_LE(run.metrics.maxErrPx, 20.0) << misses(run);
    EXPECT_LE(run.metrics.meanErrPx, 2.5) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// The hand over the top-left corner while the card turns in depth (frames 54-74): the hidden
// edge was placed by the similarity carry, then by its neighbours' last lengths, 4-15 px off (the
// similarity cannot foreshorten, the lengths drift while the corner stays hidden). With the focal
// length and the card's aspect estimated from the frames measured on all four edges, the edge is
// placed where a rectangle of that aspect projects (CardCameraEstimate).
TEST(CardFailureModes, AnEdgeUnderAHandWhileTheCardTurnsInDepthIsPlacedAsTheCardIn3d)
{
    const TrackerRun run = runScenario("hard", 3001, 20, 75, 150);
    EXPECT_EQ(run.metrics.lostFrames, 0) << misses(run);
    EXPECT_LE(run.metrics.maxErrPx, 6.0) << misses(run);
    EXPECT_GE(run.metrics.withinFraction, 0.93) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// A hand over the card's bottom-right corner while its top-right corner was out of view: the
// right edge, running out of view, was not carried (an edge at the border is unknowable), so it
// kept the wide pass's line, the hand's outline (70-85 px off from frame 121). An edge with an
// end in view is carried now.
TEST(CardFailureModes, AnEdgeRunningOutOfViewUnderAHandMovesWithTheCard)
{
    const TrackerRun run = runScenario("hard", 1001, 112, 130);
    EXPECT_EQ(run.metrics.lostFrames, 0) << misses(run);
    EXPECT_LE(run.metrics.maxErrPx, 6.0) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// Found again as it came back into view, the card's one visible piece of an edge (4 px) gave a
// quad with a corner 400 px outside the frame, followed for frames after. (A guard: the tracker
// before the shape model lost the card here instead; the second seed made this possible.)
TEST(CardFailureModes, ACornerFarOutOfViewIsNotGuessedWhenFindingTheCardAgain)
{
    const TrackerRun run = runScenario("hard", 4, 160, 195);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
    EXPECT_LE(run.metrics.maxErrPx, 12.0) << misses(run);
}

// The card leaving the view over its left corner: the colour's hull, clipped by the border, gave
// step 4 a quad with an edge along the top of the clipped part, running 300 px out of view; step 5
// found no evidence for it and the quad was taken with a corner 313 px off. An edge without
// evidence running far out of view, not carried with the card, is not the card's.
TEST(CardFailureModes, AnEdgeOfTheHullRunningOutOfViewIsNotTakenForTheCards)
{
    expectNearTheCard(runScenario("hard", 7006, 96, 112, 150), 6.0);
}

// An arm across the card hid it for four frames (half out of view at the top); found again in
// the fifth, the card was two pieces either side of the arm, each smaller than a patch of its
// colour across the frame, and the largest component (the patch) was taken for it and followed
// for the rest of the sequence (500 px off once the card was back in view). The pieces where the
// card was lost are looked for first, for a third of a second.
TEST(CardFailureModes, AfterAnArmHidItTheCardIsLookedForWhereItWasNotInAPatchOfItsColour)
{
    const TrackerRun run = runScenario("hard", 8010, 1, 100, 150);
    // Frame 61, the card half out of view as the arm comes: 5.9 px with the similarity carry,
    // 6.8 with the card in 3D; the patch was 500 px off.
    EXPECT_LE(run.metrics.maxErrPx, 12.0) << misses(run);
    EXPECT_LE(run.metrics.lostFrames, 4) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// Found afresh beside a background of nearly its colour (a stadium's blue crowd), the colour's
// hull reached 120 px past the card's right edge; the walks from deep inside, at most 0.35 of
// the hull's shortest edge, still started outside the card, so the card was refused ("an edge
// in view not found") for its first 21 frames. They start up to 0.45 of the hull's depth now.
TEST(CardFailureModes, ACardBesideABackgroundOfNearlyItsColourIsFoundFromDeepInside)
{
    const TrackerRun run = runScenario("hard", 7001, 1, 20, 150);
    EXPECT_LE(run.metrics.lostFrames, 3) << misses(run);
    EXPECT_LE(run.metrics.maxErrPx, 6.0) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// A hand over a corner while the card turned: the three fitted lines had a second 3D solution,
// its hidden corners 125-134 px from the image-plane carry with a spread under 1 px (the spread
// measures how unsure a right solution is, not whether it is right), and the blend took it:
// frames 97-105 79-120 px off. A 3D placement farther from the carry than the card moves from
// where it is expected is not used.
TEST(CardFailureModes, AWrongSolutionOfTheCardIn3DIsNotTakenForItsHiddenCorner)
{
    expectNearTheCard(runScenario("hard", 7011, 1, 110, 150), 12.0);
}

// The same rule kept a patch of the card's colour out: lost for six frames leaving the view, the
// card came back beside a patch of its colour, and the place where it was expected, grown with
// the frames lost, held both; with the pieces the rule adds, the quad spanned both (here frames
// 123-125 250-300 px off, then 11 frames lost; in `mirror-eval card` on the same seed 103-115,
// 150-165 px). From the fourth frame lost only the largest component there is taken.
TEST(CardFailureModes, ACardLostForLongerIsNotJoinedToAPatchOfItsColourBesideIt)
{
    const TrackerRun run = runScenario("hard", 9009, 1, 140, 150);
    EXPECT_LE(run.metrics.maxErrPx, 12.0) << misses(run);
    EXPECT_LE(run.metrics.lostFrames, 4) << misses(run);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
}

// An arm across the middle, the card turning: step 5 walked from where the card was expected
// to the arm's upper outline, 65 px inside the card's top edge and turned 22 degrees from it, and
// took it for that edge (frames 71-74 74-79 px off; the 3D camera estimate, fed those quads, then
// stopped being trusted). One edge's line farther from where it is expected than the card
// moves, the others as expected, is placed as a hidden edge.
TEST(CardFailureModes, AnArmsOutlineTurnedAcrossTheCardIsNotTakenForItsEdge)
{
    expectNearTheCard(runScenario("hard", 9006, 1, 111, 150), 6.0);
}

// The card leaving the view on the right, an arm across it: its right edge, both corners out of
// view, was refused as the card leaving the frame by the card in 3D, and the neighbours' lengths
// placed it at the border instead (frames 57-76 14-46 px off). Placed in 3D where the card's
// recent shape agrees, an edge out of view is kept (the rest of the card is in view).
TEST(CardFailureModes, AnEdgeOutOfViewIsPlacedAsTheCardIn3d)
{
    expectNearTheCard(runScenario("hard", 3003, 1, 100, 150), 15.0);
}

// A hand over the card's right edge while that edge is out of view: the walks found the hand's
// side, near parallel to the card's edge and 38-51 px inside it, and all four edges were taken
// (frames 90-97 24-54 px off). Its line far from where the edge is expected, the others as
// expected, it is placed as a hidden edge.
TEST(CardFailureModes, AHandsSideBesideAnEdgeOutOfViewIsNotTakenForIt)
{
    expectNearTheCard(runScenario("hard", 7007, 60, 110, 150), 12.0);
}

// An arm from the left over the card's top edge, near parallel to it and 15 px inside: the
// guided walks took its outline for that edge and all four edges were fitted (frame 89 14 px
// off, then 3-6 px for three frames), preferred to the fit that placed the edge in 3D. A quad
// fitted on four edges whose sides' ratio in 3D is not the card's aspect is not the card.
TEST(CardFailureModes, AnArmAlongAnEdgeIsNotTakenForItWhereTheCardsShapeIn3dSaysSo)
{
    expectNearTheCard(runScenario("hard", 9015, 1, 100, 150), 6.0);
}

// A hand over the card's bottom right corner, its fingers along the right edge: the walks took
// the hand's side for the lower part of that edge, turning it about its top corner, and all four
// edges were fitted (frames 69-86 12-32 px off; the aspect in 3D moved less than 3%). A quad whose
// sides are not at right angles in 3D is not the card.
TEST(CardFailureModes, AHandsSideTurningAnEdgeIsNotTakenForItWhereTheCardsRightAngleSaysSo)
{
    expectNearTheCard(runScenario("hard", 9011, 1, 86, 150), 6.0);
}

// A hand over a corner while the card turned: the similarity carry of the hidden edge drifted
// 13-29 px in a few frames (it cannot turn with the card) while the card in 3D placed it within
// 4 px, and a 3D placement farther from the carry than the guide was taken for a wrong solution:
// the carry went on to 90 px off (frames 100-116). Only one farther than twice the guide is.
TEST(CardFailureModes, AnEdgeUnderAHandIsPlacedIn3dWhereTheCarryDriftedFromIt)
{
    expectNearTheCard(runScenario("hard", 9034, 1, 120, 150), 12.0);
}

// A card in front of something as saturated as itself and of a near hue (a red card on an
// orange wall): no saturation step anywhere around it (not even the grey of a blend between
// complementary colours), so step 5 found too few edge points in every frame.
TEST(CardFailureModes, ACardInFrontOfSomethingAsSaturatedAsItself)
{
    const cv::Size size(720, 480);
    cv::Mat wall(size, CV_8UC3);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const int t = (x / 6 + y / 9) % 3 * 8;                           // a little texture
            wall.at<cv::Vec3b>(y, x) = cv::Vec3b(30 + t, 110 + t, 220 - t);  // BGR: orange
        }
    const cardgen::FrameSpec training = [] {
        cardgen::FrameSpec s;
        s.quad = {vision::Point2f{-8.5f, -8.5f}, vision::Point2f{727.5f, -8.5f},
                  vision::Point2f{727.5f, 487.5f}, vision::Point2f{-8.5f, 487.5f}};
        s.paint = cardgen::shadeCard({}, cv::Vec3b(190, 36, 44), 0.0, 77u);
        return s;
    }();
    const double focal = 0.9 * 720;
    auto scene = [&](int i) {
        if (i == 0)
            return training;
        cardgen::CardPose pose{330.0 + 2.0 * i, 230.0 + 0.6 * i, 86.0, 0.2, -0.15, 0.1 + 0.004 * i};
        cardgen::FrameSpec s;
        s.quad = cardgen::projectCard(pose, focal);
        s.paint = cardgen::shadeCard(pose, cv::Vec3b(190, 36, 44), i / 30.0, 77u + i);  // red
        return s;
    };
    std::vector<int> frames;
    for (int i = 0; i <= 30; ++i)
        frames.push_back(i);
    expectHeld(runFrames(wall, scene, frames), 1.0, 0.95);
}

// Lost while the light is up and clipping (the card leaves the view), the card comes back under
// the same light: its chromaticity is then outside the trained colour's band, and the search
// with the trained colour alone did not find it until the light went down again.
TEST(CardFailureModes, TheCardIsFoundAgainUnderTheLightItWasLostIn)
{
    const cv::Size size(720, 480);
    const cv::Mat photo = cardgen::loadBackground(
        testing_support::sharedData("debian_skimage_faces/astronaut.png"), size);
    const double focal = 0.9 * 720;
    const cv::Vec3b magenta(204, 42, 140);
    auto scene = [&](int i) {
        cardgen::FrameSpec s;
        if (i == 0) {
            s.quad = {vision::Point2f{-8.5f, -8.5f}, vision::Point2f{727.5f, -8.5f},
                      vision::Point2f{727.5f, 487.5f}, vision::Point2f{-8.5f, 487.5f}};
            s.paint = cardgen::shadeCard({}, magenta, 0.0, 5u);
            return s;
        }
        // Up to 2.2x over 20 frames; out of view to the right from 26 to 40; back by 50.
        s.gain = 1.0 + 1.2 * std::min(1.0, i / 20.0);
        const double away = i < 26   ? 0.0
                            : i < 34 ? (i - 26) / 8.0
                            : i < 42 ? 1.0
                                     : std::max(0.0, (50 - i) / 8.0);
        cardgen::CardPose pose{300.0 + 520.0 * away, 240.0, 80.0, 0.25, -0.1, 0.12};
        s.quad = cardgen::projectCard(pose, focal);
        s.card = cardgen::quadTouchesImage(s.quad, size);
        s.paint = cardgen::shadeCard(pose, magenta, i / 30.0, 5u + i);
        return s;
    };
    std::vector<int> frames;
    for (int i = 0; i <= 70; ++i)
        frames.push_back(i);
    const TrackerRun run = runFrames(photo, scene, frames);
    EXPECT_EQ(run.metrics.falseTrackingFrames, 0);
    EXPECT_LE(run.metrics.maxRecoverFrames, 2) << misses(run);
    EXPECT_EQ(run.metrics.unrecovered, 0) << misses(run);
    EXPECT_LE(run.metrics.meanErrPx, 1.0) << misses(run);
}

}  // namespace
