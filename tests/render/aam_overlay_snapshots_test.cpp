// The contact sheet of the overlays placed by the AAM fit's full pose (§5.3), for people to look
// at (docs/snapshots/README.md says how it goes into docs/snapshots/): IMM's frontal (type 1) and
// turned heads (types 3 and 4) of persons the demo model left out, and FGNet talking-face frames,
// each wearing glasses and a top hat as the firmware places them: found by the product's
// Viola-Jones detector on the half-size grey image the tracker works on, fitted there by
// TrackedFaceFitter (five frames of a person standing still), posed by headPoseFromFit. A green
// corner marks a tile whose fit held (the full pose), a red one a tile drawn by the box alone
// (the fit let go, or no face was found: then nothing is drawn). Nothing is asserted about how
// good the pictures are: mirror-eval aam measures that (docs/aam-evaluation.md).
#include "../vision/aam_demo_model.hpp"
#include "gl_test_context.hpp"
#include "overlay_test_scene.hpp"
#include "platform/image_file.hpp"
#include "platform/png_writer.hpp"
#include "render/face_overlay_layer.hpp"
#include "render/overlay_catalogue.hpp"
#include "render/renderer.hpp"
#include "test_paths.hpp"
#include "vision/face_detector.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/head_pose.hpp"
#include "vision/motion_detector.hpp"
#include "vision/tracked_face_fitter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using testing_support::DepthAttachment;
using testing_support::GlTestContext;
using testing_support::sharedData;

constexpr const char* kCascade =
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";
constexpr int kShrink = 2;  // the motion stage's default downscale: the tracker's grey image
constexpr int kTile = 200;  // a tile: the face's square, kTile x kTile pixels

/// One picture of the sheet: the face's square of the rendered frame, and whether the fit held.
struct Tile {
    std::vector<std::uint8_t> rgb = std::vector<std::uint8_t>(kTile * kTile * 3, 32);
    bool fitted = false;
    float yaw = 0.f;
};

/// The face found, fitted and drawn wearing each of `overlays`: one tile per overlay.
class Fitting {
public:
    explicit Fitting(const vision::AamModel& model)
        : cascade_(vision::loadHaarCascade(kCascade)),
          fitter_(model),
          catalogue_(render::OverlayCatalogue::load(
              testing_support::overlayCataloguePath(testing_support::sourceDir())))
    {
    }

    std::vector<Tile> tiles(const vision::ImageBuffer& photo, std::span<const char* const> overlays)
    {
        const vision::Size size = photo.view().size();
        vision::ImageBuffer grey(size.width / kShrink, size.height / kShrink,
                                 vision::PixelFormat::Gray8);
        EXPECT_TRUE(vision::downscaleToGray(photo.view(), kShrink, grey.view()));
        vision::FaceDetectorOptions o;
        o.maxFrameSize = grey.view().size();
        o.minSize = {24, 24};
        vision::FaceDetector detector(cascade_, o);
        std::vector<Tile> out(overlays.size());
        if (detector.detect(grey.view()) <= 0)
            return out;  // no face: the tiles stay dark, red-cornered
        const vision::Rect r = *std::max_element(
            detector.faces().begin(), detector.faces().end(),
            [](const vision::Rect& a, const vision::Rect& b) { return a.width < b.width; });
        vision::TrackedFace face;
        face.id = ++nextId_;
        face.centre = {r.x + 0.5f * r.width, r.y + 0.5f * r.height};
        face.size = static_cast<float>(r.width);
        face.state = vision::FaceState::Confirmed;
        for (int frame = 0; frame < 5; ++frame)
            fitter_.process(grey.view(), {&face, 1});
        vision::FaceFit fit = fitter_.fits()[0];
        // Into the photo's pixels, as the AAM stage does (MotionStage::toFrame).
        const float k = static_cast<float>(kShrink), shift = 0.5f * k - 0.5f;
        fit.eyeMidpoint = {fit.eyeMidpoint.x * k + shift, fit.eyeMidpoint.y * k + shift};
        fit.faceSize *= k;
        vision::TrackedFace frameFace = face;
        frameFace.centre = {face.centre.x * k + shift, face.centre.y * k + shift};
        frameFace.size *= k;
        for (std::size_t i = 0; i < overlays.size(); ++i)
            out[i] = draw(photo, frameFace, fit, overlays[i]);
        return out;
    }

private:
    Tile draw(const vision::ImageBuffer& photo, const vision::TrackedFace& face,
              const vision::FaceFit& fit, const char* overlay)
    {
        const vision::Size size = photo.view().size();
        GlTestContext gl(size.width, size.height);
        DepthAttachment depth(size.width, size.height);
        render::Renderer renderer(size, vision::PixelFormat::RGB24,
                                  render::RendererOptions{false, {}, false});
        render::FaceOverlayLayer layer(catalogue_);
        renderer.addLayer(&layer);
        render::FaceDrawing d;
        d.face = face;
        d.overlay = catalogue_.find(overlay);
        EXPECT_GE(d.overlay, 0) << overlay;
        d.hasPose = fit.ok();
        if (d.hasPose) {
            d.pose = vision::headPoseFromFit(fit, {size, layer.options().verticalFovDegrees},
                                             layer.options().head.faceWidthMetres);
            d.animation = fit.animation;
        }
        EXPECT_TRUE(layer.setFaces({&d, 1}));
        EXPECT_TRUE(renderer.draw(photo.view(), size.width, size.height, nullptr));
        gl.read();
        Tile t;
        t.fitted = fit.ok();
        t.yaw = fit.yawDegrees;
        // The face's square, 1.9 box sides wide (room for the hat), scaled to the tile.
        const float side = 1.9f * face.size;
        const float x0 = face.centre.x - 0.5f * side, y0 = face.centre.y - 0.62f * side;
        for (int y = 0; y < kTile; ++y)
            for (int x = 0; x < kTile; ++x) {
                const int sx = static_cast<int>(x0 + (x + 0.5f) * side / kTile);
                const int sy = static_cast<int>(y0 + (y + 0.5f) * side / kTile);
                if (sx < 0 || sy < 0 || sx >= size.width || sy >= size.height)
                    continue;
                const testing_support::Rgba p = gl.pixel(sx, sy);
                std::uint8_t* o = &t.rgb[static_cast<std::size_t>((y * kTile + x) * 3)];
                o[0] = static_cast<std::uint8_t>(p.r);
                o[1] = static_cast<std::uint8_t>(p.g);
                o[2] = static_cast<std::uint8_t>(p.b);
            }
        return t;
    }

    vision::HaarCascade cascade_;
    vision::TrackedFaceFitter fitter_;
    render::OverlayCatalogue catalogue_;
    int nextId_ = 0;
};

/// Rows of tiles side by side into one RGB picture, each tile's corner marked.
std::vector<std::uint8_t> sheet(const std::vector<std::vector<Tile>>& rows, int& width, int& height)
{
    const int columns = static_cast<int>(rows.front().size());
    width = columns * kTile;
    height = static_cast<int>(rows.size()) * kTile;
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width * height * 3), 0);
    for (std::size_t r = 0; r < rows.size(); ++r)
        for (int c = 0; c < columns; ++c) {
            const Tile& t = rows[r][static_cast<std::size_t>(c)];
            for (int y = 0; y < kTile; ++y) {
                std::uint8_t* dst = &rgb[static_cast<std::size_t>(
                    ((static_cast<int>(r) * kTile + y) * width + c * kTile) * 3)];
                std::memcpy(dst, &t.rgb[static_cast<std::size_t>(y * kTile * 3)], kTile * 3);
                for (int x = 0; x < kTile; ++x) {
                    const bool mark = x < 12 && y < 12 && x + y < 12;
                    const bool edge = x == kTile - 1 || y == kTile - 1;
                    if (mark || edge) {
                        dst[x * 3 + 0] = edge ? 0 : (t.fitted ? 40 : 230);
                        dst[x * 3 + 1] = edge ? 0 : (t.fitted ? 200 : 40);
                        dst[x * 3 + 2] = edge ? 0 : 40;
                    }
                }
            }
        }
    return rgb;
}

void writeSheet(const std::string& path, const std::vector<std::vector<Tile>>& rows)
{
    int width = 0, height = 0;
    const std::vector<std::uint8_t> rgb = sheet(rows, width, height);
    platform::PngWriter writer(std::size_t{64} << 20, 6);
    ASSERT_TRUE(
        writer.write(path.c_str(), rgb.data(), width, height, static_cast<std::size_t>(width) * 3))
        << path;
    std::printf("contact sheet: %s\n", path.c_str());
}

TEST(AamOverlaySnapshots, ImmTurnedHeadsWearGlassesAndAHatByTheFittedPose)
{
    REQUIRE_DEMO_MODEL();
    const std::string imm = sharedData("imm_face_db");
    if (!std::filesystem::is_directory(imm))
        GTEST_SKIP() << "no " << imm;
    Fitting fitting(*aam_test::demoModel());
    // Persons 04, 08, ... 20: the demo model leaves every fourth person out (scripts/dev model).
    // Columns: type 1 with glasses, types 3 and 4 with glasses, types 3 and 4 with the hat.
    constexpr const char* kGlasses[] = {"glasses"};
    constexpr const char* kBoth[] = {"glasses", "top_hat"};
    std::vector<std::vector<Tile>> rows;
    int held = 0, shown = 0;
    for (int person = 4; person <= 20; person += 4) {
        std::vector<Tile> row;
        std::vector<Tile> hats;
        for (int type : {1, 3, 4}) {
            std::string path;
            for (const char* sex : {"m", "f"}) {
                char name[32];
                std::snprintf(name, sizeof name, "/%02d-%d%s.jpg", person, type, sex);
                if (std::filesystem::exists(imm + name))
                    path = imm + name;
            }
            ASSERT_FALSE(path.empty()) << "IMM person " << person << " type " << type;
            const vision::ImageBuffer photo = platform::loadImageFile(path, "IMM face");
            const std::vector<Tile> t =
                type == 1 ? fitting.tiles(photo, kGlasses) : fitting.tiles(photo, kBoth);
            row.push_back(t[0]);
            if (type != 1)
                hats.push_back(t[1]);
            held += t[0].fitted;
            ++shown;
            std::printf("%s: fit %s, yaw %+.1f deg\n", path.c_str(),
                        t[0].fitted ? "held" : "let go", static_cast<double>(t[0].yaw));
        }
        row.insert(row.end(), hats.begin(), hats.end());
        rows.push_back(row);
    }
    std::printf("fits held: %d of %d\n", held, shown);
    writeSheet(testing_support::freshOutputDir("aam_snapshots") + "/imm_turned_heads.png", rows);
}

TEST(AamOverlaySnapshots, FgnetFramesWearGlassesAndAHatByTheFittedPose)
{
    REQUIRE_DEMO_MODEL();
    const std::string frames = sharedData("fgnet_talking_face/images");
    if (!std::filesystem::is_directory(frames))
        GTEST_SKIP() << "no " << frames;
    Fitting fitting(*aam_test::demoModel());
    // Frames 0-999 only (the rest of the recording is held back); FGNet's person is not in the
    // demo model (it is built from IMM).
    constexpr const char* kBoth[] = {"glasses", "top_hat"};
    std::vector<std::vector<Tile>> rows(2);
    int held = 0;
    for (int frame = 0; frame < 1000; frame += 166) {
        char name[64];
        std::snprintf(name, sizeof name, "/franck_%05d.jpg", frame);
        const vision::ImageBuffer photo = platform::loadImageFile(frames + name, "FGNet frame");
        const std::vector<Tile> t = fitting.tiles(photo, kBoth);
        rows[0].push_back(t[0]);
        rows[1].push_back(t[1]);
        held += t[0].fitted;
        std::printf("%s: fit %s, yaw %+.1f deg\n", name + 1, t[0].fitted ? "held" : "let go",
                    static_cast<double>(t[0].yaw));
    }
    std::printf("fits held: %d of %zu\n", held, rows[0].size());
    writeSheet(testing_support::freshOutputDir("aam_snapshots_fgnet") + "/fgnet_frames.png", rows);
}

}  // namespace
