// The training check: the card filling the region passes; a wall, a mixture of colours, a dark
// room, or a frame with no chromaticity fail, each on its own measurement.

#include "vision/card_training_check.hpp"

#include "vision/card_stage.hpp"
#include "vision/chromaticity.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>

using namespace vision;

namespace {

constexpr int kW = 64, kH = 48;

struct Scene {
    ImageBuffer rgb{kW, kH, PixelFormat::RGB24};
    ImageBuffer r{kW, kH, PixelFormat::Gray8}, g{kW, kH, PixelFormat::Gray8},
        b{kW, kH, PixelFormat::Gray8};

    /// Paints every pixel with colour(x, y) plus +-3 of deterministic noise, then converts.
    explicit Scene(const std::function<void(int, int, std::uint8_t*)>& colour)
    {
        const ImageView v = rgb.view();
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                std::uint8_t* p = v.row(y) + x * 3;
                colour(x, y, p);
                const int n = static_cast<int>((x * 7 + y * 13) % 7) - 3;
                for (int c = 0; c < 3; ++c)
                    p[c] = static_cast<std::uint8_t>(std::clamp(p[c] + n, 0, 255));
            }
        static const auto table = std::make_unique<ChromaticityTable>();
        EXPECT_TRUE(convertChromaticity(*table, rgb.view(), planes()));
    }
    ChromaticityPlanes planes() { return {r.view(), g.view(), b.view()}; }
    CardTrainingCheck check() { return checkCardTrainingRegion(rgb.view(), planes(), centre()); }
    static Rect centre() { return centralRegion({kW, kH}, 0.5f); }
};

void fill(std::uint8_t* p, int r, int g, int b)
{
    p[0] = static_cast<std::uint8_t>(r);
    p[1] = static_cast<std::uint8_t>(g);
    p[2] = static_cast<std::uint8_t>(b);
}

}  // namespace

TEST(CardTrainingCheck, AGreenCardFillingTheCentrePasses)
{
    Scene s([](int, int, std::uint8_t* p) { fill(p, 40, 172, 76); });
    const CardTrainingCheck c = s.check();
    EXPECT_TRUE(c.ok()) << c.sigma << " " << c.saturation << " " << c.brightness;
    EXPECT_LT(c.sigma, 4.f);
    EXPECT_GT(c.saturation, 60.f);
}

TEST(CardTrainingCheck, AGreyWallIsNotSaturated)
{
    Scene s([](int, int, std::uint8_t* p) { fill(p, 190, 185, 170); });
    const CardTrainingCheck c = s.check();
    EXPECT_FALSE(c.ok());
    EXPECT_TRUE(c.uniform);
    EXPECT_FALSE(c.saturated) << c.saturation;
    EXPECT_TRUE(c.lit);
}

TEST(CardTrainingCheck, TwoColoursAreNotUniform)
{
    Scene s([](int x, int, std::uint8_t* p) {
        if (x < kW / 2)
            fill(p, 40, 172, 76);
        else
            fill(p, 200, 40, 60);
    });
    const CardTrainingCheck c = s.check();
    EXPECT_FALSE(c.ok());
    EXPECT_FALSE(c.uniform) << c.sigma;
}

TEST(CardTrainingCheck, ADarkRoomIsNotLit)
{
    Scene s([](int, int, std::uint8_t* p) { fill(p, 6, 8, 4); });
    const CardTrainingCheck c = s.check();
    EXPECT_FALSE(c.ok());
    EXPECT_FALSE(c.lit) << c.brightness;
}

TEST(CardTrainingCheck, NoPlanesFailEverything)
{
    Scene s([](int, int, std::uint8_t* p) { fill(p, 40, 172, 76); });
    EXPECT_FALSE(checkCardTrainingRegion(s.rgb.view(), {}, Scene::centre()).ok());
}

TEST(CardTrainingCheck, TheStageRefusesAWallAndKeepsThePreviousColour)
{
    Scene card([](int, int, std::uint8_t* p) { fill(p, 40, 172, 76); });
    Scene wall([](int, int, std::uint8_t* p) { fill(p, 190, 185, 170); });
    CardStage stage({kW, kH});
    auto run = [&](Scene& s) {
        FrameState state;
        state.frame.image = s.rgb.view();
        state.chroma = s.planes();
        state.valid = true;
        stage.requestTraining(0.5f);
        stage.process(state);
    };
    run(card);
    ASSERT_TRUE(stage.lastTrainingSucceeded());
    const CardColorModel trained = stage.tracker().trainedModel();
    run(wall);
    EXPECT_FALSE(stage.lastTrainingSucceeded());
    EXPECT_FALSE(stage.lastTrainingCheck().saturated);
    EXPECT_EQ(stage.tracker().trainedModel().mean[1], trained.mean[1]) << "the card's colour stays";
    stage.tracker().forgetModel();
    EXPECT_FALSE(stage.tracker().trainedModel().valid);
    EXPECT_EQ(stage.tracker().observation().state, CardState::Untrained);
}
