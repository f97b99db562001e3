// The matching rules of mirror-eval detect and track: the detect rule (eyes and mouth centre
// inside, side within a factor 2 of the face's scale), one-to-one pairings, IoU, and the
// landmark box of a detector's square.

#include "face_match.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace mirror_eval;

/// An upright face with eye-mouth distance 20 centred at (100, 100).
LandmarkFace face(float cx = 100.f, float cy = 100.f)
{
    LandmarkFace f;
    f.leftEye = {cx - 10, cy - 10};
    f.rightEye = {cx + 10, cy - 10};
    f.nose = {cx, cy};
    f.mouthLeft = {cx - 6, cy + 10};
    f.mouthCentre = {cx, cy + 10};
    f.mouthRight = {cx + 6, cy + 10};
    return f;
}

TEST(FaceMatch, IouOfBoxes)
{
    EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {0, 0, 10, 10}), 1.f);
    EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {5, 0, 10, 10}), 50.f / 150.f);
    EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {10, 0, 10, 10}), 0.f);
    EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {2, 2, 5, 5}), 25.f / 100.f);
}

TEST(FaceMatch, DetectRuleNeedsEyesMouthAndScale)
{
    const LandmarkFace f = face();  // scale 2.2 x 20 = 44: sides 22..88 pass
    EXPECT_TRUE(detectionMatchesFace({78, 78, 44, 44}, f));
    EXPECT_TRUE(detectionMatchesFace({88, 88, 24, 24}, f));     // tight, eyes on the edge
    EXPECT_FALSE(detectionMatchesFace({89, 89, 20, 20}, f));    // misses the eyes
    EXPECT_FALSE(detectionMatchesFace({50, 50, 100, 100}, f));  // 100 > 88: too big
    EXPECT_TRUE(detectionMatchesFace({56, 56, 88, 88}, f));     // exactly twice
    EXPECT_FALSE(detectionMatchesFace({95, 80, 44, 44}, f));    // left eye outside
    EXPECT_FALSE(detectionMatchesFace({78, 60, 44, 44}, f));    // mouth centre outside
    EXPECT_NE(detectRuleText().find("x2 of 2.2 x eye-mouth"), std::string::npos);
}

TEST(FaceMatch, DetectionsPairOneToOneClosestFirst)
{
    const LandmarkFace a = face(100, 100), b = face(300, 100);
    const LandmarkFace* faces[] = {&a, &b};
    // Two boxes on face a (the second closer), one on b, one on nothing.
    const vision::Rect boxes[] = {
        {80, 80, 44, 44}, {78, 78, 44, 44}, {278, 78, 44, 44}, {500, 500, 44, 44}};
    const Pairing p = pairDetections(boxes, faces);
    EXPECT_EQ(p.matches, 2);
    EXPECT_EQ(p.truthOfCandidate[0], -1);  // the duplicate is a false positive
    EXPECT_EQ(p.truthOfCandidate[1], 0);
    EXPECT_EQ(p.truthOfCandidate[2], 1);
    EXPECT_EQ(p.truthOfCandidate[3], -1);
    EXPECT_EQ(p.candidateOfTruth[0], 1);
    EXPECT_EQ(p.candidateOfTruth[1], 2);
}

TEST(FaceMatch, IouPairingHighestFirstAndThreshold)
{
    const BoxF truths[] = {{0, 0, 100, 100}, {200, 0, 100, 100}};
    const BoxF shown[] = {{10, 0, 100, 100}, {0, 0, 100, 100}, {260, 0, 100, 100}};
    const Pairing p = pairByIou(shown, truths, 0.5f);
    EXPECT_EQ(p.truthOfCandidate[1], 0);   // IoU 1 wins over 0.82
    EXPECT_EQ(p.truthOfCandidate[0], -1);  // truth 0 already taken
    EXPECT_EQ(p.truthOfCandidate[2], -1);  // IoU 0.25 < 0.5
    EXPECT_EQ(p.candidateOfTruth[1], -1);
    EXPECT_EQ(p.matches, 1);
}

TEST(FaceMatch, AFaceEnteringIsMatchedByItsPartInView)
{
    const vision::Size frame{640, 480};
    EXPECT_TRUE(wholeInFrame({0.f, 0.f, 640.f, 480.f}, frame));
    // A face entering on the right: 86 px box, 20 px of it outside.
    const BoxF entering{574.f, 100.f, 86.f, 86.f};
    EXPECT_FALSE(wholeInFrame(entering, frame));
    const BoxF part = partInView(entering, frame);
    EXPECT_FLOAT_EQ(part.x, 574.f);
    EXPECT_FLOAT_EQ(part.width, 66.f);
    EXPECT_FLOAT_EQ(part.height, 86.f);
    // The detector boxes the part in view: below 0.5 against the whole box, above it against the
    // part.
    const BoxF shown{580.f, 115.f, 56.f, 56.f};
    EXPECT_LT(iou(shown, entering), 0.5f);
    EXPECT_GE(iou(shown, part), 0.5f);
    const BoxF gone = partInView({700.f, 100.f, 50.f, 50.f}, frame);
    EXPECT_FLOAT_EQ(gone.width, 0.f);
}

TEST(FaceMatch, LandmarkConventionBox)
{
    // Upright: side 0.805 x 100, centre 0.125 x 100 below (100, 100).
    const BoxF b = landmarkConventionBox({100, 100}, 100.f, 0.f);
    EXPECT_FLOAT_EQ(b.width, 80.5f);
    EXPECT_FLOAT_EQ(b.height, 80.5f);
    EXPECT_NEAR(b.x + 40.25f, 100.f, 1e-4);
    EXPECT_NEAR(b.y + 40.25f, 112.5f, 1e-4);
    // Rolled 90 degrees clockwise (the chin on the left): dropped towards -x.
    const BoxF r = landmarkConventionBox({100, 100}, 100.f, 90.f);
    EXPECT_NEAR(r.x + 40.25f, 87.5f, 1e-4);
    EXPECT_NEAR(r.y + 40.25f, 100.f, 1e-4);
}

TEST(FaceMatch, BoundingBoxAndSquare)
{
    const vision::Point2f p[] = {{1, 5}, {3, 2}, {-1, 4}};
    const BoxF b = boundingBox(p);
    EXPECT_FLOAT_EQ(b.x, -1.f);
    EXPECT_FLOAT_EQ(b.y, 2.f);
    EXPECT_FLOAT_EQ(b.width, 4.f);
    EXPECT_FLOAT_EQ(b.height, 3.f);
    const BoxF s = squareAbout({10, 20}, 8);
    EXPECT_FLOAT_EQ(s.x, 6.f);
    EXPECT_FLOAT_EQ(s.y, 16.f);
    EXPECT_TRUE(contains(s, {14, 24}));
    EXPECT_FALSE(contains(s, {14.1f, 24}));
}

}  // namespace
