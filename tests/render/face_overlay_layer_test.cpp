#include "render/face_overlay_layer.hpp"

#include "alloc_counter.hpp"
#include "gl_test_context.hpp"
#include "overlay_test_scene.hpp"
#include "platform/image_file.hpp"
#include "platform/png_writer.hpp"
#include "render/head_model.hpp"
#include "render/overlay_catalogue.hpp"
#include "render/renderer.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace {

using render::FaceOverlayLayer;
using render::FaceOverlayOptions;
using render::OverlayCatalogue;
using render::Renderer;
using render::RendererOptions;
using testing_support::DepthAttachment;
using testing_support::GlTestContext;
using testing_support::Rgba;
using testing_support::sharedData;
using testing_support::sourceDir;
using vision::PixelFormat;

vision::ImageBuffer greyFrame(int width, int height)
{
    vision::ImageBuffer image(width, height, PixelFormat::RGB24);
    for (int y = 0; y < height; ++y)
        std::memset(image.view().row(y), 128, static_cast<std::size_t>(width) * 3);
    return image;
}

// The top-down RGB pixels of the context's last read, a rectangle of it.
std::vector<std::uint8_t> crop(const GlTestContext& gl, int x0, int y0, int width, int height)
{
    std::vector<std::uint8_t> out(static_cast<std::size_t>(width * height * 3));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Rgba p = gl.pixel(x0 + x, y0 + y);
            std::uint8_t* o = &out[static_cast<std::size_t>((y * width + x) * 3)];
            o[0] = static_cast<std::uint8_t>(p.r);
            o[1] = static_cast<std::uint8_t>(p.g);
            o[2] = static_cast<std::uint8_t>(p.b);
        }
    return out;
}

// Level 6 for the approved pictures kept in the repository; 1 for snapshots (fast).
bool writePng(const std::string& path, const std::vector<std::uint8_t>& rgb, int width, int height,
              int level = 1)
{
    platform::PngWriter writer(std::size_t{16} << 20, level);
    return writer.write(path.c_str(), rgb.data(), width, height,
                        static_cast<std::size_t>(width) * 3);
}

/// `face` wearing catalogue entry `overlay`, as the layer is given it for one frame.
render::FaceDrawing wearing(const vision::TrackedFace& face, int overlay, float alpha = 1.f,
                            float brightness = 1.f)
{
    render::FaceDrawing d;
    d.face = face;
    d.overlay = overlay;
    d.alpha = alpha;
    d.brightness = brightness;
    return d;
}

struct Counts {
    int red = 0;    // the left temple of the test glasses (x < 0, the image left when upright)
    int green = 0;  // the right temple
};

Counts countTemplePixels(const GlTestContext& gl)
{
    Counts c;
    for (int y = 0; y < gl.height(); ++y)
        for (int x = 0; x < gl.width(); ++x) {
            const Rgba p = gl.pixel(x, y);
            if (p.r > p.g + 40 && p.r > p.b + 40)
                ++c.red;
            if (p.g > p.r + 40 && p.g > p.b + 40)
                ++c.green;
        }
    return c;
}

class FaceOverlayTest : public ::testing::Test {
protected:
    static constexpr int kWidth = 640;
    static constexpr int kHeight = 480;

    GlTestContext gl{kWidth, kHeight};
    DepthAttachment depth{kWidth, kHeight};
    OverlayCatalogue testCatalogue =
        OverlayCatalogue::load(sourceDir() + "/tests/data/overlays/catalogue.toml");

    static vision::TrackedFace centredFace(float size = 200.f, float roll = 0.f)
    {
        vision::TrackedFace face;
        face.id = 7;
        face.centre = {320.f, 250.f};
        face.size = size;
        face.rollDegrees = roll;
        face.state = vision::FaceState::Confirmed;
        return face;
    }
};

TEST_F(FaceOverlayTest, TheFarTempleArmHidesBehindTheHeadWhenItTurns)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, RendererOptions{false, {}, false});
    FaceOverlayLayer layer(testCatalogue);
    renderer.addLayer(&layer);
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    const vision::TrackedFace face = centredFace();
    render::FaceDrawing glasses = wearing(face, testCatalogue.find("test_glasses"));

    const std::string out = testing_support::freshOutputDir("overlay_occlusion");
    auto render = [&](float yawDegrees, bool proxy) {
        FaceOverlayOptions options = layer.options();
        options.headProxy = proxy;
        layer.setOptions(options);
        vision::HeadPose pose =
            vision::headPoseFromFace(face, {{kWidth, kHeight}, options.verticalFovDegrees});
        // Yaw: about the head's vertical axis; +60 turns its +x (green) side towards the camera.
        pose.rotation = pose.rotation * Eigen::AngleAxisf(yawDegrees * 3.14159265f / 180.f,
                                                          Eigen::Vector3f::UnitY())
                                            .toRotationMatrix();
        glasses.hasPose = true;
        glasses.pose = pose;
        EXPECT_TRUE(layer.setFaces({&glasses, 1}));
        EXPECT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr)) << renderer.lastError();
        EXPECT_STREQ(layer.lastError(), "");
        gl.read();
        // Pictures of the proof, e.g. yaw_60_head.png, for people to look at.
        writePng(out + "/yaw_" + std::to_string(static_cast<int>(yawDegrees)) +
                     (proxy ? "_head.png" : "_no_head.png"),
                 crop(gl, 0, 0, kWidth, kHeight), kWidth, kHeight);
        return countTemplePixels(gl);
    };

    const Counts frontal = render(0.f, true);
    EXPECT_GT(frontal.red, 20) << "both arms show beside a face looking at the camera";
    EXPECT_GT(frontal.green, 20);

    // Yaw 60: the near (green) arm is seen from the side, the far (red) one is behind the head.
    const Counts turned = render(60.f, true);
    const Counts noHead = render(60.f, false);
    EXPECT_GT(turned.green, 3 * frontal.green);
    EXPECT_EQ(turned.green, noHead.green) << "the near arm is not hidden";
    EXPECT_GT(noHead.red, 200) << "without the head proxy the far arm shows";
    EXPECT_LE(turned.red, 2) << "with it, the far arm is hidden";

    const Counts otherWay = render(-60.f, true);
    const Counts otherWayNoHead = render(-60.f, false);
    EXPECT_GT(otherWay.red, 3 * frontal.red);
    EXPECT_GT(otherWayNoHead.green, 200);
    EXPECT_LE(otherWay.green, 2);
    std::printf(
        "temple pixels red/green: frontal %d/%d, yaw 60 %d/%d (no head %d/%d), "
        "yaw -60 %d/%d (no head %d/%d)\n",
        frontal.red, frontal.green, turned.red, turned.green, noHead.red, noHead.green,
        otherWay.red, otherWay.green, otherWayNoHead.red, otherWayNoHead.green);
}

TEST_F(FaceOverlayTest, AFittedHeadsFullPoseTurnsTheGlassesAndTheHeadHidesTheFarArm)
{
    // §5.3: the pose of an AAM fit (headPoseFromFit), as the firmware gives it for a face whose
    // fit holds. Untwisted and unturned it is the box's pose; turned by the fit's yaw (positive:
    // the nose to image right, the person's right, red, side towards the camera), the far arm
    // hides behind the head proxy posed with it.
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, RendererOptions{false, {}, false});
    FaceOverlayLayer layer(testCatalogue);
    renderer.addLayer(&layer);
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    const vision::TrackedFace face = centredFace();
    const vision::CameraModel camera{{kWidth, kHeight}, layer.options().verticalFovDegrees};
    auto render = [&](const render::FaceDrawing& drawing) {
        EXPECT_TRUE(layer.setFaces({&drawing, 1}));
        EXPECT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr)) << renderer.lastError();
        gl.read();
        return countTemplePixels(gl);
    };
    vision::FaceFit fit;
    fit.faceSize = face.size;
    fit.eyeMidpoint = {face.centre.x, face.centre.y - vision::kEyeMidpointAboveBoxCentre * face.size};
    auto fitted = [&](float yaw, float pitch) {
        render::FaceDrawing d = wearing(face, testCatalogue.find("test_glasses"));
        fit.yawDegrees = yaw;
        fit.pitchDegrees = pitch;
        d.hasPose = true;
        d.pose = vision::headPoseFromFit(fit, camera, layer.options().head.faceWidthMetres);
        return d;
    };
    const Counts box = render(wearing(face, testCatalogue.find("test_glasses")));
    const Counts frontal = render(fitted(0.f, 0.f));
    EXPECT_EQ(frontal.red, box.red) << "an unturned fit draws as the box";
    EXPECT_EQ(frontal.green, box.green);
    const Counts right = render(fitted(60.f, 0.f));
    EXPECT_GT(right.red, 3 * frontal.red) << "the near (red) arm seen from the side";
    EXPECT_LE(right.green, 2) << "the far (green) arm behind the head";
    const Counts left = render(fitted(-60.f, 0.f));
    EXPECT_GT(left.green, 3 * frontal.green);
    EXPECT_LE(left.red, 2);
    std::printf("temple pixels red/green by the fitted pose: frontal %d/%d, yaw 60 %d/%d, "
                "yaw -60 %d/%d\n",
                frontal.red, frontal.green, right.red, right.green, left.red, left.green);
}

TEST_F(FaceOverlayTest, MirroredIsTheUnmirroredPictureFlipped)
{
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    vision::TrackedFace face = centredFace(160.f, 20.f);
    face.centre = {260.f, 270.f};
    std::vector<std::uint8_t> pictures[2];
    for (int mirror = 0; mirror < 2; ++mirror) {
        Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24,
                          RendererOptions{mirror == 1, {}, false});
        FaceOverlayLayer layer(testCatalogue);
        renderer.addLayer(&layer);
        const render::FaceDrawing hat = wearing(face, testCatalogue.find("test_hat"));
        ASSERT_TRUE(layer.setFaces({&hat, 1}));
        ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr));
        gl.read();
        pictures[mirror] = crop(gl, 0, 0, kWidth, kHeight);
    }
    int changed = 0;
    int differing = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::uint8_t* a = &pictures[0][static_cast<std::size_t>((y * kWidth + x) * 3)];
            const std::uint8_t* b =
                &pictures[1][static_cast<std::size_t>((y * kWidth + (kWidth - 1 - x)) * 3)];
            changed += a[0] != 128 ? 1 : 0;
            differing += std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) > 30 ? 1 : 0;
        }
    EXPECT_GT(changed, 5000) << "the hat is drawn";
    EXPECT_LT(differing, changed / 100) << "mirrored = flipped, up to edge pixels";
}

// A closed cube wound counter-clockwise seen from outside (the OBJ convention), in a catalogue of
// its own, single- or double-sided.
std::string cubeCatalogue(bool doubleSided)
{
    const std::string dir = testing_support::freshOutputDir(doubleSided ? "overlay_cube_double"
                                                                        : "overlay_cube_single");
    std::ofstream obj(dir + "/cube.obj");
    obj << "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
           "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
           "f 5 6 7 8\nf 2 1 4 3\nf 6 2 3 7\nf 1 5 8 4\nf 8 7 3 4\nf 1 2 6 5\n";
    obj.close();
    std::ofstream toml(dir + "/catalogue.toml");
    toml << "version = 1\n[[overlay]]\nname = \"cube\"\nkind = \"other\"\n"
            "anchor = \"eye_midpoint\"\nmeasure = \"interocular\"\nrotation = [20.0, 30.0, 0.0]\n"
            "offset = [0.0, 0.0, 1.5]\n"
            "  [[overlay.mesh]]\n  obj = \"cube.obj\"\n  color = [0.9, 0.6, 0.2, 1.0]\n"
            "  double_sided = "
         << (doubleSided ? "true" : "false") << "\n";
    return dir + "/catalogue.toml";
}

TEST_F(FaceOverlayTest, SingleSidedClosedMeshesLookTheSameMirroredOrNot)
{
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    const vision::TrackedFace face = centredFace(200.f, 15.f);
    for (int mirror = 0; mirror < 2; ++mirror) {
        std::vector<std::uint8_t> pictures[2];
        for (int single = 0; single < 2; ++single) {
            const OverlayCatalogue cube = OverlayCatalogue::load(cubeCatalogue(single == 0));
            Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24,
                              RendererOptions{mirror == 1, {}, false});
            FaceOverlayOptions options;
            options.headProxy = false;
            FaceOverlayLayer layer(cube, options);
            renderer.addLayer(&layer);
            const render::FaceDrawing cubeOnFace = wearing(face, 0);
            ASSERT_TRUE(layer.setFaces({&cubeOnFace, 1}));
            ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr));
            gl.read();
            pictures[single] = crop(gl, 0, 0, kWidth, kHeight);
        }
        int drawn = 0;
        int differing = 0;
        for (std::size_t i = 0; i < pictures[0].size(); i += 3) {
            drawn += pictures[0][i] != 128 ? 1 : 0;
            differing += std::abs(pictures[0][i] - pictures[1][i]) > 8 ? 1 : 0;
        }
        EXPECT_GT(drawn, 2000) << "mirror " << mirror;
        EXPECT_LT(differing, 20) << "mirror " << mirror << ": culled the wrong side";
    }
}

TEST_F(FaceOverlayTest, BrightnessAndFadeChangeTheLightAndTheOpacity)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, RendererOptions{true, {}, false});
    FaceOverlayLayer layer(testCatalogue);
    renderer.addLayer(&layer);
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    const vision::TrackedFace face = centredFace();
    const int hat = testCatalogue.find("test_hat");
    // Sum over the crown (above the face) of |pixel - grey|.
    auto contrast = [&](float brightness, float alpha) {
        const render::FaceDrawing d = wearing(face, hat, alpha, brightness);
        EXPECT_TRUE(layer.setFaces({&d, 1}));
        EXPECT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr));
        gl.read();
        long sum = 0;
        long redSum = 0;
        for (int y = 0; y < 120; ++y)
            for (int x = 220; x < 420; ++x) {
                const Rgba p = gl.pixel(x, y);
                sum += std::abs(p.g - 128);
                redSum += p.r;
            }
        return std::pair<long, long>{sum, redSum};
    };
    const auto normal = contrast(1.f, 1.f);
    EXPECT_GT(normal.first, 0);
    const auto none = contrast(1.f, 0.f);
    EXPECT_EQ(none.first, 0) << "alpha 0: nothing drawn";
    const auto half = contrast(1.f, 0.5f);
    EXPECT_GT(half.first, normal.first / 4);
    EXPECT_LT(half.first, normal.first * 3 / 4);
    const auto bright = contrast(2.f, 1.f);
    const auto dark = contrast(0.5f, 1.f);
    EXPECT_GT(bright.second, normal.second);
    EXPECT_LT(dark.second, normal.second);

    // No overlay, an overlay the catalogue does not have, or a face not shown: nothing drawn.
    for (const int nothing : {-1, testCatalogue.size(), -2}) {
        const render::FaceDrawing d = wearing(face, nothing);
        EXPECT_EQ(layer.setFaces({&d, 1}), nothing == -1) << nothing;
        ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr));
        gl.read();
        EXPECT_EQ(gl.pixel(320, 60).g, 128) << nothing;
    }
    vision::TrackedFace tentative = face;
    tentative.state = vision::FaceState::Tentative;
    const render::FaceDrawing notShown = wearing(tentative, hat);
    EXPECT_TRUE(layer.setFaces({&notShown, 1}));
    ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr));
    gl.read();
    EXPECT_EQ(gl.pixel(320, 60).g, 128);
}

TEST_F(FaceOverlayTest, SaysSoWhenTheFramebufferHasNoDepthBuffer)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, RendererOptions{true, {}, false});
    FaceOverlayLayer layer(testCatalogue);
    renderer.addLayer(&layer);
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    const render::FaceDrawing d = wearing(centredFace(), 0);
    layer.setFaces({&d, 1});
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, 0);
    ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr));
    EXPECT_NE(std::string(layer.lastError()).find("no depth buffer"), std::string::npos);
}

// The layer clears only the depth under the overlays when they are small (and the head proxies
// only write there): whatever earlier frames left elsewhere in the depth buffer must not change a
// pixel, for small faces (rectangles cleared), a big one (whole buffer cleared), and a far face
// partly behind a near one (the near head hides the far face's glasses).
TEST_F(FaceOverlayTest, WhatEarlierFramesLeftInTheDepthBufferChangesNothing)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, RendererOptions{true, {}, false});
    FaceOverlayLayer layer(testCatalogue);
    renderer.addLayer(&layer);
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    const int hat = testCatalogue.find("test_hat");
    const int glasses = testCatalogue.find("test_glasses");

    auto face = [](int id, float x, float y, float size, int overlay) {
        vision::TrackedFace f;
        f.id = id;
        f.centre = {x, y};
        f.size = size;
        f.state = vision::FaceState::Confirmed;
        return wearing(f, overlay);
    };
    // Face 2 (smaller: farther) stands behind face 1's head; face 3 is apart.
    const render::FaceDrawing group[3] = {face(1, 300.f, 260.f, 90.f, hat),
                                          face(2, 345.f, 240.f, 55.f, glasses),
                                          face(3, 520.f, 200.f, 60.f, hat)};
    const render::FaceDrawing close[1] = {face(4, 320.f, 260.f, 260.f, hat)};
    auto render = [&](std::span<const render::FaceDrawing> faces, float staleDepth, bool proxy) {
        FaceOverlayOptions options = layer.options();
        options.headProxy = proxy;
        layer.setOptions(options);
        glClearDepthf(staleDepth);
        glClear(GL_DEPTH_BUFFER_BIT);
        layer.setFaces(faces);
        EXPECT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr)) << renderer.lastError();
        gl.read();
        return crop(gl, 0, 0, kWidth, kHeight);
    };
    auto changed = [&](const std::vector<std::uint8_t>& picture) {
        int n = 0;
        for (std::size_t i = 0; i < picture.size(); i += 3)
            n += picture[i] != 128 || picture[i + 1] != 128 || picture[i + 2] != 128 ? 1 : 0;
        return n;
    };

    for (const std::span<const render::FaceDrawing> faces :
         {std::span<const render::FaceDrawing>(group),
          std::span<const render::FaceDrawing>(close)}) {
        const std::vector<std::uint8_t> clean = render(faces, 1.f, true);
        EXPECT_GT(changed(clean), 500) << faces.size() << " faces: the overlays show";
        EXPECT_TRUE(render(faces, 0.f, true) == clean) << faces.size() << " faces, stale depth 0";
        EXPECT_TRUE(render(faces, 0.5f, true) == clean) << faces.size() << " faces, depth 0.5";
    }
    // Face 1's head hides a lens of face 2's glasses (the lenses make the only blue pixels).
    auto blue = [](const std::vector<std::uint8_t>& picture) {
        int n = 0;
        for (std::size_t i = 0; i < picture.size(); i += 3)
            n += picture[i + 2] > picture[i] + 25 ? 1 : 0;
        return n;
    };
    const int alone = blue(render({&group[1], 1}, 0.f, true));
    const int behind = blue(render({group, 2}, 0.f, true));
    EXPECT_GT(alone, 40);
    EXPECT_LT(behind, alone * 3 / 4);
    std::printf("lens pixels of the far face: %d alone, %d behind the near face\n", alone, behind);
}

// Textured meshes have a program of their own: a textured and an untextured mesh of one
// overlay, on two faces, all show with their colours.
TEST_F(FaceOverlayTest, TexturedAndUntexturedMeshesOfOneOverlayBothShow)
{
    const std::string dir = testing_support::freshOutputDir("overlay_textured");
    {
        std::ofstream(dir + "/catalogue.toml") << R"(version = 1
[[overlay]]
name = "card"
kind = "other"
anchor = "eye_midpoint"
measure = "interocular"
  [[overlay.mesh]]
  obj = "card.obj"
  objects = ["picture"]
  texture = "picture.png"
  [[overlay.mesh]]
  obj = "card.obj"
  objects = ["bar"]
  color = [0.0, 1.0, 0.0, 1.0]
)";
        std::ofstream(dir + "/card.obj") << R"(vn 0 0 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
o picture
v -1 0.2 0.3
v 1 0.2 0.3
v 1 1.2 0.3
v -1 1.2 0.3
f 1/1/1 2/2/1 3/3/1 4/4/1
o bar
v -1 -1.2 0.3
v 1 -1.2 0.3
v 1 -0.2 0.3
v -1 -0.2 0.3
f 5//1 6//1 7//1 8//1
)";
        // 4x1: red on the left, blue on the right (linear filtering blends only the middle).
        const std::uint8_t png[12] = {255, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0, 255};
        ASSERT_TRUE(platform::PngWriter().write((dir + "/picture.png").c_str(), png, 4, 1, 12));
    }
    const OverlayCatalogue catalogue = OverlayCatalogue::load(dir + "/catalogue.toml");
    ASSERT_FALSE(catalogue[0].meshes[0].texture.empty());
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, RendererOptions{true, {}, false});
    FaceOverlayLayer layer(catalogue);
    renderer.addLayer(&layer);
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    vision::TrackedFace faces[2] = {centredFace(150.f), centredFace(150.f)};
    faces[0].centre.x = 170.f;
    faces[1].centre.x = 470.f;
    faces[1].id = 8;
    const render::FaceDrawing drawings[2] = {wearing(faces[0], 0), wearing(faces[1], 0)};
    ASSERT_TRUE(layer.setFaces(drawings));
    ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr)) << renderer.lastError();
    gl.read();
    for (int half = 0; half < 2; ++half) {
        int red = 0;
        int blue = 0;
        int green = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = half * kWidth / 2; x < (half + 1) * kWidth / 2; ++x) {
                const Rgba p = gl.pixel(x, y);
                red += p.r > 150 && p.g < 60 && p.b < 60 ? 1 : 0;
                blue += p.b > 150 && p.r < 60 && p.g < 60 ? 1 : 0;
                green += p.g > 150 && p.r < 60 && p.b < 60 ? 1 : 0;
            }
        EXPECT_GT(red, 1000) << "half " << half;
        EXPECT_GT(blue, 1000) << "half " << half;
        EXPECT_GT(green, 1000) << "half " << half;
    }
}

TEST_F(FaceOverlayTest, DrawingThreeFacesAllocatesNothing)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, RendererOptions{true, {}, true});
    FaceOverlayLayer layer(testCatalogue);
    renderer.addLayer(&layer);
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    vision::TrackedFace faces[3] = {centredFace(120.f), centredFace(100.f, 10.f),
                                    centredFace(90.f, -15.f)};
    for (int i = 0; i < 3; ++i) {
        faces[i].id = i + 1;
        faces[i].centre = {140.f + 180.f * static_cast<float>(i), 260.f};
    }
    render::FaceDrawing drawings[3];
    for (int i = 0; i < 4; ++i) {  // warm-up: llvmpipe compiles shader variants on first use
        for (int f = 0; f < 3; ++f)
            drawings[f] = wearing(faces[f], f % 2, i == 3 ? 0.5f : 1.f);
        layer.setFaces(drawings);
        ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, "fps 30"));
    }
    testing_support::AllocationScope scope;
    bool ok = true;
    for (int i = 0; i < 6; ++i) {
        faces[0].centre.x += 1.f;
        for (int f = 0; f < 3; ++f)
            drawings[f] = wearing(faces[f], (f + i) % 2, i % 2 ? 0.5f : 1.f, 0.8f);
        ok = layer.setFaces(drawings) && ok;
        ok = renderer.draw(video.view(), kWidth, kHeight, "fps 30") && ok;
    }
    const testing_support::AllocationCounts counts = scope.counts();
    EXPECT_TRUE(ok) << renderer.lastError();
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
}

// llvmpipe compiles a shader variant (heap, LLVM) the first time a program is drawn with a new
// GL state. After the first frame with an overlay (here: a hat fading in), nothing the layer
// does later may compile one: the fade ending, lenses appearing, faces coming near or going far
// (whole or scissored depth clears).
TEST_F(FaceOverlayTest, LaterFramesCompileNoShaderVariant)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, RendererOptions{true, {}, false});
    FaceOverlayLayer layer(testCatalogue);
    renderer.addLayer(&layer);
    const vision::ImageBuffer video = greyFrame(kWidth, kHeight);
    vision::TrackedFace face = centredFace(60.f);
    render::FaceDrawing d = wearing(face, testCatalogue.find("test_hat"), 0.3f);
    ASSERT_TRUE(layer.setFaces({&d, 1}));
    // Two frames: the renderer's video quad is drawn in the first in GL's initial state.
    ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr));
    ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr));

    testing_support::AllocationScope scope;
    bool ok = true;
    for (const float size : {60.f, 300.f}) {  // small: rectangles cleared; big: all
        face.size = size;
        for (const auto& [name, alpha] :
             {std::pair{"test_hat", 1.f}, std::pair{"test_glasses", 1.f},
              std::pair{"test_glasses", 0.5f}}) {
            d = wearing(face, testCatalogue.find(name), alpha);
            ok = layer.setFaces({&d, 1}) && ok;
            ok = renderer.draw(video.view(), kWidth, kHeight, nullptr) && ok;
        }
    }
    const testing_support::AllocationCounts counts = scope.counts();
    EXPECT_TRUE(ok) << renderer.lastError();
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
    EXPECT_EQ(counts.foreignNew, 0) << "the GL driver compiled a shader variant";
}

// Every overlay of a catalogue on a real face (IMM 01, frontal), compared with its approved
// picture in tests/data/overlay_refs/<name>.png. MIRROR_UPDATE_REFS=1 writes the pictures instead
// (look at them before committing).
void checkReferences(const std::string& cataloguePath)
{
    constexpr int kWidth = 320;  // the 640x480 photo drawn at half size
    constexpr int kHeight = 240;
    constexpr int kCropX = 80;
    constexpr int kCropY = 0;
    constexpr int kCropWidth = 160;
    constexpr int kCropHeight = 200;
    GlTestContext gl(kWidth, kHeight);
    DepthAttachment depth(kWidth, kHeight);
    const OverlayCatalogue catalogue = OverlayCatalogue::load(cataloguePath);
    const vision::ImageBuffer photo =
        platform::loadImageFile(sharedData("imm_face_db/01-1m.jpg"), "IMM face");
    const vision::TrackedFace face = testing_support::faceFromEyes(
        testing_support::immEyes(sharedData("imm_face_db/01-1m.asf")), 1);
    Renderer renderer(photo.view().size(), PixelFormat::RGB24, RendererOptions{true, {}, false});
    FaceOverlayLayer layer(catalogue);
    renderer.addLayer(&layer);

    const bool update = std::getenv("MIRROR_UPDATE_REFS") != nullptr &&
                        std::string(std::getenv("MIRROR_UPDATE_REFS")) == "1";
    const std::string refs = sourceDir() + "/tests/data/overlay_refs";
    const std::string actualDir = testing_support::binaryDir() + "/test-output/overlay_refs_actual";
    std::filesystem::create_directories(actualDir);
    for (int i = 0; i < catalogue.size(); ++i) {
        const std::string name = catalogue[i].name;
        const render::FaceDrawing wearer = wearing(face, i);
        ASSERT_TRUE(layer.setFaces({&wearer, 1}));
        ASSERT_TRUE(renderer.draw(photo.view(), kWidth, kHeight, nullptr));
        gl.read();
        const std::vector<std::uint8_t> actual = crop(gl, kCropX, kCropY, kCropWidth, kCropHeight);
        const std::string refPath = refs + "/" + name + ".png";
        if (update) {
            ASSERT_TRUE(writePng(refPath, actual, kCropWidth, kCropHeight, 9)) << refPath;
            continue;
        }
        ASSERT_TRUE(writePng(actualDir + "/" + name + ".png", actual, kCropWidth, kCropHeight));
        if (!std::filesystem::exists(refPath)) {
            ADD_FAILURE() << "no approved picture " << refPath << " for overlay '" << name
                          << "': look at " << actualDir << "/" << name
                          << ".png and approve it with MIRROR_UPDATE_REFS=1";
            continue;
        }
        const vision::ImageBuffer ref = platform::loadImageFile(refPath, "reference");
        ASSERT_EQ(ref.view().size(), (vision::Size{kCropWidth, kCropHeight})) << refPath;
        long totalDifference = 0;
        int differing = 0;
        for (int y = 0; y < kCropHeight; ++y)
            for (int x = 0; x < kCropWidth * 3; x += 3) {
                const std::uint8_t* r = ref.view().row(y) + x;
                const std::uint8_t* a = &actual[static_cast<std::size_t>(y * kCropWidth * 3 + x)];
                int worst = 0;
                for (int c = 0; c < 3; ++c) {
                    const int d = std::abs(r[c] - a[c]);
                    totalDifference += d;
                    worst = std::max(worst, d);
                }
                differing += worst > 40 ? 1 : 0;
            }
        const double mean = static_cast<double>(totalDifference) / (kCropWidth * kCropHeight * 3);
        EXPECT_LT(mean, 1.5) << name << ": see " << actualDir << "/" << name << ".png";
        EXPECT_LT(differing, kCropWidth * kCropHeight / 200)
            << name << ": see " << actualDir << "/" << name << ".png";
    }
}

TEST(FaceOverlayReferences, TheTestOverlaysOnARealFaceMatchTheirApprovedPictures)
{
    checkReferences(sourceDir() + "/tests/data/overlays/catalogue.toml");
}

TEST(FaceOverlayReferences, TheProjectOverlaysOnARealFaceMatchTheirApprovedPictures)
{
    const std::string path = sourceDir() + "/assets/overlays/catalogue.toml";
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "no " << path;
    checkReferences(path);
}

// Snapshots for people to look at (the issue's note): every overlay on a real face at 720p, and
// two faces at once, in <build>/test-output/overlay_snapshots/.
TEST(FaceOverlaySnapshots, WritesEveryOverlayOnRealFacesAt720p)
{
    constexpr int kWidth = 1280;
    constexpr int kHeight = 720;
    GlTestContext gl(kWidth, kHeight);
    DepthAttachment depth(kWidth, kHeight);
    const OverlayCatalogue catalogue =
        OverlayCatalogue::load(testing_support::overlayCataloguePath(sourceDir()));
    const std::string out = testing_support::freshOutputDir("overlay_snapshots");

    // One face: the 640x480 photo covering the 720p screen.
    const vision::ImageBuffer photo =
        platform::loadImageFile(sharedData("imm_face_db/01-1m.jpg"), "IMM face");
    const vision::TrackedFace face = testing_support::faceFromEyes(
        testing_support::immEyes(sharedData("imm_face_db/01-1m.asf")), 1);
    {
        Renderer renderer(photo.view().size(), PixelFormat::RGB24,
                          RendererOptions{true, {}, false});
        FaceOverlayLayer layer(catalogue);
        renderer.addLayer(&layer);
        for (int i = 0; i < catalogue.size(); ++i) {
            const render::FaceDrawing d = wearing(face, i);
            layer.setFaces({&d, 1});
            ASSERT_TRUE(renderer.draw(photo.view(), kWidth, kHeight, nullptr));
            gl.read();
            ASSERT_TRUE(writePng(out + "/" + catalogue[i].name + ".png",
                                 crop(gl, 0, 0, kWidth, kHeight), kWidth, kHeight));
        }
    }

    // Two faces: two photos side by side in a 1280x720 frame.
    const vision::ImageBuffer second =
        platform::loadImageFile(sharedData("imm_face_db/08-1f.jpg"), "IMM face");
    vision::ImageBuffer frame(kWidth, kHeight, PixelFormat::RGB24);
    for (int y = 0; y < kHeight; ++y)
        std::memset(frame.view().row(y), 40, static_cast<std::size_t>(kWidth) * 3);
    constexpr int kTop = 120;
    for (int y = 0; y < 480; ++y) {
        std::memcpy(frame.view().row(y + kTop), photo.view().row(y), 640 * 3);
        std::memcpy(frame.view().row(y + kTop) + 640 * 3, second.view().row(y), 640 * 3);
    }
    const vision::TrackedFace faces[2] = {
        testing_support::faceFromEyes(testing_support::immEyes(sharedData("imm_face_db/01-1m.asf")),
                                      1, 0.f, kTop),
        testing_support::faceFromEyes(testing_support::immEyes(sharedData("imm_face_db/08-1f.asf")),
                                      2, 640.f, kTop)};
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, RendererOptions{true, {}, false});
    FaceOverlayLayer layer(catalogue);
    renderer.addLayer(&layer);
    for (int i = 0; i < catalogue.size(); ++i) {
        const int j = (i + 1) % catalogue.size();
        const render::FaceDrawing drawings[2] = {wearing(faces[0], i), wearing(faces[1], j)};
        layer.setFaces(drawings);
        ASSERT_TRUE(renderer.draw(frame.view(), kWidth, kHeight, nullptr));
        gl.read();
        ASSERT_TRUE(
            writePng(out + "/two_faces_" + catalogue[i].name + "_" + catalogue[j].name + ".png",
                     crop(gl, 0, 0, kWidth, kHeight), kWidth, kHeight));
    }
    std::printf("snapshots in %s\n", out.c_str());
}

}  // namespace

// A facet is a chord of the round head, behind its surface; a brim passing just behind the head
// is cut along the facets. Coarse facets (8 rings of 16) sank 3.6 % of the radius inside it and
// cut a near face's top-hat brim along one straight ring edge, a box across the forehead.
TEST(HeadProxy, ItsFacetsStayWithinAPercentOfTheRoundHead)
{
    const float n = render::HeadModel{}.proxySquareness;
    const render::HeadProxyMesh mesh = render::unitHeadProxy(n);
    ASSERT_EQ(mesh.indices.size() % 3, 0u);
    float deepest = 1.f;  // the smallest "radius" of a facet's centre: 1 on the surface
    for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
        Eigen::Vector3f c = Eigen::Vector3f::Zero();
        for (std::size_t k = 0; k < 3; ++k) {
            const auto& p = mesh.points[mesh.indices[i + k]];
            c += Eigen::Vector3f(p[0], p[1], p[2]) / 3.f;
        }
        // The surface: horizontal sections |x|^n + |z|^n = r^n with r^2 + y^2 = 1.
        const float r =
            std::pow(std::pow(std::fabs(c.x()), n) + std::pow(std::fabs(c.z()), n), 1.f / n);
        deepest = std::min(deepest, std::sqrt(r * r + c.y() * c.y()));
    }
    EXPECT_GT(deepest, 0.99f);
}
