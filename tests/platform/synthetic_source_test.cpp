// SyntheticSource: deterministic procedural frames with texture and motion.

#include "platform/synthetic_source.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace {

using platform::SourceStatus;
using platform::SyntheticSource;

/// Sum of absolute byte differences of two equally sized RGB24 views.
long difference(vision::ConstImageView a, vision::ConstImageView b)
{
    long sum = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width * 3; ++x)
            sum += std::abs(a.row(y)[x] - b.row(y)[x]);
    return sum;
}

bool sameBytes(vision::ConstImageView a, vision::ConstImageView b)
{
    for (int y = 0; y < a.height; ++y)
        if (std::memcmp(a.row(y), b.row(y), static_cast<std::size_t>(a.width) * 3) != 0)
            return false;
    return true;
}

TEST(SyntheticSource, DescribesItself)
{
    SyntheticSource paced(640, 480, 30.0);
    EXPECT_EQ(paced.size(), (vision::Size{640, 480}));
    EXPECT_EQ(paced.format(), vision::PixelFormat::RGB24);
    EXPECT_STREQ(paced.description(), "synthetic (640x480 RGB24, 30 fps)");
    SyntheticSource max(320, 240, 0.0);
    EXPECT_STREQ(max.description(), "synthetic (320x240 RGB24, max rate)");
    EXPECT_STREQ(max.lastError(), "");
}

TEST(SyntheticSource, RejectsBadParameters)
{
    EXPECT_THROW(SyntheticSource(8, 480, 30.0), std::runtime_error);
    EXPECT_THROW(SyntheticSource(640, 0, 30.0), std::runtime_error);
    EXPECT_THROW(SyntheticSource(640, 480, -1.0), std::runtime_error);
    try {
        SyntheticSource(20000, 480, 30.0);
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "synthetic: size 20000x480 out of range (16..16384)");
    }
}

TEST(SyntheticSource, SameIndexGivesSameBytes)
{
    SyntheticSource a(640, 480, 0.0);
    SyntheticSource b(640, 480, 0.0);
    vision::ImageBuffer first(640, 480, vision::PixelFormat::RGB24);
    vision::ImageBuffer second(640, 480, vision::PixelFormat::RGB24);
    for (std::uint64_t index : {0ull, 1ull, 57ull, 1000ull}) {
        ASSERT_TRUE(a.renderFrame(index, first.view()));
        ASSERT_TRUE(b.renderFrame(index, second.view()));
        EXPECT_TRUE(sameBytes(first.view(), second.view())) << "index " << index;
    }
    // next() delivers exactly renderFrame(sequence).
    vision::Frame frame;
    for (std::uint64_t k = 0; k < 3; ++k) {
        ASSERT_EQ(a.next(frame), SourceStatus::Ok);
        EXPECT_EQ(frame.sequence, k);
        ASSERT_TRUE(b.renderFrame(k, second.view()));
        EXPECT_TRUE(sameBytes(frame.image, second.view()));
    }
}

TEST(SyntheticSource, FrameIsNotFlat)
{
    SyntheticSource source(640, 480, 0.0);
    vision::Frame frame;
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    const vision::ConstImageView img = frame.image;
    ASSERT_FALSE(img.empty());
    EXPECT_EQ(img.format, vision::PixelFormat::RGB24);
    // Variance of each channel is substantial, and small blocks everywhere have some texture.
    for (int c = 0; c < 3; ++c) {
        double sum = 0.0, sum2 = 0.0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const double v = img.row(y)[3 * x + c];
                sum += v;
                sum2 += v * v;
            }
        const double n = static_cast<double>(img.width) * img.height;
        const double variance = sum2 / n - (sum / n) * (sum / n);
        EXPECT_GT(variance, 200.0) << "channel " << c;
    }
    int flatBlocks = 0;
    for (int by = 0; by + 8 <= img.height; by += 8)
        for (int bx = 0; bx + 8 <= img.width; bx += 8) {
            int lo = 255, hi = 0;
            for (int y = by; y < by + 8; ++y)
                for (int x = bx; x < bx + 8; ++x) {
                    const int g = img.row(y)[3 * x + 1];
                    lo = std::min(lo, g);
                    hi = std::max(hi, g);
                }
            flatBlocks += hi == lo;
        }
    EXPECT_EQ(flatBlocks, 0);
}

TEST(SyntheticSource, ObjectsMoveAndTheBackgroundStays)
{
    SyntheticSource source(640, 480, 0.0);
    vision::ImageBuffer a(640, 480, vision::PixelFormat::RGB24);
    vision::ImageBuffer b(640, 480, vision::PixelFormat::RGB24);
    ASSERT_TRUE(source.renderFrame(10, a.view()));
    ASSERT_TRUE(source.renderFrame(11, b.view()));
    // Something changes between consecutive frames ...
    EXPECT_GT(difference(a.view(), b.view()), 1000);
    // ... but only a small part of the picture (moving objects over a static background).
    long changed = 0;
    for (int y = 0; y < 480; ++y)
        for (int x = 0; x < 640 * 3; x += 3)
            changed += std::memcmp(a.view().row(y) + x, b.view().row(y) + x, 3) != 0;
    EXPECT_GT(changed, 200);
    EXPECT_LT(changed, 640 * 480 / 4);
    // Over a second, the moved region is clearly larger than over one frame.
    ASSERT_TRUE(source.renderFrame(40, b.view()));
    EXPECT_GT(difference(a.view(), b.view()), 100000);
}

TEST(SyntheticSource, HasAFaceLikeFigure)
{
    // Skin-toned pixels (R > G > B, warm) exist in the upper middle of the frame.
    SyntheticSource source(640, 480, 0.0);
    vision::ImageBuffer img(640, 480, vision::PixelFormat::RGB24);
    ASSERT_TRUE(source.renderFrame(0, img.view()));
    int skin = 0;
    for (int y = 100; y < 300; ++y)
        for (int x = 160; x < 480; ++x) {
            const std::uint8_t* p = img.view().row(y) + 3 * x;
            skin += p[0] > 200 && p[1] > 150 && p[1] < 200 && p[2] > 115 && p[2] < 175;
        }
    EXPECT_GT(skin, 3000);
}

TEST(SyntheticSource, RenderRejectsWrongTarget)
{
    SyntheticSource source(64, 48, 0.0);
    vision::ImageBuffer wrongSize(64, 40, vision::PixelFormat::RGB24);
    vision::ImageBuffer wrongFormat(64, 48, vision::PixelFormat::BGR24);
    EXPECT_FALSE(source.renderFrame(0, wrongSize.view()));
    EXPECT_FALSE(source.renderFrame(0, wrongFormat.view()));
}

TEST(SyntheticSource, TimestampsAreMonotonicAndNextDoesNotAllocate)
{
    SyntheticSource source(320, 240, 0.0);
    vision::Frame frame;
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    std::int64_t last = frame.timestampNs;
    EXPECT_GT(last, 0);
    testing_support::AllocationScope scope;
    for (int k = 0; k < 20; ++k) {
        ASSERT_EQ(source.next(frame), SourceStatus::Ok);
        EXPECT_GE(frame.timestampNs, last);
        last = frame.timestampNs;
    }
    if (testing_support::allocationCountingAvailable()) {
        EXPECT_EQ(scope.counts().cxxNew, 0);
        EXPECT_EQ(scope.counts().ownMalloc, 0);
    }
}

}  // namespace
