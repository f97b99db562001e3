#include "vision/scene_cut.hpp"

#include <gtest/gtest.h>

using vision::SceneCut;

namespace {

constexpr int kPixels = 10000;

int pixels(float fraction)
{
    return static_cast<int>(fraction * kPixels);
}

}  // namespace

TEST(SceneCut, TheDemoVideosCutIsOneAndTheFramesAfterItAreNot)
{
    // The foreground fractions of the demo video around its first cut (frame 98), as measured.
    SceneCut cut;
    for (int i = 0; i < SceneCut::kWarmUpFrames; ++i)
        EXPECT_FALSE(cut.update(pixels(0.27f), kPixels));
    for (const float f : {0.260f, 0.240f, 0.224f, 0.215f, 0.210f, 0.207f, 0.206f, 0.202f})
        EXPECT_FALSE(cut.update(pixels(f), kPixels)) << f;
    EXPECT_TRUE(cut.update(pixels(0.436f), kPixels));
    for (const float f : {0.429f, 0.422f, 0.415f, 0.408f, 0.400f})
        EXPECT_FALSE(cut.update(pixels(f), kPixels)) << f;
}

TEST(SceneCut, ARampIsNoCutHoweverHighItGoes)
{
    // The card leaving the centre after training: the background it covered shows, frame by
    // frame, up to 0.59.
    SceneCut cut;
    for (int i = 0; i < SceneCut::kWarmUpFrames; ++i)
        EXPECT_FALSE(cut.update(pixels(0.17f), kPixels));
    for (const float f : {0.170f, 0.207f, 0.278f, 0.356f, 0.424f, 0.473f, 0.506f, 0.532f, 0.586f})
        EXPECT_FALSE(cut.update(pixels(f), kPixels)) << f;
}

TEST(SceneCut, AJumpThatStaysSmallIsNoCut)
{
    // A person close to the camera starting to move: a jump, but most of the view stays still.
    SceneCut cut;
    for (int i = 0; i < SceneCut::kWarmUpFrames; ++i)
        EXPECT_FALSE(cut.update(pixels(0.02f), kPixels));
    EXPECT_FALSE(cut.update(pixels(0.30f), kPixels));
}

TEST(SceneCut, TheMotionModelsFirstFramesAreNeverACut)
{
    // The demo video's first frames: the model has seen one frame and marks noise as motion.
    SceneCut cut;
    EXPECT_FALSE(cut.update(pixels(0.0f), kPixels));
    EXPECT_FALSE(cut.update(pixels(0.41f), kPixels));
    for (int i = 2; i < SceneCut::kWarmUpFrames; ++i)
        EXPECT_FALSE(cut.update(pixels(i % 2 ? 0.0f : 0.9f), kPixels));
    EXPECT_FALSE(cut.update(pixels(0.1f), kPixels));
    EXPECT_TRUE(cut.update(pixels(0.9f), kPixels));
}

TEST(SceneCut, AfterAGapItStartsAgain)
{
    SceneCut cut;
    for (int i = 0; i < SceneCut::kWarmUpFrames; ++i)
        EXPECT_FALSE(cut.update(pixels(0.1f), kPixels));
    EXPECT_FALSE(cut.update(-1, kPixels));  // a frame the motion stage could not use
    EXPECT_FALSE(cut.update(pixels(0.9f), kPixels));
    cut.reset();
    EXPECT_FALSE(cut.update(pixels(0.1f), kPixels));
    EXPECT_FALSE(cut.update(pixels(0.9f), kPixels));
    EXPECT_FALSE(cut.update(pixels(0.9f), 0));
}
