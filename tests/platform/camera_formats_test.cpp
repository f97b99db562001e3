// Camera format mapping (libcamera/DRM and V4L2 fourccs by byte order) and format negotiation.

#include "platform/camera_formats.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using vision::PixelFormat;
namespace lc = platform::libcameraFourcc;
namespace v4 = platform::v4l2Fourcc;

TEST(CameraFormats, FourccMatchesTheKernelDefinitions)
{
    // Values from drm_fourcc.h and videodev2.h.
    EXPECT_EQ(lc::BGR888, 0x34324742u);
    EXPECT_EQ(lc::RGB888, 0x34324752u);
    EXPECT_EQ(lc::XRGB8888, 0x34325258u);
    EXPECT_EQ(lc::YUYV, 0x56595559u);
    EXPECT_EQ(lc::NV12, 0x3231564eu);
    EXPECT_EQ(v4::RGB24, 0x33424752u);
    EXPECT_EQ(v4::BGR24, 0x33524742u);
    EXPECT_EQ(v4::MJPEG, 0x47504a4du);
    char text[16];
    EXPECT_STREQ(platform::fourccName(lc::BGR888, text, sizeof text), "BG24");
    EXPECT_STREQ(platform::fourccName(0x00000001u, text, sizeof text), "0x00000001");
}

TEST(CameraFormats, LibcameraNamesByWordSoBgr888IsBytesRgb)
{
    EXPECT_EQ(platform::pixelFormatFromLibcamera(lc::BGR888), PixelFormat::RGB24);
    EXPECT_EQ(platform::pixelFormatFromLibcamera(lc::RGB888), PixelFormat::BGR24);
    EXPECT_EQ(platform::pixelFormatFromLibcamera(lc::XRGB8888), PixelFormat::XRGB8888);
    EXPECT_EQ(platform::pixelFormatFromLibcamera(lc::YUYV), PixelFormat::YUYV);
    EXPECT_EQ(platform::pixelFormatFromLibcamera(lc::NV12), PixelFormat::NV12);
    EXPECT_FALSE(platform::pixelFormatFromLibcamera(platform::fourcc('R', 'G', '1', '0')));
    for (PixelFormat f : {PixelFormat::RGB24, PixelFormat::BGR24, PixelFormat::XRGB8888,
                          PixelFormat::YUYV, PixelFormat::NV12})
        EXPECT_EQ(platform::pixelFormatFromLibcamera(platform::libcameraFourccFor(f)), f);
    EXPECT_EQ(platform::libcameraFourccFor(PixelFormat::Gray8), 0u);
}

TEST(CameraFormats, V4l2NamesByByteOrder)
{
    EXPECT_EQ(platform::pixelFormatFromV4l2(v4::RGB24), PixelFormat::RGB24);
    EXPECT_EQ(platform::pixelFormatFromV4l2(v4::BGR24), PixelFormat::BGR24);
    EXPECT_EQ(platform::pixelFormatFromV4l2(v4::XBGR32), PixelFormat::XRGB8888);
    EXPECT_EQ(platform::pixelFormatFromV4l2(v4::BGR32), PixelFormat::XRGB8888);
    EXPECT_EQ(platform::pixelFormatFromV4l2(v4::YUYV), PixelFormat::YUYV);
    EXPECT_FALSE(platform::pixelFormatFromV4l2(v4::MJPEG));
}

TEST(CameraFormats, LibcameraChoosesThePreferredOfferedFormat)
{
    const std::vector<PixelFormat> preference = platform::defaultFormatPreference();
    // vimc offers these (among Bayer formats we do not take).
    const std::vector<std::uint32_t> vimc = {lc::RGB888, platform::fourcc('B', 'A', '8', '1'),
                                             lc::BGR888};
    EXPECT_EQ(platform::chooseLibcameraFormat(vimc, preference), PixelFormat::RGB24);
    const std::vector<std::uint32_t> yuvOnly = {lc::NV12, lc::YUYV};
    EXPECT_EQ(platform::chooseLibcameraFormat(yuvOnly, preference), PixelFormat::YUYV);
    const std::vector<PixelFormat> nv12First = {PixelFormat::NV12, PixelFormat::YUYV};
    EXPECT_EQ(platform::chooseLibcameraFormat(yuvOnly, nv12First), PixelFormat::NV12);
    const std::vector<std::uint32_t> bayer = {platform::fourcc('B', 'A', '8', '1')};
    EXPECT_FALSE(platform::chooseLibcameraFormat(bayer, preference));
}

TEST(CameraFormats, V4l2PrefersRawAndFallsBackToMjpeg)
{
    const std::vector<PixelFormat> preference = platform::defaultFormatPreference();
    const std::vector<std::uint32_t> webcam = {v4::MJPEG, v4::YUYV};
    auto choice = platform::chooseV4l2Format(webcam, preference, true);
    ASSERT_TRUE(choice);
    EXPECT_EQ(choice->fourcc, v4::YUYV);
    EXPECT_EQ(choice->format, PixelFormat::YUYV);
    EXPECT_FALSE(choice->mjpeg);

    // A consumer that takes only RGB: the MJPEG stream, decoded to RGB24.
    const std::vector<PixelFormat> rgbOnly = {PixelFormat::RGB24, PixelFormat::BGR24};
    choice = platform::chooseV4l2Format(webcam, rgbOnly, true);
    ASSERT_TRUE(choice);
    EXPECT_EQ(choice->fourcc, v4::MJPEG);
    EXPECT_EQ(choice->format, PixelFormat::RGB24);
    EXPECT_TRUE(choice->mjpeg);
    EXPECT_FALSE(platform::chooseV4l2Format(webcam, rgbOnly, false));

    const std::vector<std::uint32_t> vivid = {v4::YUYV, v4::BGR24, v4::RGB24, v4::NV12};
    choice = platform::chooseV4l2Format(vivid, preference, true);
    ASSERT_TRUE(choice);
    EXPECT_EQ(choice->fourcc, v4::RGB24);
    EXPECT_EQ(choice->format, PixelFormat::RGB24);

    const std::vector<std::uint32_t> jpegOnly = {v4::JPEG};
    choice = platform::chooseV4l2Format(jpegOnly, preference, true);
    ASSERT_TRUE(choice);
    EXPECT_TRUE(choice->mjpeg);
    const std::vector<std::uint32_t> nothing;
    EXPECT_FALSE(platform::chooseV4l2Format(nothing, preference, true));
}

}  // namespace
