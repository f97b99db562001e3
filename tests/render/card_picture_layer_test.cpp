#include "render/card_picture_layer.hpp"

#include "alloc_counter.hpp"
#include "gl_test_context.hpp"
#include "platform/png_writer.hpp"
#include "render/default_card_picture.hpp"
#include "render/renderer.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <set>
#include <stdexcept>
#include <string>

namespace {

using render::CardPictureLayer;
using render::Renderer;
using render::RendererOptions;
using testing_support::GlTestContext;
using testing_support::Rgba;
using vision::CardObservation;
using vision::CardState;
using vision::PixelFormat;
using vision::Quad;

// Camera and screen the same size, so with the mirror camera pixel (x, y) is screen pixel
// (kWidth - 1 - x, y). 150 wide: the Gray8 mask's rows are padded (ImageBuffer pads to 16).
constexpr int kWidth = 150;
constexpr int kHeight = 100;
constexpr Rgba kVideo{20, 60, 20, 255};
constexpr Rgba kBlue{0, 0, 255, 255};
constexpr Rgba kRed{255, 0, 0, 255};

vision::ImageBuffer solidImage(int width, int height, PixelFormat format, std::uint8_t value0,
                               std::uint8_t value1 = 0, std::uint8_t value2 = 0)
{
    vision::ImageBuffer image(width, height, format);
    const vision::ImageView v = image.view();
    const int bpp = vision::bytesPerPixel(format);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = v.row(y) + x * bpp;
            p[0] = value0;
            if (bpp == 3) {
                p[1] = value1;
                p[2] = value2;
            }
        }
    return image;
}

// Blue picture with a red square marker centred on uv (0.5, 0.5).
vision::ImageBuffer markerPicture()
{
    vision::ImageBuffer picture = solidImage(64, 64, PixelFormat::RGB24, 0, 0, 255);
    const vision::ImageView v = picture.view();
    for (int y = 28; y < 36; ++y)
        for (int x = 28; x < 36; ++x) {
            std::uint8_t* p = v.row(y) + x * 3;
            p[0] = 255;
            p[1] = 0;
            p[2] = 0;
        }
    return picture;
}

void fillRect(vision::ImageBuffer& image, int x0, int y0, int x1, int y1, std::uint8_t value)
{
    const vision::ImageView v = image.view();
    for (int y = y0; y < y1; ++y)
        std::memset(v.row(y) + x0, value, static_cast<std::size_t>(x1 - x0));
}

CardObservation tracking(const Quad& quad, const vision::ImageBuffer& mask)
{
    CardObservation card;
    card.state = CardState::Tracking;
    card.confidence = 0.9f;
    card.hasQuad = true;
    card.quad = quad;
    card.rawQuad = quad;
    card.mask = mask.view();
    return card;
}

bool near(const Rgba& a, const Rgba& b, int tolerance = 8)
{
    return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance &&
           std::abs(a.b - b.b) <= tolerance;
}

std::string text(const Rgba& c)
{
    return "(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

const Quad kSquareQuad{{{30.f, 20.f}, {90.f, 20.f}, {90.f, 70.f}, {30.f, 70.f}}};

class CardPictureLayerTest : public ::testing::Test {
protected:
    CardPictureLayerTest()
        : gl(kWidth, kHeight),
          video(solidImage(kWidth, kHeight, PixelFormat::RGB24, static_cast<std::uint8_t>(kVideo.r),
                           static_cast<std::uint8_t>(kVideo.g),
                           static_cast<std::uint8_t>(kVideo.b))),
          fullMask(solidImage(kWidth, kHeight, PixelFormat::Gray8, 255))
    {
    }

    static RendererOptions options(bool mirror = true)
    {
        RendererOptions o;
        o.mirror = mirror;
        o.hud = false;
        return o;
    }

    // One frame: update, draw, read back.
    void frame(Renderer& renderer, CardPictureLayer& layer, const CardObservation* card)
    {
        layer.update(card);
        ASSERT_TRUE(renderer.draw(video.view(), gl.width(), gl.height(), nullptr))
            << renderer.lastError();
        gl.read();
    }

    // The screen pixel showing camera pixel (x, y) when mirrored (screen = camera size).
    Rgba camera(int x, int y) const { return gl.pixel(kWidth - 1 - x, y); }

    GlTestContext gl;
    vision::ImageBuffer video;
    vision::ImageBuffer fullMask;
};

TEST_F(CardPictureLayerTest, PictureInsideTheQuadVideoOutside)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options());
    const vision::ImageBuffer picture = solidImage(32, 32, PixelFormat::RGB24, 0, 0, 255);
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    renderer.addLayer(&layer);
    EXPECT_FALSE(layer.outlineMode());
    const CardObservation card = tracking(kSquareQuad, fullMask);
    frame(renderer, layer, &card);
    EXPECT_TRUE(layer.visible());
    EXPECT_STREQ(layer.lastError(), "");
    for (const auto& [x, y] : {std::pair{32, 22}, {60, 45}, {88, 68}, {31, 69}})
        EXPECT_TRUE(near(camera(x, y), kBlue)) << x << "," << y << " " << text(camera(x, y));
    for (const auto& [x, y] : {std::pair{5, 5}, {28, 45}, {92, 45}, {60, 18}, {60, 72}, {140, 90}})
        EXPECT_TRUE(near(camera(x, y), kVideo)) << x << "," << y << " " << text(camera(x, y));
}

TEST_F(CardPictureLayerTest, MaskZeroInsideTheQuadShowsTheVideo)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options());
    const vision::ImageBuffer picture = solidImage(32, 32, PixelFormat::RGB24, 0, 0, 255);
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    renderer.addLayer(&layer);
    // A hand over the card's lower-left: not card-coloured, so the mask is 0 there.
    vision::ImageBuffer mask = solidImage(kWidth, kHeight, PixelFormat::Gray8, 0);
    fillRect(mask, 30, 20, 91, 71, 255);
    fillRect(mask, 25, 45, 55, 80, 0);
    const CardObservation card = tracking(kSquareQuad, mask);
    frame(renderer, layer, &card);
    for (const auto& [x, y] : {std::pair{35, 50}, {50, 65}, {40, 60}})
        EXPECT_TRUE(near(camera(x, y), kVideo)) << x << "," << y << " " << text(camera(x, y));
    for (const auto& [x, y] : {std::pair{35, 30}, {70, 60}, {60, 40}})
        EXPECT_TRUE(near(camera(x, y), kBlue)) << x << "," << y << " " << text(camera(x, y));
}

TEST_F(CardPictureLayerTest, MaskEdgeIsBlendedWhenTheScreenIsLargerThanTheCamera)
{
    gl.resize(kWidth * 4, kHeight * 4);
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options(false));
    const vision::ImageBuffer picture = solidImage(32, 32, PixelFormat::RGB24, 0, 0, 255);
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    renderer.addLayer(&layer);
    vision::ImageBuffer mask = solidImage(kWidth, kHeight, PixelFormat::Gray8, 255);
    fillRect(mask, 0, 0, 60, kHeight, 0);  // camera columns < 60 not card-coloured
    const CardObservation card = tracking(kSquareQuad, mask);
    frame(renderer, layer, &card);
    // Not mirrored, 4x: camera pixel centres 59 and 60 are at screen x 238 and 242. Between
    // them the picture's alpha ramps, so the colour is a mix, not a step.
    const int y = 45 * 4;
    EXPECT_TRUE(near(gl.pixel(236, y), kVideo)) << text(gl.pixel(236, y));
    EXPECT_TRUE(near(gl.pixel(244, y), kBlue)) << text(gl.pixel(244, y));
    const Rgba middle = gl.pixel(240, y);
    EXPECT_GT(middle.b, kVideo.b + 40) << text(middle);
    EXPECT_LT(middle.b, 255 - 40) << text(middle);
}

TEST_F(CardPictureLayerTest, PictureCentreLandsOnTheQuadsDiagonalsUnderPerspective)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options());
    const vision::ImageBuffer picture = markerPicture();
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    renderer.addLayer(&layer);
    // A card tilted far back: its top edge much shorter than its bottom.
    const Quad quad{{{60.f, 10.f}, {90.f, 10.f}, {140.f, 95.f}, {10.f, 95.f}}};
    const CardObservation card = tracking(quad, fullMask);
    frame(renderer, layer, &card);
    // Where the diagonals 0-2 and 1-3 cross: the projective image of the picture's centre.
    const double d1x = quad[2].x - quad[0].x, d1y = quad[2].y - quad[0].y;
    const double d2x = quad[3].x - quad[1].x, d2y = quad[3].y - quad[1].y;
    const double t =
        ((quad[1].x - quad[0].x) * d2y - (quad[1].y - quad[0].y) * d2x) / (d1x * d2y - d1y * d2x);
    const double crossX = quad[0].x + t * d1x;
    const double crossY = quad[0].y + t * d1y;
    double sumX = 0, sumY = 0;
    int count = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const Rgba c = camera(x, y);
            if (c.r > 128 && c.b < 128) {
                sumX += x;
                sumY += y;
                ++count;
            }
        }
    ASSERT_GT(count, 10);
    const double markerX = sumX / count;
    const double markerY = sumY / count;
    EXPECT_NEAR(markerX, crossX, 1.0);
    EXPECT_NEAR(markerY, crossY, 1.5);
    // The affine guess (average of the corners) is far off: the test can tell them apart.
    const double averageY = (quad[0].y + quad[1].y + quad[2].y + quad[3].y) / 4.0;
    EXPECT_GT(std::fabs(markerY - averageY), 15.0);
    // And the picture fills the quad: just inside each corner is blue.
    for (const auto& [x, y] : {std::pair{62, 12}, {88, 12}, {135, 93}, {15, 93}})
        EXPECT_TRUE(near(camera(x, y), kBlue, 30)) << x << "," << y << " " << text(camera(x, y));
}

TEST_F(CardPictureLayerTest, PicturesOfAnySizeKeepTheirLayout)
{
    // Non-power-of-two and larger-than-texture pictures are resampled at construction; the
    // picture's left half (red) must still land on the quad's left half, top (green bar) on top.
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options(false));
    for (const vision::Size size : {vision::Size{100, 60}, vision::Size{2400, 1800}}) {
        vision::ImageBuffer picture =
            solidImage(size.width, size.height, PixelFormat::RGB24, 0, 0, 255);
        const vision::ImageView v = picture.view();
        for (int y = 0; y < size.height; ++y)
            for (int x = 0; x < size.width / 2; ++x) {
                std::uint8_t* p = v.row(y) + x * 3;
                p[0] = 255, p[1] = 0, p[2] = 0;
            }
        for (int y = 0; y < size.height / 6; ++y)
            for (int x = 0; x < size.width; ++x) {
                std::uint8_t* p = v.row(y) + x * 3;
                p[0] = 0, p[1] = 255, p[2] = 0;
            }
        CardPictureLayer layer(picture.view(), {kWidth, kHeight});
        Renderer plain({kWidth, kHeight}, PixelFormat::RGB24, options(false));
        plain.addLayer(&layer);
        const CardObservation card = tracking(kSquareQuad, fullMask);
        layer.update(&card);
        ASSERT_TRUE(plain.draw(video.view(), kWidth, kHeight, nullptr)) << plain.lastError();
        gl.read();
        // Quad x 30..90, y 20..70; not mirrored.
        EXPECT_TRUE(near(gl.pixel(45, 50), kRed, 12))
            << size.width << " " << text(gl.pixel(45, 50));
        EXPECT_TRUE(near(gl.pixel(75, 50), kBlue, 12))
            << size.width << " " << text(gl.pixel(75, 50));
        EXPECT_TRUE(near(gl.pixel(75, 22), Rgba{0, 255, 0, 255}, 12))
            << size.width << " " << text(gl.pixel(75, 22));
    }
}

TEST_F(CardPictureLayerTest, MirroredWithTheVideo)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options(true));
    const vision::ImageBuffer picture = solidImage(32, 32, PixelFormat::RGB24, 0, 0, 255);
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    renderer.addLayer(&layer);
    // On the left of the camera image.
    const Quad quad{{{5.f, 30.f}, {45.f, 30.f}, {45.f, 70.f}, {5.f, 70.f}}};
    const CardObservation card = tracking(quad, fullMask);
    frame(renderer, layer, &card);
    EXPECT_TRUE(near(gl.pixel(kWidth - 1 - 25, 50), kBlue)) << text(gl.pixel(kWidth - 1 - 25, 50));
    EXPECT_TRUE(near(gl.pixel(25, 50), kVideo)) << text(gl.pixel(25, 50));

    // Without the mirror it stays on the left.
    Renderer plain({kWidth, kHeight}, PixelFormat::RGB24, options(false));
    plain.addLayer(&layer);
    layer.update(&card);
    ASSERT_TRUE(plain.draw(video.view(), kWidth, kHeight, nullptr)) << plain.lastError();
    gl.read();
    EXPECT_TRUE(near(gl.pixel(25, 50), kBlue)) << text(gl.pixel(25, 50));
    EXPECT_TRUE(near(gl.pixel(kWidth - 1 - 25, 50), kVideo));
}

TEST_F(CardPictureLayerTest, PictureReadsTheRightWayRoundOnScreenMirroredOrNot)
{
    // Left half of the picture blue, right half red: a viewer must see blue on the left of the
    // card on screen, whether or not the video is mirrored (text on the picture is not reversed).
    vision::ImageBuffer picture = solidImage(32, 32, PixelFormat::RGB24, 255, 0, 0);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 16; ++x) {
            std::uint8_t* p = picture.view().row(y) + 3 * x;
            p[0] = 0;
            p[2] = 255;
        }
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    const CardObservation card = tracking(kSquareQuad, fullMask);  // camera x 30..90
    for (const bool mirror : {true, false}) {
        Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options(mirror));
        renderer.addLayer(&layer);
        frame(renderer, layer, &card);
        // The card spans camera x 30..90: on screen 30..90, or 59..119 when mirrored.
        const int left = mirror ? kWidth - 1 - 85 : 35;
        const int right = mirror ? kWidth - 1 - 35 : 85;
        EXPECT_TRUE(near(gl.pixel(left, 45), kBlue)) << mirror << " " << text(gl.pixel(left, 45));
        EXPECT_FALSE(near(gl.pixel(right, 45), kBlue))
            << mirror << " " << text(gl.pixel(right, 45));
    }
}

TEST_F(CardPictureLayerTest, WithoutAPictureTheQuadIsOutlined)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options());
    CardPictureLayer layer(vision::ConstImageView{}, {kWidth, kHeight});
    renderer.addLayer(&layer);
    EXPECT_TRUE(layer.outlineMode());
    const CardObservation card = tracking(kSquareQuad, fullMask);
    frame(renderer, layer, &card);
    const auto isOutline = [](const Rgba& c) { return c.r > 200 && c.g > 160 && c.b < 60; };
    // On each edge and at each corner.
    for (const auto& [x, y] : {std::pair{60, 20}, {90, 45}, {60, 70}, {30, 45}, {30, 20}, {90, 70}})
        EXPECT_TRUE(isOutline(camera(x, y))) << x << "," << y << " " << text(camera(x, y));
    // Not filled, and nothing far outside.
    for (const auto& [x, y] : {std::pair{60, 45}, {40, 30}, {10, 10}, {120, 90}})
        EXPECT_TRUE(near(camera(x, y), kVideo)) << x << "," << y << " " << text(camera(x, y));
}

TEST_F(CardPictureLayerTest, NothingDrawnWithoutATrackedCard)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options());
    const vision::ImageBuffer picture = solidImage(32, 32, PixelFormat::RGB24, 0, 0, 255);
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    CardPictureLayer outline(vision::ConstImageView{}, {kWidth, kHeight});
    renderer.addLayer(&layer);
    renderer.addLayer(&outline);
    CardObservation lost = tracking(kSquareQuad, fullMask);
    lost.state = CardState::Lost;  // still has the last good quad: not drawn
    CardObservation searching = tracking(kSquareQuad, fullMask);
    searching.state = CardState::Searching;
    CardObservation noQuad = tracking(kSquareQuad, fullMask);
    noQuad.hasQuad = false;
    CardObservation folded = tracking(
        Quad{{{30.f, 20.f}, {90.f, 70.f}, {90.f, 20.f}, {30.f, 70.f}}}, fullMask);  // bow-tie
    const CardObservation tracked = tracking(kSquareQuad, fullMask);
    const CardObservation* cards[] = {nullptr, &lost, &searching, &noQuad, &folded};
    for (const CardObservation* card : cards) {
        // A tracked frame first, so a layer that failed to clear would still show it.
        frame(renderer, layer, &tracked);
        outline.update(&tracked);
        layer.update(card);
        outline.update(card);
        ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr));
        gl.read();
        EXPECT_FALSE(layer.visible());
        EXPECT_FALSE(outline.visible());
        int different = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                different += near(gl.pixel(x, y), kVideo, 2) ? 0 : 1;
        EXPECT_EQ(different, 0);
    }
}

TEST_F(CardPictureLayerTest, MaskOfTheWrongSizeIsIgnoredAndReported)
{
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options());
    const vision::ImageBuffer picture = solidImage(32, 32, PixelFormat::RGB24, 0, 0, 255);
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    renderer.addLayer(&layer);
    const vision::ImageBuffer small = solidImage(10, 10, PixelFormat::Gray8, 0);
    const CardObservation card = tracking(kSquareQuad, small);
    frame(renderer, layer, &card);
    EXPECT_NE(std::string(layer.lastError()).find("does not match"), std::string::npos)
        << layer.lastError();
    EXPECT_TRUE(near(camera(60, 45), kBlue)) << text(camera(60, 45));
}

TEST_F(CardPictureLayerTest, ConstructorRejectsWhatItCannotDraw)
{
    const vision::ImageBuffer gray = solidImage(8, 8, PixelFormat::Gray8, 0);
    try {
        CardPictureLayer layer(gray.view(), {kWidth, kHeight});
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "card picture layer: picture is GRAY8, need RGB24");
    }
    EXPECT_THROW(CardPictureLayer(vision::ConstImageView{}, {0, 0}), std::runtime_error);
}

TEST_F(CardPictureLayerTest, UpdateAndDrawDoNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting is not available in this build";
    RendererOptions withHud = options();
    withHud.hud = true;  // the HUD drawn after the layer: GL state left usable
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, withHud);
    const vision::ImageBuffer picture = markerPicture();
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    CardPictureLayer outline(vision::ConstImageView{}, {kWidth, kHeight});
    renderer.addLayer(&layer);
    renderer.addLayer(&outline);
    vision::ImageBuffer mask = solidImage(kWidth, kHeight, PixelFormat::Gray8, 255);
    fillRect(mask, 40, 40, 60, 60, 0);
    CardObservation card = tracking(kSquareQuad, mask);
    CardObservation lost = card;
    lost.state = CardState::Lost;
    // Warm up: llvmpipe compiles shader variants on the first draws of each GL state.
    for (int i = 0; i < 4; ++i) {
        layer.update(i == 3 ? &lost : &card);
        outline.update(&card);
        ASSERT_TRUE(renderer.draw(video.view(), kWidth, kHeight, "fps 30.0"))
            << renderer.lastError();
    }
    testing_support::AllocationScope scope;
    bool ok = true;
    for (int i = 0; i < 6; ++i) {
        card.quad[2].x = 90.f + static_cast<float>(i);  // a moving card
        layer.update(i == 4 ? &lost : &card);
        outline.update(i == 5 ? nullptr : &card);
        ok = renderer.draw(video.view(), kWidth, kHeight, "fps 30.0") && ok;
    }
    const testing_support::AllocationCounts counts = scope.counts();
    EXPECT_TRUE(ok) << renderer.lastError();
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
}

TEST(CardPictureHomography, MapsTheQuadCornersToTheUnitSquare)
{
    const Quad quad{{{60.f, 10.f}, {90.f, 12.f}, {140.f, 95.f}, {10.f, 90.f}}};
    float inverse[9];
    ASSERT_TRUE(CardPictureLayer::unitSquareToQuadInverse(quad, inverse));
    const double expected[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (std::size_t i = 0; i < 4; ++i) {
        const double x = quad[i].x, y = quad[i].y;
        const double u = inverse[0] * x + inverse[1] * y + inverse[2];
        const double v = inverse[3] * x + inverse[4] * y + inverse[5];
        const double w = inverse[6] * x + inverse[7] * y + inverse[8];
        EXPECT_GT(w, 0.0);
        EXPECT_NEAR(u / w, expected[i][0], 1e-5) << i;
        EXPECT_NEAR(v / w, expected[i][1], 1e-5) << i;
    }
    const Quad flat{{{0.f, 0.f}, {10.f, 0.f}, {20.f, 0.f}, {30.f, 0.f}}};
    EXPECT_FALSE(CardPictureLayer::unitSquareToQuadInverse(flat, inverse));
}

TEST(DefaultCardPicture, IsDeterministicAndAPicture)
{
    const vision::ImageBuffer a = render::defaultCardPicture({320, 240});
    const vision::ImageBuffer b = render::defaultCardPicture({320, 240});
    const vision::ConstImageView va = a.view();
    const vision::ConstImageView vb = b.view();
    ASSERT_EQ(va.format, PixelFormat::RGB24);
    ASSERT_EQ(va.width, 320);
    ASSERT_EQ(va.height, 240);
    std::set<std::uint32_t> colours;
    double sum = 0, sumSquares = 0;
    for (int y = 0; y < va.height; ++y) {
        ASSERT_EQ(std::memcmp(va.row(y), vb.row(y), 320 * 3), 0) << "row " << y;
        for (int x = 0; x < va.width; ++x) {
            const std::uint8_t* p = va.row(y) + x * 3;
            colours.insert(static_cast<std::uint32_t>(p[0] << 16 | p[1] << 8 | p[2]));
            const double luma = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
            sum += luma;
            sumSquares += luma * luma;
        }
    }
    const double n = 320.0 * 240.0;
    const double sd = std::sqrt(sumSquares / n - (sum / n) * (sum / n));
    EXPECT_GT(colours.size(), 500u);  // graded sky, not a few flat fills
    EXPECT_GT(sd, 30.0);              // contrast: bright sky and sun, dark mountains and frame
    // Not symmetric either way (it is a scene, not a pattern), and the sky is above the lake.
    const std::uint8_t* top = va.row(40) + 160 * 3;
    const std::uint8_t* bottom = va.row(225 - 20) + 160 * 3;
    EXPECT_NE(std::memcmp(top, bottom, 3), 0);

    // Other sizes and aspects work, down to tiny ones.
    for (const vision::Size size : {vision::Size{1, 1}, vision::Size{7, 3}, vision::Size{64, 256}})
        EXPECT_EQ(render::defaultCardPicture(size).view().size(), size);
    EXPECT_THROW(render::defaultCardPicture({0, 10}), std::invalid_argument);

    // For a person to look at: build/test-output/default_card_picture/picture.png.
    const std::string dir = testing_support::freshOutputDir("default_card_picture");
    const vision::ImageBuffer big = render::defaultCardPicture({640, 480});
    platform::PngWriter png;
    EXPECT_TRUE(png.write((dir + "/picture.png").c_str(), big.view().data, 640, 480,
                          static_cast<std::size_t>(big.view().stride)))
        << png.lastError();
}

TEST_F(CardPictureLayerTest, DefaultPictureOnATiltedCard)
{
    // An end-to-end look: the default picture on a perspective card, written for a person.
    gl.resize(kWidth * 4, kHeight * 4);
    Renderer renderer({kWidth, kHeight}, PixelFormat::RGB24, options());
    const vision::ImageBuffer picture = render::defaultCardPicture({400, 300});
    CardPictureLayer layer(picture.view(), {kWidth, kHeight});
    renderer.addLayer(&layer);
    vision::ImageBuffer mask = solidImage(kWidth, kHeight, PixelFormat::Gray8, 255);
    fillRect(mask, 70, 50, 85, 100, 0);  // a finger
    const Quad quad{{{40.f, 15.f}, {110.f, 25.f}, {120.f, 85.f}, {25.f, 80.f}}};
    const CardObservation card = tracking(quad, mask);
    frame(renderer, layer, &card);
    const std::string dir = testing_support::freshOutputDir("card_picture_layer");
    platform::PngWriter png;
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(gl.width()) * gl.height() * 4);
    glReadPixels(0, 0, gl.width(), gl.height(), GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    EXPECT_TRUE(png.write((dir + "/tilted.png").c_str(), pixels.data(), gl.width(), gl.height(),
                          static_cast<std::size_t>(gl.width()) * 4, platform::PngInputLayout::Rgbx,
                          platform::PngRowOrder::BottomUp))
        << png.lastError();
}

}  // namespace
