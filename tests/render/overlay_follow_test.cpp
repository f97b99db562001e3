// Overlays that follow the fitted face's animation units ([[overlay.follow]], FORMAT.md): how the
// catalogue declares them, what it refuses, and the shipped moustache and goatee moving with the
// upper lip and the jaw on screen.
#include "gl_test_context.hpp"
#include "overlay_test_scene.hpp"
#include "render/face_overlay_layer.hpp"
#include "render/overlay_catalogue.hpp"
#include "render/renderer.hpp"
#include "test_paths.hpp"
#include "vision/face_fit.hpp"
#include "vision/head_pose.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace {

using render::OverlayCatalogue;
using testing_support::DepthAttachment;
using testing_support::GlTestContext;
using testing_support::sourceDir;

std::size_t unitIndex(std::string_view name)
{
    const auto& names = vision::kFaceFitAnimationNames;
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

// Loads `follows` (TOML of [[overlay.follow]] tables) on a one-mesh overlay beside a copy of the
// test glasses; the error line, or "" when it loads (then *out holds the overlay).
std::string loadWithFollows(const std::string& folder, const std::string& follows,
                            render::Overlay* out = nullptr)
{
    const std::string dir = testing_support::freshOutputDir("overlay_follow_" + folder);
    std::filesystem::copy_file(sourceDir() + "/tests/data/overlays/test_glasses.obj",
                               dir + "/glasses.obj");
    std::ofstream(dir + "/catalogue.toml") << "version = 1\n[[overlay]]\nname = \"m\"\n"
                                              "kind = \"other\"\nanchor = \"upper_lip\"\n"
                                              "measure = \"face_width\"\n"
                                              "  [[overlay.mesh]]\n  obj = \"glasses.obj\"\n"
                                           << follows;
    try {
        const OverlayCatalogue c = OverlayCatalogue::load(dir + "/catalogue.toml");
        if (out != nullptr)
            *out = c[0];
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

TEST(OverlayFollow, TheCatalogueDeclaresWhichUnitsAnOverlayFollowsAndHow)
{
    render::Overlay o;
    ASSERT_EQ(loadWithFollows("good",
                              "  [[overlay.follow]]\n  unit = \"jaw_drop\"\n"
                              "  offset = [0.0, -0.02, 0.0]\n"
                              "  [[overlay.follow]]\n  unit = \"lip_stretcher\"\n"
                              "  stretch = [0.4, 0.0, 0.0]\n  rotation = [0.0, 0.0, 5.0]\n",
                              &o),
              "");
    EXPECT_EQ(o.anchor, render::OverlayAnchor::UpperLip);
    ASSERT_EQ(o.follows.size(), 2u);
    EXPECT_EQ(o.follows[0].unit, static_cast<int>(unitIndex("jaw_drop")));
    EXPECT_FLOAT_EQ(o.follows[0].offset[1], -0.02f);
    EXPECT_EQ(o.follows[1].unit, static_cast<int>(unitIndex("lip_stretcher")));
    EXPECT_FLOAT_EQ(o.follows[1].stretch[0], 0.4f);
    EXPECT_FLOAT_EQ(o.follows[1].rotationDegrees[2], 5.f);
}

TEST(OverlayFollow, ABadFollowIsOneLineNamingItsLineAndWhy)
{
    const std::string unit = loadWithFollows("unit", "  [[overlay.follow]]\n  unit = \"smile\"\n");
    EXPECT_NE(unit.find("catalogue.toml:10"), std::string::npos) << unit;
    EXPECT_NE(unit.find("follow unit must be one of jaw_drop|lip_stretcher|"), std::string::npos)
        << unit;
    EXPECT_NE(unit.find("not 'smile'"), std::string::npos) << unit;
    EXPECT_EQ(unit.find('\n'), std::string::npos);

    const std::string twice =
        loadWithFollows("twice",
                        "  [[overlay.follow]]\n  unit = \"jaw_drop\"\n  [[overlay.follow]]\n"
                        "  unit = \"jaw_drop\"\n");
    EXPECT_NE(twice.find("a second follow of unit 'jaw_drop'"), std::string::npos) << twice;

    const std::string key =
        loadWithFollows("key", "  [[overlay.follow]]\n  unit = \"jaw_drop\"\n  scale = 2\n");
    EXPECT_NE(key.find("unknown follow key 'scale'"), std::string::npos) << key;

    const std::string range = loadWithFollows(
        "range", "  [[overlay.follow]]\n  unit = \"jaw_drop\"\n  stretch = [9.0, 0.0, 0.0]\n");
    EXPECT_NE(range.find("stretch values must be in [-2, 2]"), std::string::npos) << range;

    const std::string none =
        loadWithFollows("missing", "  [[overlay.follow]]\n  offset = [0, 0, 0]\n");
    EXPECT_NE(none.find("missing key 'unit'"), std::string::npos) << none;
}

// The bounding box of the pixels the overlay changed on a uniform grey frame.
struct Extent {
    int left = 1 << 20, top = 1 << 20, right = -1, bottom = -1;
    int width() const { return right - left + 1; }
    bool empty() const { return right < left; }
};

class OverlayFollowOnScreen : public ::testing::Test {
protected:
    static constexpr int kWidth = 640;
    static constexpr int kHeight = 480;

    void SetUp() override
    {
        const std::string path = sourceDir() + "/assets/overlays/catalogue.toml";
        if (!std::filesystem::exists(path))
            GTEST_SKIP() << "no " << path;
        catalogue = OverlayCatalogue::load(path);
        for (int y = 0; y < kHeight; ++y)
            std::memset(video.view().row(y), 128, static_cast<std::size_t>(kWidth) * 3);
    }

    // Where `overlay` is drawn on a frontal fitted face with these animation values (or,
    // without `fitted`, on the face's box alone).
    Extent drawn(const char* overlay, std::array<float, vision::kAamAnimationUnits> animation,
                 bool fitted = true)
    {
        render::Renderer renderer({kWidth, kHeight}, vision::PixelFormat::RGB24,
                                  render::RendererOptions{false, {}, false});
        render::FaceOverlayLayer layer(catalogue);
        renderer.addLayer(&layer);
        vision::TrackedFace face;
        face.id = 1;
        face.centre = {320.f, 220.f};
        face.size = 220.f;
        face.state = vision::FaceState::Confirmed;
        vision::FaceFit fit;
        fit.faceSize = face.size;
        fit.eyeMidpoint = {face.centre.x,
                           face.centre.y - vision::kEyeMidpointAboveBoxCentre * face.size};
        render::FaceDrawing d;
        d.face = face;
        d.overlay = catalogue.find(overlay);
        d.hasPose = fitted;
        d.pose =
            vision::headPoseFromFit(fit, {{kWidth, kHeight}, layer.options().verticalFovDegrees},
                                    layer.options().head.faceWidthMetres);
        d.animation = animation;
        EXPECT_GE(d.overlay, 0) << overlay;
        EXPECT_TRUE(layer.setFaces({&d, 1}));
        EXPECT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr)) << renderer.lastError();
        gl.read();
        Extent e;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const testing_support::Rgba p = gl.pixel(x, y);
                if (std::abs(p.r - 128) + std::abs(p.g - 128) + std::abs(p.b - 128) > 30) {
                    e.left = std::min(e.left, x);
                    e.right = std::max(e.right, x);
                    e.top = std::min(e.top, y);
                    e.bottom = std::max(e.bottom, y);
                }
            }
        return e;
    }

    static std::array<float, vision::kAamAnimationUnits> with(std::string_view unit, float value)
    {
        std::array<float, vision::kAamAnimationUnits> a{};
        a[unitIndex(unit)] = value;
        return a;
    }

    GlTestContext gl{kWidth, kHeight};
    DepthAttachment depth{kWidth, kHeight};
    OverlayCatalogue catalogue;
    vision::ImageBuffer video{kWidth, kHeight, vision::PixelFormat::RGB24};
};

TEST_F(OverlayFollowOnScreen, TheMoustacheRisesAndWidensWithTheUpperLip)
{
    const Extent neutral = drawn("moustache", {});
    ASSERT_FALSE(neutral.empty());
    // Under the eyes (the eye midpoint is at y = 193.6) and centred on the face.
    EXPECT_GT(neutral.top, 230);
    EXPECT_NEAR(0.5 * (neutral.left + neutral.right), 320.0, 2.0);

    const Extent raised = drawn("moustache", with("upper_lip_raiser", 1.f));
    EXPECT_LE(raised.top, neutral.top - 4) << "5.9 mm up on a 0.15 m face 220 px wide";
    EXPECT_LE(raised.bottom, neutral.bottom - 4);
    EXPECT_NEAR(raised.width(), neutral.width(), 2);

    const Extent stretched = drawn("moustache", with("lip_stretcher", 1.f));
    EXPECT_GT(stretched.width(), 1.25 * neutral.width());

    const Extent boxOnly = drawn("moustache", with("upper_lip_raiser", 1.f), false);
    EXPECT_EQ(boxOnly.top, drawn("moustache", {}, false).top)
        << "without a fit the values are not the face's: nothing follows them";
}

TEST_F(OverlayFollowOnScreen, TheGoateeDropsWithTheJawAndAWildValueIsHeldInBounds)
{
    const Extent closed = drawn("goatee", {});
    ASSERT_FALSE(closed.empty());
    const Extent open = drawn("goatee", with("jaw_drop", 1.f));
    EXPECT_GE(open.top, closed.top + 10) << "18 mm down on a 0.15 m face 220 px wide";

    const Extent wild = drawn("goatee", with("jaw_drop", 1e9f));
    const Extent limit = drawn("goatee", with("jaw_drop", 1.5f));
    EXPECT_EQ(wild.top, limit.top);
    const Extent notANumber = drawn("goatee", with("jaw_drop", std::nanf("")));
    EXPECT_EQ(notANumber.top, closed.top);
}

}  // namespace
