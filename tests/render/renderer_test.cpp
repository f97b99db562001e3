#include "render/renderer.hpp"

#include "../../render/src/gl_program.hpp"  // private helper, tested directly for its errors
#include "alloc_counter.hpp"
#include "gl_test_context.hpp"
#include "render/hud_text.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

using render::Fit;
using render::Renderer;
using render::RendererOptions;
using testing_support::GlTestContext;
using testing_support::Rgba;
using vision::PixelFormat;

// An owned test image; rows may be padded beyond width * bytesPerPixel.
struct TestImage {
    int width = 0;
    int height = 0;
    int stride = 0;
    PixelFormat format = PixelFormat::RGB24;
    std::vector<std::uint8_t> bytes;

    vision::ConstImageView view() const { return {bytes.data(), width, height, stride, format}; }
};

using ColorFunction = std::function<Rgba(int x, int y)>;

// Distinct colours everywhere, asymmetric left-right and top-bottom.
Rgba pattern(int x, int y)
{
    return {x * 4 % 256, y * 5 % 256, (x * 7 + y * 3) % 256, 255};
}

TestImage makeImage(int width, int height, PixelFormat format, const ColorFunction& color,
                    int padding = 0)
{
    TestImage image;
    image.width = width;
    image.height = height;
    image.format = format;
    image.stride = width * vision::bytesPerPixel(format) + padding;
    image.bytes.assign(static_cast<std::size_t>(image.stride) * height, 0xAB);  // padding junk
    for (int y = 0; y < height; ++y) {
        std::uint8_t* p = image.bytes.data() + static_cast<std::size_t>(y) * image.stride;
        for (int x = 0; x < width; ++x) {
            const Rgba c = color(x, y);
            const auto r = static_cast<std::uint8_t>(c.r);
            const auto g = static_cast<std::uint8_t>(c.g);
            const auto b = static_cast<std::uint8_t>(c.b);
            switch (format) {
                case PixelFormat::RGB24:
                    *p++ = r, *p++ = g, *p++ = b;
                    break;
                case PixelFormat::BGR24:
                    *p++ = b, *p++ = g, *p++ = r;
                    break;
                case PixelFormat::XRGB8888:
                    *p++ = b, *p++ = g, *p++ = r, *p++ = 0x5A;
                    break;
                case PixelFormat::Gray8:
                    *p++ = r;
                    break;
                default:
                    throw std::logic_error("test image format");
            }
        }
    }
    return image;
}

// Counts pixels of the last read() farther than `tolerance` from `expected`; reports the first.
int countMismatches(const GlTestContext& gl, const ColorFunction& expected, int tolerance = 2,
                    bool report = true)
{
    int mismatches = 0;
    for (int y = 0; y < gl.height(); ++y) {
        for (int x = 0; x < gl.width(); ++x) {
            const Rgba got = gl.pixel(x, y);
            const Rgba want = expected(x, y);
            if (std::abs(got.r - want.r) > tolerance || std::abs(got.g - want.g) > tolerance ||
                std::abs(got.b - want.b) > tolerance) {
                if (mismatches++ == 0 && report)
                    ADD_FAILURE() << "first mismatch at (" << x << "," << y << "): got " << got.r
                                  << "," << got.g << "," << got.b << " want " << want.r << ","
                                  << want.g << "," << want.b;
            }
        }
    }
    return mismatches;
}

::testing::AssertionResult near(Rgba got, Rgba want, int tolerance = 3)
{
    if (std::abs(got.r - want.r) <= tolerance && std::abs(got.g - want.g) <= tolerance &&
        std::abs(got.b - want.b) <= tolerance)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "got " << got.r << "," << got.g << "," << got.b
                                         << " want " << want.r << "," << want.g << "," << want.b;
}

RendererOptions options(bool mirror, Fit fit = Fit::Cover, bool hud = false)
{
    RendererOptions o;
    o.mirror = mirror;
    o.fit = fit;
    o.hud = hud;
    return o;
}

// Draws one frame into the context's framebuffer and reads it back.
void drawAndRead(GlTestContext& gl, Renderer& renderer, const TestImage& image,
                 const char* hud = "")
{
    ASSERT_TRUE(renderer.draw(image.view(), gl.width(), gl.height(), hud)) << renderer.lastError();
    gl.read();
}

TEST(Renderer, WithoutMirrorTheOutputIsTheImage)
{
    GlTestContext gl(64, 48);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(false));
    drawAndRead(gl, renderer, makeImage(64, 48, PixelFormat::RGB24, pattern));
    EXPECT_EQ(countMismatches(gl, pattern), 0);
}

TEST(Renderer, MirrorFlipsLeftRight)
{
    GlTestContext gl(64, 48);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(true));
    drawAndRead(gl, renderer, makeImage(64, 48, PixelFormat::RGB24, pattern));
    EXPECT_EQ(countMismatches(gl, [](int x, int y) { return pattern(63 - x, y); }), 0);
}

struct RotationCase {
    int degrees;
    int displayWidth;
    int displayHeight;
    /// The image pixel (x, y) shown at display pixel (dx, dy), both counted from the top-left.
    std::function<std::pair<int, int>(int dx, int dy)> source;
};

class RendererRotation : public ::testing::TestWithParam<RotationCase> {};

// A portrait panel: the whole picture turns clockwise onto the display, exactly (no scaling).
TEST_P(RendererRotation, TurnsThePictureClockwise)
{
    const RotationCase c = GetParam();
    GlTestContext gl(c.displayWidth, c.displayHeight);
    RendererOptions o = options(false);
    o.rotation = c.degrees;
    Renderer renderer({64, 48}, PixelFormat::RGB24, o);
    drawAndRead(gl, renderer, makeImage(64, 48, PixelFormat::RGB24, pattern));
    EXPECT_EQ(countMismatches(gl,
                              [&](int x, int y) {
                                  const auto [sx, sy] = c.source(x, y);
                                  return pattern(sx, sy);
                              }),
              0);
}

INSTANTIATE_TEST_SUITE_P(Degrees, RendererRotation,
                         ::testing::Values(RotationCase{90, 48, 64,
                                                        [](int dx, int dy) {
                                                            return std::pair{dy, 47 - dx};
                                                        }},
                                           RotationCase{180, 64, 48,
                                                        [](int dx, int dy) {
                                                            return std::pair{63 - dx, 47 - dy};
                                                        }},
                                           RotationCase{270, 48, 64,
                                                        [](int dx, int dy) {
                                                            return std::pair{63 - dy, dx};
                                                        }}),
                         [](const ::testing::TestParamInfo<RotationCase>& p) {
                             return "Rotation" + std::to_string(p.param.degrees);
                         });

TEST(Renderer, RotationOtherThanQuarterTurnsIsRefused)
{
    GlTestContext gl(64, 48);
    RendererOptions o = options(false);
    o.rotation = 45;
    EXPECT_THROW(Renderer({64, 48}, PixelFormat::RGB24, o), std::runtime_error);
}

struct FormatCase {
    PixelFormat format;
    int padding;
};

class RendererFormats : public ::testing::TestWithParam<FormatCase> {};

TEST_P(RendererFormats, GiveTheSamePictureAsRgb24)
{
    const FormatCase c = GetParam();
    // Gray8 carries one channel: compare with the RGB24 picture of equal R, G and B.
    const ColorFunction color = c.format == PixelFormat::Gray8 ? ColorFunction([](int x, int y) {
        const int v = pattern(x, y).r;
        return Rgba{v, v, v, 255};
    })
                                                               : ColorFunction(pattern);
    GlTestContext gl(64, 48);
    Renderer renderer({64, 48}, c.format, options(true));
    drawAndRead(gl, renderer, makeImage(64, 48, c.format, color, c.padding));
    EXPECT_EQ(countMismatches(gl, [&](int x, int y) { return color(63 - x, y); }), 0);
}

INSTANTIATE_TEST_SUITE_P(
    All, RendererFormats,
    ::testing::Values(FormatCase{PixelFormat::RGB24, 0}, FormatCase{PixelFormat::BGR24, 0},
                      FormatCase{PixelFormat::XRGB8888, 0}, FormatCase{PixelFormat::Gray8, 0},
                      FormatCase{PixelFormat::RGB24, 7}, FormatCase{PixelFormat::BGR24, 64},
                      FormatCase{PixelFormat::XRGB8888, 16}, FormatCase{PixelFormat::Gray8, 3}),
    [](const auto& testInfo) {
        return std::string(vision::pixelFormatName(testInfo.param.format)) + "_padding" +
               std::to_string(testInfo.param.padding);
    });

// 640x480: red rows 0..59, blue rows 420..479, green between.
Rgba bands(int, int y)
{
    if (y < 60)
        return {255, 0, 0, 255};
    if (y >= 420)
        return {0, 0, 255, 255};
    return {0, 255, 0, 255};
}
constexpr Rgba kRed{255, 0, 0, 255};
constexpr Rgba kGreen{0, 255, 0, 255};
constexpr Rgba kBlue{0, 0, 255, 255};
constexpr Rgba kBlack{0, 0, 0, 255};

TEST(Renderer, ContainShowsTheWholeImageBetweenBlackBars)
{
    // 4:3 on 16:9 at 1.5x: 960 pixels wide, centred, 160-pixel bars left and right.
    GlTestContext gl(1280, 720);
    Renderer renderer({640, 480}, PixelFormat::RGB24, options(true, Fit::Contain));
    drawAndRead(gl, renderer, makeImage(640, 480, PixelFormat::RGB24, bands));
    for (int x : {0, 80, 159, 1120, 1200, 1279})
        EXPECT_TRUE(near(gl.pixel(x, 360), kBlack)) << "bar pixel x=" << x;
    for (int x : {160, 640, 1119})
        EXPECT_TRUE(near(gl.pixel(x, 360), kGreen)) << "image pixel x=" << x;
    EXPECT_TRUE(near(gl.pixel(640, 10), kRed));    // image row 7
    EXPECT_TRUE(near(gl.pixel(640, 709), kBlue));  // image row 473
}

TEST(Renderer, CoverFillsTheScreenAndCropsSymmetrically)
{
    // 4:3 on 16:9 at 2x: 1280x960, 120 screen rows (60 image rows) cut at top and bottom, so
    // the red and blue bands are (nearly) gone.
    GlTestContext gl(1280, 720);
    Renderer renderer({640, 480}, PixelFormat::RGB24, options(true, Fit::Cover));
    drawAndRead(gl, renderer, makeImage(640, 480, PixelFormat::RGB24, bands));
    for (int x : {0, 640, 1279}) {
        EXPECT_TRUE(near(gl.pixel(x, 360), kGreen)) << "x=" << x;
        EXPECT_TRUE(near(gl.pixel(x, 2), kGreen)) << "x=" << x;
        EXPECT_TRUE(near(gl.pixel(x, 717), kGreen)) << "x=" << x;
        // The edge rows sample a quarter of the first cropped row (linear filtering).
        EXPECT_GT(gl.pixel(x, 0).g, 150);
        EXPECT_LT(gl.pixel(x, 0).r, 100);
        EXPECT_LT(gl.pixel(x, 719).b, 100);
    }
}

struct NdcCase {
    int viewportWidth;
    int viewportHeight;
    Fit fit;
    bool mirror;
    float left, top, right, bottom;  // NDC of image x = 0, y = 0, x = 640, y = 480
};

class RendererImageToNdc : public ::testing::TestWithParam<NdcCase> {};

TEST_P(RendererImageToNdc, MapsTheImageCorners)
{
    const NdcCase c = GetParam();
    GlTestContext gl(c.viewportWidth, c.viewportHeight);
    Renderer renderer({640, 480}, PixelFormat::RGB24, options(c.mirror, c.fit));
    drawAndRead(gl, renderer, makeImage(640, 480, PixelFormat::RGB24, bands));
    const render::LayerContext& context = renderer.layerContext();
    const auto ndcX = [&](float x) { return context.imageToNdc[0] * x + context.imageToNdc[1]; };
    const auto ndcY = [&](float y) { return context.imageToNdc[2] * y + context.imageToNdc[3]; };
    EXPECT_NEAR(ndcX(0.f), c.left, 1e-5);
    EXPECT_NEAR(ndcX(640.f), c.right, 1e-5);
    EXPECT_NEAR(ndcY(0.f), c.top, 1e-5);
    EXPECT_NEAR(ndcY(480.f), c.bottom, 1e-5);
    EXPECT_EQ(context.image, (vision::Size{640, 480}));
    EXPECT_EQ(context.viewportWidth, c.viewportWidth);
    EXPECT_EQ(context.viewportHeight, c.viewportHeight);
    EXPECT_EQ(context.mirrored, c.mirror);
    EXPECT_EQ(context.imageToNdc[0] < 0.f, c.mirror);
}

constexpr float kWide = 4.f / 3.f;           // 4:3 covering 16:9: 1280x960 in 1280x720
constexpr float kTall = (4.f / 3.f) / 0.6f;  // 4:3 covering 480x800: 1066.7 wide in 480
INSTANTIATE_TEST_SUITE_P(
    All, RendererImageToNdc,
    ::testing::Values(NdcCase{1280, 720, Fit::Contain, false, -0.75f, 1.f, 0.75f, -1.f},
                      NdcCase{1280, 720, Fit::Contain, true, 0.75f, 1.f, -0.75f, -1.f},
                      NdcCase{1280, 720, Fit::Cover, false, -1.f, kWide, 1.f, -kWide},
                      NdcCase{1280, 720, Fit::Cover, true, 1.f, kWide, -1.f, -kWide},
                      NdcCase{480, 800, Fit::Contain, false, -1.f, 0.45f, 1.f, -0.45f},
                      NdcCase{480, 800, Fit::Contain, true, 1.f, 0.45f, -1.f, -0.45f},
                      NdcCase{480, 800, Fit::Cover, false, -kTall, 1.f, kTall, -1.f},
                      NdcCase{480, 800, Fit::Cover, true, kTall, 1.f, -kTall, -1.f},
                      NdcCase{640, 480, Fit::Cover, true, 1.f, 1.f, -1.f, -1.f}));

TEST(Renderer, HudTextIsDrawnTopLeftAndNotMirrored)
{
    GlTestContext gl(1280, 720);
    Renderer renderer({64, 48}, PixelFormat::Gray8, options(true, Fit::Cover, true));
    const TestImage gray = makeImage(64, 48, PixelFormat::Gray8, [](int, int) {
        return Rgba{128, 128, 128, 255};
    });
    drawAndRead(gl, renderer, gray, "L");

    const render::HudText::Layout l = render::HudText::layout("L", 720);
    ASSERT_EQ(l.scale, 2);
    ASSERT_EQ(l.lines, 1);
    // Box: 60% black over the 128 grey; outside it the video is untouched.
    EXPECT_LT(gl.pixel(l.boxX + 1, l.boxY + 1).r, 70);
    EXPECT_GT(gl.pixel(l.boxX + 1, l.boxY + 1).r, 35);
    EXPECT_TRUE(near(gl.pixel(l.boxX + l.boxWidth + 1, l.boxY + 1), {128, 128, 128, 255}));
    EXPECT_TRUE(near(gl.pixel(l.boxX + 1, l.boxY + l.boxHeight + 1), {128, 128, 128, 255}));
    EXPECT_TRUE(near(gl.pixel(l.boxX - 1, l.boxY + 1), {128, 128, 128, 255}));

    // "L" unmirrored: the left column is lit all the way down, the right one only at the foot.
    const char* picture[8] = {"#....", "#....", "#....", "#....",
                              "#....", "#....", "#####", "....."};
    for (int fy = 0; fy < 8; ++fy) {
        for (int fx = 0; fx < 5; ++fx) {
            const Rgba p = gl.pixel(l.textX + fx * l.scale + l.scale / 2,
                                    l.textY + fy * l.scale + l.scale / 2);
            if (picture[fy][fx] == '#')
                EXPECT_GT(p.r, 240) << "font pixel " << fx << "," << fy << " should be lit";
            else
                EXPECT_LT(p.r, 70) << "font pixel " << fx << "," << fy << " should be dark";
        }
    }
}

TEST(Renderer, HudOffOrEmptyLeavesTheVideoUntouched)
{
    GlTestContext gl(64, 48);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(false, Fit::Cover, true));
    const TestImage image = makeImage(64, 48, PixelFormat::RGB24, pattern);

    drawAndRead(gl, renderer, image, "fps 30");
    EXPECT_GT(countMismatches(gl, pattern, 2, false), 0) << "the HUD should have drawn something";

    renderer.setHudVisible(false);
    EXPECT_FALSE(renderer.hudVisible());
    drawAndRead(gl, renderer, image, "fps 30");
    EXPECT_EQ(countMismatches(gl, pattern), 0);

    renderer.setHudVisible(true);
    drawAndRead(gl, renderer, image, "");
    EXPECT_EQ(countMismatches(gl, pattern), 0);
    drawAndRead(gl, renderer, image, nullptr);
    EXPECT_EQ(countMismatches(gl, pattern), 0);
}

TEST(HudText, LayoutScalesWithTheViewportAndTruncates)
{
    EXPECT_EQ(render::HudText::layout("x", 240).scale, 1);
    EXPECT_EQ(render::HudText::layout("x", 480).scale, 1);
    EXPECT_EQ(render::HudText::layout("x", 720).scale, 2);
    EXPECT_EQ(render::HudText::layout("x", 1080).scale, 3);
    EXPECT_EQ(render::HudText::layout("x", 2160).scale, 6);

    EXPECT_EQ(render::HudText::layout("", 720).lines, 0);
    EXPECT_EQ(render::HudText::layout(nullptr, 720).lines, 0);
    EXPECT_EQ(render::HudText::layout("fps\n", 720).lines, 1);
    EXPECT_EQ(render::HudText::layout("a\n\nbcd", 720).lines, 3);
    EXPECT_EQ(render::HudText::layout("a\n\nbcd", 720).columns, 3);

    std::string many;
    for (int i = 0; i < 20; ++i)
        many += std::string(100, 'W') + "\n";
    const render::HudText::Layout l = render::HudText::layout(many.c_str(), 720);
    EXPECT_EQ(l.lines, render::HudText::kMaxLines);
    EXPECT_EQ(l.columns, render::HudText::kMaxColumns);
    EXPECT_EQ(l.boxWidth, l.columns * l.cellWidth - l.scale + 2 * (l.textX - l.boxX));
    // A line is about 2.5% of the height.
    EXPECT_NEAR(static_cast<double>(l.cellHeight) / 720, 0.025, 0.005);
}

TEST(Renderer, LongHudTextIsTruncatedNotOverflowed)
{
    GlTestContext gl(320, 240);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(true, Fit::Cover, true));
    std::string many;
    for (int i = 0; i < 50; ++i)
        many += std::string(200, '#') + "\t\x7f\n";  // non-printables show as '?'
    ASSERT_TRUE(renderer.draw(makeImage(64, 48, PixelFormat::RGB24, pattern).view(), 320, 240,
                              many.c_str()))
        << renderer.lastError();
}

class RecordingLayer : public render::OverlayLayer {
public:
    explicit RecordingLayer(std::vector<const char*>& order, const char* name)
        : order_(order), name_(name)
    {
    }
    const char* name() const noexcept override { return name_; }
    void draw(const render::LayerContext& context) noexcept override
    {
        ++calls;
        last = context;
        blendEnabled = glIsEnabled(GL_BLEND);
        depthTestEnabled = glIsEnabled(GL_DEPTH_TEST);
        order_.push_back(name_);
    }

    int calls = 0;
    render::LayerContext last;
    GLboolean blendEnabled = GL_FALSE;
    GLboolean depthTestEnabled = GL_TRUE;

private:
    std::vector<const char*>& order_;
    const char* name_;
};

TEST(Renderer, LayersAreDrawnOncePerFrameInOrderWithTheContext)
{
    GlTestContext gl(128, 72);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(true, Fit::Cover, true));
    std::vector<const char*> order;
    RecordingLayer first(order, "first");
    RecordingLayer second(order, "second");
    renderer.addLayer(&first);
    renderer.addLayer(&second);
    const TestImage image = makeImage(64, 48, PixelFormat::RGB24, pattern);

    drawAndRead(gl, renderer, image, "hud");
    EXPECT_EQ(first.calls, 1);
    EXPECT_EQ(second.calls, 1);
    drawAndRead(gl, renderer, image, "hud");
    EXPECT_EQ(first.calls, 2);
    EXPECT_EQ(second.calls, 2);
    EXPECT_EQ(order, (std::vector<const char*>{"first", "second", "first", "second"}));

    EXPECT_EQ(first.blendEnabled, GL_TRUE);
    EXPECT_EQ(first.depthTestEnabled, GL_FALSE);
    EXPECT_EQ(first.last.viewportWidth, 128);
    EXPECT_EQ(first.last.viewportHeight, 72);
    EXPECT_EQ(first.last.image, (vision::Size{64, 48}));
    EXPECT_TRUE(first.last.mirrored);
    for (int i = 0; i < 4; ++i)
        EXPECT_EQ(first.last.imageToNdc[i], renderer.layerContext().imageToNdc[i]);
}

TEST(Renderer, AtMostMaxLayers)
{
    GlTestContext gl(64, 48);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(true));
    std::vector<const char*> order;
    RecordingLayer layer(order, "layer");
    for (std::size_t i = 0; i < Renderer::kMaxLayers; ++i)
        renderer.addLayer(&layer);
    EXPECT_THROW(renderer.addLayer(&layer), std::runtime_error);
    EXPECT_THROW(renderer.addLayer(nullptr), std::runtime_error);
}

class BrokenLayer : public render::OverlayLayer {
public:
    const char* name() const noexcept override { return "broken"; }
    void draw(const render::LayerContext&) noexcept override
    {
        if (broken)
            glEnable(0x1234);  // GL_INVALID_ENUM
    }
    bool broken = true;
};

TEST(Renderer, GlErrorMakesDrawFailWithTheCode)
{
    GlTestContext gl(64, 48);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(true));
    BrokenLayer layer;
    renderer.addLayer(&layer);
    const TestImage image = makeImage(64, 48, PixelFormat::RGB24, pattern);
    EXPECT_FALSE(renderer.draw(image.view(), 64, 48, ""));
    EXPECT_STREQ(renderer.lastError(), "GL error 0x0500 after draw");
    layer.broken = false;
    EXPECT_TRUE(renderer.draw(image.view(), 64, 48, "")) << renderer.lastError();
}

TEST(Renderer, FrameOfAnotherSizeOrFormatIsRefused)
{
    GlTestContext gl(64, 48);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(true));
    EXPECT_FALSE(renderer.draw(makeImage(32, 24, PixelFormat::RGB24, pattern).view(), 64, 48, ""));
    EXPECT_NE(std::strstr(renderer.lastError(), "32x24"), nullptr) << renderer.lastError();
    EXPECT_FALSE(renderer.draw(makeImage(64, 48, PixelFormat::BGR24, pattern).view(), 64, 48, ""));
    EXPECT_FALSE(renderer.draw(makeImage(64, 48, PixelFormat::RGB24, pattern).view(), 0, 48, ""));
}

TEST(Renderer, EmptyFrameRedrawsTheLastOne)
{
    GlTestContext gl(64, 48);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(false));
    // Before any frame the video is black.
    ASSERT_TRUE(renderer.draw({}, 64, 48, "")) << renderer.lastError();
    gl.read();
    EXPECT_EQ(countMismatches(gl, [](int, int) { return kBlack; }), 0);
    drawAndRead(gl, renderer, makeImage(64, 48, PixelFormat::RGB24, pattern));
    ASSERT_TRUE(renderer.draw({}, 64, 48, "")) << renderer.lastError();
    gl.read();
    EXPECT_EQ(countMismatches(gl, pattern), 0);
}

TEST(Renderer, UnsupportedFormatThrowsOneLine)
{
    GlTestContext gl(64, 48);
    try {
        Renderer renderer({64, 48}, PixelFormat::YUYV, options(true));
        FAIL() << "YUYV accepted";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("YUYV"), std::string::npos) << what;
        EXPECT_NE(what.find("unsupported"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

TEST(GlProgram, CompileErrorIsOneLineWithTheLog)
{
    GlTestContext gl(8, 8);
    const char* vertex =
        "#version 100\nattribute vec2 a;\nvoid main() { gl_Position = vec4(a, 0.0, 1.0); }\n";
    try {
        render::detail::GlProgram program(
            "broken", vertex, "#version 100\nvoid main() { gl_FragColor = oops; }\n", {"a"});
        FAIL() << "a broken shader compiled";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("broken fragment shader does not compile: ", 0), 0u) << what;
        EXPECT_GT(what.size(), std::strlen("broken fragment shader does not compile: ") + 3);
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

TEST(Renderer, DrawDoesNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting is not available in this build";
    GlTestContext gl(320, 240);
    Renderer renderer({64, 48}, PixelFormat::RGB24, options(true, Fit::Contain, true));
    std::vector<const char*> order;
    order.reserve(16);
    RecordingLayer layer(order, "layer");
    renderer.addLayer(&layer);
    const TestImage tight = makeImage(64, 48, PixelFormat::RGB24, pattern);
    const TestImage padded = makeImage(64, 48, PixelFormat::RGB24, pattern, 5);
    // Warm up both upload paths: llvmpipe compiles shader variants (with LLVM, in C++, so its
    // operator new calls count too) on the first draws of each new GL state.
    for (int i = 0; i < 4; ++i)
        ASSERT_TRUE(renderer.draw(i % 2 ? padded.view() : tight.view(), 320, 240, "warm up"))
            << renderer.lastError();

    testing_support::AllocationScope scope;
    bool ok = renderer.draw(tight.view(), 320, 240, "fps 30.0\nfaces 1");
    ok = renderer.draw(padded.view(), 320, 240, "fps 29.9\nfaces 2") && ok;
    const testing_support::AllocationCounts counts = scope.counts();
    EXPECT_TRUE(ok) << renderer.lastError();
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
}

}  // namespace
