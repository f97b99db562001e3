// CardSceneSource: a perspective card composited over inner frames, with ground-truth corners.

#include "platform/card_scene_source.hpp"

#include "alloc_counter.hpp"
#include "platform/card_raster.hpp"
#include "platform/synthetic_source.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {

using platform::CardSceneOptions;
using platform::CardSceneSource;
using platform::SourceStatus;
using vision::Point2f;

/// A known inner source: a byte pattern that depends on position and sequence.
class PatternSource final : public platform::FrameSource {
public:
    PatternSource(int width, int height, vision::PixelFormat format, int frames = -1)
        : buffer_(width, height, format), frames_(frames)
    {
    }

    static std::uint8_t value(int x, int y, int byte, std::uint64_t sequence)
    {
        return static_cast<std::uint8_t>((x * 3 + y * 5 + byte * 70 + sequence * 11) & 255);
    }

    const char* description() const noexcept override { return "pattern"; }
    vision::Size size() const noexcept override { return buffer_.view().size(); }
    vision::PixelFormat format() const noexcept override { return buffer_.view().format; }
    const char* lastError() const noexcept override { return lost_ ? "pattern: unplugged" : ""; }

    SourceStatus next(vision::Frame& frame) noexcept override
    {
        if (lost_)
            return SourceStatus::Lost;
        if (frames_ >= 0 && sequence_ >= static_cast<std::uint64_t>(frames_))
            return SourceStatus::EndOfStream;
        const vision::ImageView v = buffer_.view();
        const int bpp = vision::bytesPerPixel(v.format);
        for (int y = 0; y < v.height; ++y)
            for (int x = 0; x < v.width; ++x)
                for (int b = 0; b < bpp; ++b)
                    v.row(y)[x * bpp + b] = value(x, y, b, sequence_);
        frame.image = v;
        frame.sequence = sequence_++;
        frame.timestampNs = 1000 + static_cast<std::int64_t>(frame.sequence);
        return SourceStatus::Ok;
    }

    vision::ImageView view() noexcept { return buffer_.view(); }
    bool lost_ = false;

private:
    vision::ImageBuffer buffer_;
    int frames_;
    std::uint64_t sequence_ = 0;
};

/// Signed distance of (x, y) to the quad's boundary, positive inside (corners clockwise on screen).
double insideDistance(const std::array<Point2f, 4>& c, double x, double y)
{
    double d = 1e9;
    for (int i = 0; i < 4; ++i) {
        const Point2f p = c[i], q = c[(i + 1) % 4];
        const double ex = q.x - p.x, ey = q.y - p.y;
        d = std::min(d, (ex * (y - p.y) - ey * (x - p.x)) / std::hypot(ex, ey));
    }
    return d;
}

double cross(Point2f o, Point2f a, Point2f b)
{
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

TEST(CardSceneSource, CornersAreClockwiseConvexAndInsideTheFrame)
{
    for (const vision::Size size : {vision::Size{640, 480}, vision::Size{720, 528},
                                    vision::Size{480, 640}, vision::Size{64, 48}}) {
        CardSceneSource card(
            std::make_unique<PatternSource>(size.width, size.height, vision::PixelFormat::RGB24));
        for (std::uint64_t seq = 0; seq < 3000; seq += 7) {
            const auto c = card.cornersFor(seq);
            for (int i = 0; i < 4; ++i) {
                // Clockwise on screen (y down): every turn is to the right.
                EXPECT_GT(cross(c[i], c[(i + 1) % 4], c[(i + 2) % 4]), 0.0) << "seq " << seq;
                EXPECT_GE(c[i].x, 0.0f);
                EXPECT_GE(c[i].y, 0.0f);
                EXPECT_LE(c[i].x, size.width - 1.0f);
                EXPECT_LE(c[i].y, size.height - 1.0f);
            }
            // The first corner is the top-left one: smallest x + y.
            for (int i = 1; i < 4; ++i)
                EXPECT_LT(c[0].x + c[0].y, c[i].x + c[i].y) << "seq " << seq;
        }
    }
}

TEST(CardSceneSource, TrainingIntroHoldsTheCardOverTheCentreThenJoinsThePath)
{
    for (const vision::Size size : {vision::Size{640, 480}, vision::Size{720, 528}}) {
        CardSceneOptions options;
        options.introFrames = 30;
        CardSceneSource held(
            std::make_unique<PatternSource>(size.width, size.height, vision::PixelFormat::RGB24),
            options);
        CardSceneSource plain(
            std::make_unique<PatternSource>(size.width, size.height, vision::PixelFormat::RGB24));
        // Held still during the intro, covering the central half of the view (what `card train`
        // learns from with the default train_fraction 0.5), with a margin of a few pixels.
        const auto c0 = held.cornersFor(0);
        EXPECT_EQ(c0, held.cornersFor(29));
        const double x0 = 0.25 * size.width, x1 = 0.75 * size.width;
        const double y0 = 0.25 * size.height, y1 = 0.75 * size.height;
        for (const auto& [x, y] : {std::pair{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}})
            EXPECT_GT(insideDistance(c0, x, y), 3.0) << x << "," << y;
        // Easing into the path: always inside the frame and clockwise.
        for (std::uint64_t seq = 30; seq < 60; ++seq) {
            const auto c = held.cornersFor(seq);
            for (int i = 0; i < 4; ++i) {
                EXPECT_GT(cross(c[i], c[(i + 1) % 4], c[(i + 2) % 4]), 0.0) << "seq " << seq;
                EXPECT_GE(c[i].x, 0.0f);
                EXPECT_GE(c[i].y, 0.0f);
                EXPECT_LE(c[i].x, size.width - 1.0f);
                EXPECT_LE(c[i].y, size.height - 1.0f);
            }
        }
        // Then exactly the path of a card without intro, shifted by the intro's length.
        for (std::uint64_t seq = 60; seq < 400; seq += 13)
            EXPECT_EQ(held.cornersFor(seq), plain.cornersFor(seq - 30)) << "seq " << seq;
    }
}

TEST(CardSceneSource, APathCentredInACornerKeepsTheCardThereAndInsideTheFrame)
{
    // The demo video's card: trained over the centre, then kept to the lower right of the
    // camera's frame (the mirrored screen's lower left), clear of the faces in the middle.
    const vision::Size size{720, 528};
    CardSceneOptions options;
    options.introFrames = 12;
    options.heightFraction = 0.24;
    options.pathCentreX = 0.8;
    options.pathCentreY = 0.72;
    CardSceneSource card(
        std::make_unique<PatternSource>(size.width, size.height, vision::PixelFormat::RGB24),
        options);
    float minX = 1e9f, maxX = 0.f, minY = 1e9f;
    for (std::uint64_t seq = 24; seq < 3000; seq += 5) {
        for (const auto& p : card.cornersFor(seq)) {
            EXPECT_GE(p.x, 0.0f);
            EXPECT_LE(p.x, size.width - 1.0f);
            EXPECT_LE(p.y, size.height - 1.0f);
            minX = std::min(minX, p.x);
            maxX = std::max(maxX, p.x);
            minY = std::min(minY, p.y);
        }
    }
    EXPECT_GT(minX, 0.5f * size.width);   // never over the middle of the view
    EXPECT_GT(minY, 0.4f * size.height);  // nor over the upper part, where the heads are
    EXPECT_GT(maxX - minX, 0.25f * size.width) << "it still moves";
}

TEST(CardSceneSource, CardIsAboutAThirdOfTheFrameHeightAndMoves)
{
    CardSceneSource card(std::make_unique<PatternSource>(640, 480, vision::PixelFormat::RGB24));
    double minHeight = 1e9, maxHeight = 0.0;
    for (std::uint64_t seq = 0; seq < 1000; seq += 5) {
        const auto c = card.cornersFor(seq);
        const double left = std::hypot(c[3].x - c[0].x, c[3].y - c[0].y);
        const double right = std::hypot(c[2].x - c[1].x, c[2].y - c[1].y);
        minHeight = std::min(minHeight, std::min(left, right));
        maxHeight = std::max(maxHeight, std::max(left, right));
    }
    EXPECT_GT(minHeight, 0.2 * 480);
    EXPECT_LT(maxHeight, 0.4 * 480);
    const auto a = card.cornersFor(0);
    const auto b = card.cornersFor(30);
    EXPECT_GT(std::hypot(a[0].x - b[0].x, a[0].y - b[0].y), 5.0);
}

/// Checks one delivered frame: card colour well inside, inner pixels well outside.
void checkComposite(const CardSceneSource& card, const vision::Frame& frame)
{
    const CardSceneOptions& o = card.options();
    const auto corners = card.corners();
    const vision::ConstImageView img = frame.image;
    const int bpp = vision::bytesPerPixel(img.format);
    int rOff = 0, gOff = 1, bOff = 2;
    if (img.format != vision::PixelFormat::RGB24) {
        rOff = 2;
        bOff = 0;
    }
    const int expected[3] = {o.red, o.green, o.blue};
    const int offsets[3] = {rOff, gOff, bOff};
    long insidePixels = 0, outsidePixels = 0;
    int lowest = 255, highest = 0;  // of the card's strongest channel: shaded and noisy, not flat
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const double d = insideDistance(corners, x, y);
            const std::uint8_t* p = img.row(y) + x * bpp;
            if (d >= 1.0) {
                ++insidePixels;
                const int strongest = o.green >= o.red ? gOff : rOff;
                lowest = std::min<int>(lowest, p[strongest]);
                highest = std::max<int>(highest, p[strongest]);
                for (int c = 0; c < 3; ++c) {
                    const double tolerance = expected[c] * o.shading + o.noise + 1.0;
                    ASSERT_NEAR(p[offsets[c]], expected[c], tolerance)
                        << "inside at " << x << "," << y << " channel " << c;
                }
            } else if (d <= -1.0) {
                ++outsidePixels;
                for (int b = 0; b < bpp; ++b)
                    ASSERT_EQ(p[b], PatternSource::value(x, y, b, frame.sequence))
                        << "outside at " << x << "," << y;
            }
        }
    EXPECT_GT(insidePixels, 5000);
    EXPECT_GE(highest - lowest, 2 * o.noise);
    EXPECT_GT(outsidePixels, 100000);
}

TEST(CardSceneSource, CompositesOverRgbFrames)
{
    CardSceneSource card(std::make_unique<PatternSource>(640, 480, vision::PixelFormat::RGB24));
    EXPECT_EQ(card.format(), vision::PixelFormat::RGB24);
    EXPECT_EQ(card.size(), (vision::Size{640, 480}));
    vision::Frame frame;
    for (int k = 0; k < 40; ++k) {
        ASSERT_EQ(card.next(frame), SourceStatus::Ok);
        EXPECT_EQ(frame.sequence, static_cast<std::uint64_t>(k));
        EXPECT_EQ(frame.timestampNs, 1000 + k);
        if (k % 13 == 0)
            checkComposite(card, frame);
    }
}

TEST(CardSceneSource, CompositesOverBgrAndXrgbFramesInTheirByteOrder)
{
    for (const auto format : {vision::PixelFormat::BGR24, vision::PixelFormat::XRGB8888}) {
        CardSceneSource card(std::make_unique<PatternSource>(720, 528, format),
                             CardSceneOptions::magentaCard());
        EXPECT_EQ(card.format(), format);
        vision::Frame frame;
        ASSERT_EQ(card.next(frame), SourceStatus::Ok);
        checkComposite(card, frame);
    }
}

TEST(CardSceneSource, EdgesAreAntiAliased)
{
    // Pixels straddling an edge take intermediate values between the inner frame and the card.
    auto inner = std::make_unique<PatternSource>(640, 480, vision::PixelFormat::RGB24);
    CardSceneSource card(std::move(inner));
    vision::Frame frame;
    ASSERT_EQ(card.next(frame), SourceStatus::Ok);
    const auto corners = card.corners();
    int partial = 0;
    for (int y = 0; y < 480; ++y)
        for (int x = 0; x < 640; ++x) {
            const double d = insideDistance(corners, x, y);
            if (std::abs(d) > 0.25)
                continue;
            const std::uint8_t g = frame.image.row(y)[3 * x + 1];
            const int under = PatternSource::value(x, y, 1, 0);
            const int cardG = card.options().green;
            if (std::abs(g - under) > 8 && std::abs(g - cardG) > 20)
                ++partial;
        }
    EXPECT_GT(partial, 50);
}

TEST(CardSceneSource, IsDeterministicFromTheSequenceNumber)
{
    CardSceneSource a(std::make_unique<platform::SyntheticSource>(320, 240, 0.0));
    CardSceneSource b(std::make_unique<platform::SyntheticSource>(320, 240, 0.0));
    EXPECT_STREQ(a.description(), "synthetic (320x240 RGB24, max rate) + card #28ac4c");
    platform::SyntheticSource scene(320, 240, 0.0);
    vision::ImageBuffer expected(320, 240, vision::PixelFormat::RGB24);
    const auto before = a.corners();
    const auto first = a.cornersFor(0);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(before[i].x, first[i].x);
        EXPECT_EQ(before[i].y, first[i].y);
    }
    vision::Frame fa, fb;
    for (int k = 0; k < 20; ++k) {
        ASSERT_EQ(a.next(fa), SourceStatus::Ok);
        ASSERT_EQ(b.next(fb), SourceStatus::Ok);
        ASSERT_EQ(fa.sequence, fb.sequence);
        ASSERT_NE(fa.image.data, fb.image.data);
        // The delivered frame is exactly the scene of that index with the card of that index.
        ASSERT_TRUE(scene.renderFrame(fa.sequence, expected.view()));
        ASSERT_TRUE(a.drawCard(fa.sequence, expected.view()));
        for (int y = 0; y < 240; ++y) {
            ASSERT_EQ(std::memcmp(fa.image.row(y), fb.image.row(y), 320 * 3), 0);
            ASSERT_EQ(std::memcmp(fa.image.row(y), expected.view().row(y), 320 * 3), 0);
        }
        const auto now = a.corners();
        const auto recomputed = b.cornersFor(fa.sequence);
        for (int i = 0; i < 4; ++i) {
            EXPECT_EQ(now[i].x, recomputed[i].x);
            EXPECT_EQ(now[i].y, recomputed[i].y);
        }
    }
}

TEST(CardSceneSource, LeavesTheInnerFrameUntouched)
{
    auto owned = std::make_unique<PatternSource>(160, 120, vision::PixelFormat::BGR24);
    PatternSource* inner = owned.get();
    CardSceneSource card(std::move(owned));
    vision::Frame frame;
    ASSERT_EQ(card.next(frame), SourceStatus::Ok);
    // A second view of the inner buffer: the pattern of sequence 0 everywhere, card or not.
    const vision::ImageView v = inner->view();
    for (int y = 0; y < 120; ++y)
        for (int x = 0; x < 160 * 3; ++x)
            ASSERT_EQ(v.row(y)[x], PatternSource::value(x / 3, y, x % 3, 0));
}

TEST(CardSceneSource, PassesEndOfStreamAndLostThrough)
{
    auto owned = std::make_unique<PatternSource>(64, 48, vision::PixelFormat::RGB24, 2);
    PatternSource* inner = owned.get();
    CardSceneSource card(std::move(owned));
    vision::Frame frame;
    EXPECT_EQ(card.next(frame), SourceStatus::Ok);
    inner->lost_ = true;
    EXPECT_EQ(card.next(frame), SourceStatus::Lost);
    EXPECT_STREQ(card.lastError(), "pattern: unplugged");
    inner->lost_ = false;
    EXPECT_EQ(card.next(frame), SourceStatus::Ok);
    EXPECT_EQ(card.next(frame), SourceStatus::EndOfStream);
}

TEST(CardSceneSource, RejectsUnusableInnerSources)
{
    EXPECT_THROW(CardSceneSource(nullptr), std::runtime_error);
    EXPECT_THROW(
        CardSceneSource(std::make_unique<PatternSource>(64, 48, vision::PixelFormat::Gray8)),
        std::runtime_error);
    EXPECT_THROW(
        CardSceneSource(std::make_unique<PatternSource>(20, 48, vision::PixelFormat::RGB24)),
        std::runtime_error);
}

TEST(CardSceneSource, NextDoesNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting unavailable in this build";
    CardSceneSource card(std::make_unique<platform::SyntheticSource>(320, 240, 0.0));
    vision::Frame frame;
    ASSERT_EQ(card.next(frame), SourceStatus::Ok);
    testing_support::AllocationScope scope;
    for (int k = 0; k < 10; ++k)
        ASSERT_EQ(card.next(frame), SourceStatus::Ok);
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}

// drawCardQuad: the one card renderer, shared with cardgen.

vision::Quad rectQuad(float l, float t, float r, float b)
{
    return {Point2f{l, t}, Point2f{r, t}, Point2f{r, b}, Point2f{l, b}};
}

TEST(CardRaster, EdgeCoverageIsSubpixel)
{
    // Vertical edges at x = 20.25 and x = 60.25: the border pixels are 25 % and 75 % card.
    vision::ImageBuffer img(80, 40, vision::PixelFormat::RGB24);
    std::memset(img.view().data, 0, img.bytes());
    platform::CardPaint paint;
    paint.red = paint.green = paint.blue = 200;
    ASSERT_TRUE(platform::drawCardQuad(img.view(), rectQuad(20.25f, 5.f, 60.25f, 35.f), paint));
    const std::uint8_t* row = img.view().row(20);
    EXPECT_EQ(row[19 * 3], 0);
    EXPECT_NEAR(row[20 * 3], 50, 4);
    EXPECT_EQ(row[21 * 3], 200);
    EXPECT_EQ(row[59 * 3], 200);
    EXPECT_NEAR(row[60 * 3], 150, 4);
    EXPECT_EQ(row[61 * 3], 0);
}

TEST(CardRaster, HomographyMapsTheUnitSquareOntoTheCorners)
{
    const vision::Quad q = {Point2f{10, 12}, Point2f{90, 20}, Point2f{80, 70}, Point2f{15, 60}};
    double m[9];
    platform::cardToImageHomography(q, m);
    const double us[4] = {-1, 1, 1, -1}, vs[4] = {-1, -1, 1, 1};
    for (int i = 0; i < 4; ++i) {
        const double w = m[6] * us[i] + m[7] * vs[i] + m[8];
        EXPECT_NEAR((m[0] * us[i] + m[1] * vs[i] + m[2]) / w, q[i].x, 1e-9);
        EXPECT_NEAR((m[3] * us[i] + m[4] * vs[i] + m[5]) / w, q[i].y, 1e-9);
    }
}

TEST(CardRaster, ClipsQuadsPartlyOrWhollyOutsideAndRejectsOtherFormats)
{
    vision::ImageBuffer img(40, 30, vision::PixelFormat::XRGB8888);
    std::memset(img.view().data, 0, img.bytes());
    platform::CardPaint paint;
    // Wholly outside: nothing drawn.
    ASSERT_TRUE(platform::drawCardQuad(img.view(), rectQuad(-100, -100, -50, -50), paint));
    for (std::size_t i = 0; i < img.bytes(); ++i)
        ASSERT_EQ(img.view().data[i], 0);
    // Covering the whole image with margin: every pixel is the card (XRGB: B, G, R, X in memory).
    ASSERT_TRUE(platform::drawCardQuad(img.view(), rectQuad(-10, -10, 50, 40), paint));
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            ASSERT_EQ(img.view().row(y)[4 * x + 2], paint.red);
            ASSERT_EQ(img.view().row(y)[4 * x + 1], paint.green);
            ASSERT_EQ(img.view().row(y)[4 * x + 0], paint.blue);
        }
    vision::ImageBuffer gray(40, 30, vision::PixelFormat::Gray8);
    EXPECT_FALSE(platform::drawCardQuad(gray.view(), rectQuad(0, 0, 10, 10), paint));
}

}  // namespace
