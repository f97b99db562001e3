// cardgen's hard family: each member switches on its own difficulty over the same seed's card,
// background and path; the seed varies colour and background; the difficulties are there.

#include "hard_scenarios.hpp"

#include "scenarios.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

namespace {

using cardgen::FrameSpec;
using cardgen::Scenario;

const cv::Size kSize(720, 480);
constexpr int kFrames = 240;

bool outside(vision::Point2f p)
{
    return p.x < 0 || p.y < 0 || p.x > kSize.width - 1 || p.y > kSize.height - 1;
}

TEST(HardScenarios, SeedsPickColoursAndBackgrounds)
{
    std::set<std::string> colours, backgrounds;
    for (std::uint32_t seed = 1; seed <= 12; ++seed) {
        const Scenario s("hard", kSize, kFrames, seed);
        const FrameSpec f = s.frame(1);
        colours.insert(std::to_string(f.paint.red) + "," + std::to_string(f.paint.green));
        backgrounds.insert(s.backgrounds().front());
        EXPECT_EQ(s.backgrounds().size(), cardgen::hardBackgrounds().size());
        EXPECT_FALSE(s.choices().empty());
    }
    EXPECT_GE(colours.size(), 4u);
    EXPECT_GE(backgrounds.size(), 6u);
}

TEST(HardScenarios, MembersShareTheSeedsCardAndPath)
{
    for (const char* member :
         {"hard_light", "hard_shading", "hard_noise", "hard_occluder", "hard_distractors"}) {
        const Scenario base("hard_light", kSize, kFrames, 5), other(member, kSize, kFrames, 5);
        for (int i = 0; i < kFrames; i += 17) {
            const FrameSpec a = base.frame(i), b = other.frame(i);
            EXPECT_EQ(a.paint.red, b.paint.red);
            for (int k = 0; k < 4; ++k)
                EXPECT_EQ(a.quad[k].x, b.quad[k].x) << member << " frame " << i;
        }
    }
}

TEST(HardScenarios, EachMemberHasItsDifficultyAndOnlyIt)
{
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        auto count = [&](const char* name, auto test) {
            const Scenario s(name, kSize, kFrames, seed);
            int n = 0;
            for (int i = 1; i < kFrames; ++i)
                n += test(s.frame(i));
            return n;
        };
        const auto clipping = [](const FrameSpec& f) { return f.gain > 1.4; };
        const auto dim = [](const FrameSpec& f) { return f.gain < 0.7; };
        const auto hand = [](const FrameSpec& f) { return f.hand; };
        const auto cornerOut = [](const FrameSpec& f) {
            return std::count_if(f.quad.begin(), f.quad.end(), outside) > 0;
        };
        const auto noisy = [](const FrameSpec& f) { return f.noiseSigma >= 4.0; };
        const auto shaded = [](const FrameSpec& f) {
            return std::hypot(f.paint.gradientU, f.paint.gradientV) >= 0.15;
        };
        EXPECT_GT(count("hard_light", clipping), 10) << seed;
        EXPECT_GT(count("hard_light", dim), 10) << seed;
        EXPECT_EQ(count("hard_motion", clipping), 0) << seed;
        EXPECT_GT(count("hard_occluder", hand), 40) << seed;
        EXPECT_EQ(count("hard_light", hand), 0) << seed;
        EXPECT_GT(count("hard_corner", cornerOut), 20) << seed;
        EXPECT_EQ(count("hard_noise", noisy), kFrames - 1) << seed;
        EXPECT_EQ(count("hard_light", noisy), 0) << seed;
        EXPECT_EQ(count("hard_shading", shaded), kFrames - 1) << seed;
        EXPECT_EQ(count("hard_occluder", shaded), 0) << seed;
        for (const char* all : {"hard"}) {
            EXPECT_GT(count(all, clipping), 0) << seed;
            EXPECT_GT(count(all, hand), 0) << seed;
            EXPECT_GT(count(all, noisy), 0) << seed;
        }
    }
}

TEST(HardScenarios, TheHandCoversTheCardAndTheCornerGoesOutByTheSeedsDepth)
{
    const Scenario s("hard_occluder", kSize, kFrames, 3);
    int over = 0;
    for (int i = 1; i < kFrames; ++i) {
        const FrameSpec f = s.frame(i);
        if (!f.hand)
            continue;
        // The palm centre inside the card's outline at some point of the reach.
        bool inside = true;
        for (int k = 0; k < 4; ++k) {
            const vision::Point2f a = f.quad[k], b = f.quad[(k + 1) % 4];
            inside = inside &&
                     (b.x - a.x) * (f.handPose.y - a.y) - (b.y - a.y) * (f.handPose.x - a.x) >= 0;
        }
        over += inside;
        EXPECT_GT(f.handPose.armLength, 0.0);
    }
    EXPECT_GT(over, 10);

    const cardgen::HardScene corner("hard_corner", kSize, kFrames, 3);
    const int k = corner.plan().corner;
    double deepest = 0.0;
    for (int i = 1; i < kFrames; ++i) {
        const vision::Point2f p = corner.frame(i).quad[k];
        const double out =
            std::max({-p.x, -p.y, p.x - (kSize.width - 1), p.y - (kSize.height - 1)});
        deepest = std::max(deepest, out);
    }
    EXPECT_NEAR(deepest, corner.plan().cornerDepth, 1.0);
}

TEST(HardScenarios, TheCardColouredPatchNeverComesNearTheCard)
{
    int placed = 0;
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        const cardgen::HardScene s("hard", kSize, kFrames, seed);
        if (!s.plan().havePatch)
            continue;
        ++placed;
        for (int i = 1; i < kFrames; ++i) {
            const FrameSpec f = s.frame(i);
            ASSERT_TRUE(f.distractor);
            // Every corner of the patch at least 16 px outside the card along some card edge.
            for (const auto& p : f.distractorQuad) {
                double d = 1e9;
                for (int k = 0; k < 4; ++k) {
                    const vision::Point2f a = f.quad[k], b = f.quad[(k + 1) % 4];
                    d = std::min(d, static_cast<double>((b.x - a.x) * (p.y - a.y) -
                                                        (b.y - a.y) * (p.x - a.x)) /
                                        std::hypot(b.x - a.x, b.y - a.y));
                }
                EXPECT_LT(d, -15.9) << "seed " << seed << " frame " << i;
            }
        }
    }
    EXPECT_GE(placed, 3);
}

}  // namespace
