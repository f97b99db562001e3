// The face pipeline on the ways it used to show a false or duplicate face, or leave a face in
// view unshown, each on frames facegen renders here from the shared photographs (nothing else is
// read from disk): the opening frames of facegen scenarios whose seeds made the tracker fail,
// from a cold start, with the shipped window budget, scored as `mirror-eval track` scores them
// (METHOD.md §3, "Integration").

#include "face_match.hpp"
#include "sequence_writer.hpp"
#include "test_paths.hpp"
#include "vision/face_stage.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/motion_stage.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

using namespace vision;

namespace {

const char* kCascade = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";

struct Score {
    int truePositives = 0;
    int falsePositives = 0;  ///< shown faces on no moving face (static ones included)
    int missed = 0;          ///< moving faces wholly in view not shown, after the first 2 frames
    std::string log;         ///< the frames of the false positives
    double recall() const
    {
        return truePositives + missed > 0
                   ? static_cast<double>(truePositives) / (truePositives + missed)
                   : 1.0;
    }
};

/// Frames [start, start + frames) of facegen's `scenario` (its 300-frame timeline) from a cold
/// start at `start`, camera shake `shakePx`, scored from frame `scoreFrom` on.
Score run(const char* scenario, std::uint32_t seed, int start, int frames, double shakePx = 0.0,
          int scoreFrom = 0)
{
    facegen::GenerateOptions o;
    o.scenario = scenario;
    o.seed = seed;
    o.frames = 300;
    o.dataDir = testing_support::sharedData("");
    o.cascadePath = kCascade;
    o.shakePx = shakePx;
    const facegen::SequenceRenderer renderer(o);
    const HaarCascade cascade = loadHaarCascade(kCascade);
    MotionStage motion({o.size.width, o.size.height}, MotionStageOptions{});
    FaceTrackerOptions tracker;
    tracker.detectionWindowBudget = 5000;  // faces.detection_window_budget
    FaceStage faces(motion, cascade, tracker);
    const Size frameSize{o.size.width, o.size.height};
    Score score;
    for (int k = start; k < start + frames; ++k) {
        const facegen::SequenceRenderer::Frame f = renderer.frame(k);
        FrameState state;
        state.frame.image = ConstImageView{f.bgr.data, f.bgr.cols, f.bgr.rows,
                                           static_cast<int>(f.bgr.step), PixelFormat::BGR24};
        motion.process(state);
        faces.process(state);
        std::vector<mirror_eval::BoxF> shown, truth;
        for (const TrackedFace& t : state.faces)
            if (t.shown())
                shown.push_back(mirror_eval::squareAbout(t.centre, t.size));
        for (const facegen::FaceState& t : f.faces)
            truth.push_back(mirror_eval::squareAbout(
                {static_cast<float>(t.cx), static_cast<float>(t.cy)}, static_cast<float>(t.size)));
        const mirror_eval::Pairing p = mirror_eval::pairByIou(shown, truth, 0.5f);
        if (k < scoreFrom)
            continue;
        for (std::size_t c = 0; c < shown.size(); ++c) {
            const int ti = p.truthOfCandidate[c];
            bool partly = false;  // a face coming in or going out: neither true nor false
            for (std::size_t u = 0; u < truth.size() && ti < 0; ++u)
                partly = partly || (f.faces[u].moving && !wholeInFrame(truth[u], frameSize) &&
                                    iou(shown[c], partInView(truth[u], frameSize)) >= 0.5f);
            if (ti >= 0 && f.faces[static_cast<std::size_t>(ti)].moving)
                ++score.truePositives;
            else if (!partly) {
                ++score.falsePositives;
                char frame[16];
                std::snprintf(frame, sizeof frame, " %d", k);
                score.log += frame;
            }
        }
        for (std::size_t u = 0; u < truth.size(); ++u)
            score.missed += k >= start + 2 && f.faces[u].moving && p.candidateOfTruth[u] < 0 &&
                            wholeInFrame(truth[u], frameSize);
    }
    std::printf("%s seed %u frames %d-%d shake %.0f: %d true, %d false, %d missed\n", scenario,
                seed, start, start + frames - 1, shakePx, score.truePositives, score.falsePositives,
                score.missed);
    return score;
}

}  // namespace

// A face moving past a still, high-contrast edge kept the corners it left behind there: the
// similarity fit explained its move as a growth about that side (scale 1.04 a frame), the box
// grew half as large again as the face, and it was a false and a missed face at once for 8
// frames (frames 98-107). Corners that leave the face's box are now dropped (CornerFlow).
TEST(FaceFailureModes, CornersLeftBehindOnTheBackgroundDoNotGrowTheBox)
{
    const Score s = run("enter-leave", 23, 0, 108);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_GE(s.recall(), 0.97);
}

// The grouped scan of a re-anchoring found the chin and neck, a quarter of the face below it, and
// moved the box off the face for 5 frames (275-279). Re-anchoring now needs a box that shares
// half with the track's (TrackVerifier).
TEST(FaceFailureModes, ReanchoringOnAnotherGroupingDoesNotMoveTheBoxOffTheFace)
{
    const Score s = run("four", 42, 240, 45);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_GE(s.recall(), 0.97);
}

// A camera that shakes by a few pixels moves the prints on the wall as far as a calm head sways:
// all three of the background's faces were shown from the second frame (117 false faces in 40
// frames). The face rules now judge a face's flow less the view's (BackgroundMotion).
TEST(FaceFailureModes, PrintsOnAShakingCameraAreNotShown)
{
    const Score s = run("one", 1, 0, 40, 3.0);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_GE(s.recall(), 0.97);
}

// A print on the wall of a still camera was shown from frame 22 to the end (278 false faces):
// a face coming in untracked at the top biased the view's motion (BackgroundMotion) by 0.1 px
// in one frame, and the print's flow less the view's swayed together by as much, which the
// liveness cue took for a calm person. The view's motion taken off the flow now raises the sway
// asked of a face by as much (LivenessCue).
TEST(FaceFailureModes, APrintIsNotShownWhenAFaceComingInBiasesTheViewsMotion)
{
    const Score s = run("enter-leave", 21, 0, 40);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
}

// The ways a moving face wholly in view went unshown for frames (recall), each the frames around
// the misses of one facegen scene.

// An upright face the cascade answers only when turned by about 15 degrees: the cold start's
// three looks (upright, +-25) missed it, and it was unshown for its first 15 frames (0-14), until
// its own roll brought it into the +25 scan's reach. A cold start's tilted scans now also turn
// by +-15 (TiltedScan).
TEST(FaceFailureModes, AColdStartFindsAFaceTheCascadeAnswersOnlyAtFifteenDegrees)
{
    const Score s = run("four", 7, 0, 20);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_EQ(s.missed, 0);
}

// A face tilted -19 degrees coming in at the top was in view, unshown, for three frames (91-93):
// the tilted scan's hit was thrown away while the detector's box (larger than the face) still
// reached a few pixels above the image. A hit's box may now reach beyond the edge by 12% of its
// side (TiltedScan).
TEST(FaceFailureModes, AFaceComingInTiltedAtTheTopIsShownAsItComesIntoView)
{
    const Score s = run("enter-leave", 7, 0, 100);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_LE(s.missed, 1);
}

// A face coming in at the left edge was wholly in view at frame 87 and shown only at 91: the
// budgeted scan goes over the whole search mask in order and reached the edge where it came in
// two frames later, and a detection needs two frames to be shown. The moving part of each edge's
// band is now scanned first in each frame's budget (EntryScan): found at 86, partly in view,
// and shown at 87, as it came wholly into view.
TEST(FaceFailureModes, AFaceComingInAtTheEdgeIsShownAsItComesWhollyIntoView)
{
    const Score s = run("enter-leave", 13, 0, 95, 0.0, 80);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_LE(s.missed, 1);
}

// A face coming in at the right was boxed by the cascade 40 px inward of its centre while partly
// out of view (frames 52-61), and the corners carried that box on after it was wholly in view:
// shown off the face until frame 72 (18 false faces, 10 missed). A track that came in at the
// edge is now re-centred, while young and near the edge, by a grouped scan of the image about
// it (TrackVerifier::recentre).
TEST(FaceFailureModes, AFaceComingInAtTheEdgeIsReCentredAsItComesIntoView)
{
    const Score s = run("enter-leave", 57, 40, 36);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_LE(s.missed, 1);
}

// A face found at a cold start turning in place (rolling a degree a frame, its centre still) was
// shown only after its roll had turned 4 degrees, at frame 6. The image's symmetry is now asked
// after every 2 degrees of tracked turn (StaticFaceRule), and it was shown at frame 3.
TEST(FaceFailureModes, AFaceTurningInPlaceIsShownWithinThreeFramesOfAColdStart)
{
    const Score s = run("rotate", 42, 0, 12);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_LE(s.missed, 1);
}

// A hit of the -25 degree scan on the lower part of a head and what is below it (its centre 0.7
// of the head's size below the head's) started a track that moved with the head and was shown
// for 24 frames (30-53). A turned scan's hit that close to a tracked face's centre is now not a
// new face (FaceTracker::match); an upright one still is (crossing faces come so close).
TEST(FaceFailureModes, ATiltedHitOnPartOfATrackedHeadIsNotANewFace)
{
    const Score s = run("two", 13, 0, 56);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_LE(s.missed, 1);
}

// A 52 px upright hit between two shown 82 px heads (its centre 0.70 and 0.66 of their size from
// theirs) started a track: its patch held what the two heads show of a face, so first-hit
// verification passed, their corners moved it, and it was shown, then held by its corners for the
// occluded grace (34 false faces, 107-140). An upright hit within the reach of two shown heads at
// once is now not a new face (FaceTracker::match).
TEST(FaceFailureModes, AHitBetweenTwoShownHeadsIsNotANewFace)
{
    const Score s = run("three", 57, 0, 116, 0.0, 100);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_LE(s.missed, 3);
}

// Two faces crossing pulled the corners of the upper one's box apart: the similarity fit grew it
// from 125 to 280 px over 30 frames (66-96) while the cascade missed it, and its corners, moving
// together, held it for the whole occluded grace: a false face, and the face under it hidden
// from the scan (excluded as tracked). A missed track is now held by its corners only while its
// box is within a quarter of the size it was last seen at (CornerFlow): it goes after the usual
// grace, and the face is found again.
TEST(FaceFailureModes, ABoxGrownByCrossingFacesIsNotHeldByItsCorners)
{
    const Score s = run("two", 13, 0, 100, 0.0, 60);
    EXPECT_LE(s.falsePositives, 7) << "frames" << s.log;  // graceFrames + 1 at most
    EXPECT_LE(s.missed, 16);
}

// The same crossing, before the cascade missed the face: first-hit verification still passed on
// part of it while the corners grew the box from 103 to 153 px over a face of 87 (frames 63-72):
// a false face and a missed one for 7 frames, then the track went and the face was unshown until
// the whole mask's scan found it again (frame 80; 16 misses in all). A box grown by more than 15%
// since a detection or a grouped scan last placed it is now found again by a grouped scan of the
// image about it at the size it was placed at (TrackVerifier::recentre), and its corners found
// afresh.
TEST(FaceFailureModes, ABoxGrownByCrossingFacesIsFoundAgainOnItsFace)
{
    const Score s = run("two", 13, 0, 85, 0.0, 60);
    EXPECT_EQ(s.falsePositives, 0) << "frames" << s.log;
    EXPECT_EQ(s.missed, 0);
}
