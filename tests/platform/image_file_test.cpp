#include "platform/image_file.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <utility>

namespace {

std::string loadError(const std::string& path)
{
    try {
        platform::loadImageFile(path, "card picture");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(no exception)";
}

// Every pixel of `image` equals OpenCV's own decoding of `path` with B and R swapped.
void expectSameAsOpenCv(const vision::ImageBuffer& image, const std::string& path)
{
    const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
    ASSERT_FALSE(bgr.empty());
    const vision::ConstImageView view = image.view();
    ASSERT_EQ(view.format, vision::PixelFormat::RGB24);
    ASSERT_EQ(view.width, bgr.cols);
    ASSERT_EQ(view.height, bgr.rows);
    int mismatches = 0;
    for (int y = 0; y < view.height; ++y)
        for (int x = 0; x < view.width; ++x) {
            const cv::Vec3b b = bgr.at<cv::Vec3b>(y, x);
            const std::uint8_t* p = view.row(y) + x * 3;
            mismatches += (p[0] != b[2] || p[1] != b[1] || p[2] != b[0]) ? 1 : 0;
        }
    EXPECT_EQ(mismatches, 0);
}

TEST(ImageFile, LoadsAPngAsRgb)
{
    const std::string path = testing_support::sharedData("debian_skimage_faces/astronaut.png");
    const vision::ImageBuffer image = platform::loadImageFile(path, "card picture");
    const vision::ConstImageView view = image.view();
    EXPECT_EQ(view.width, 512);
    EXPECT_EQ(view.height, 512);
    // One pixel by hand: OpenCV's BGR order swapped, and not a grey pixel (so a swap shows).
    const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
    const cv::Vec3b suit = bgr.at<cv::Vec3b>(100, 50);
    ASSERT_NE(suit[0], suit[2]);
    const std::uint8_t* p = view.row(100) + 50 * 3;
    EXPECT_EQ(p[0], suit[2]);
    EXPECT_EQ(p[1], suit[1]);
    EXPECT_EQ(p[2], suit[0]);
    expectSameAsOpenCv(image, path);
}

TEST(ImageFile, LoadsAJpegAndOddWidths)
{
    // A JPEG of an odd width (padded rows in the buffer), made from the real photograph.
    const cv::Mat astronaut =
        cv::imread(testing_support::sharedData("debian_skimage_faces/astronaut.png"));
    ASSERT_FALSE(astronaut.empty());
    const std::string dir = testing_support::freshOutputDir("image_file");
    const std::string path = dir + "/astronaut.jpg";
    ASSERT_TRUE(cv::imwrite(path, astronaut(cv::Rect(3, 5, 301, 199))));
    const vision::ImageBuffer image = platform::loadImageFile(path);
    EXPECT_EQ(image.view().width, 301);
    EXPECT_EQ(image.view().height, 199);
    EXPECT_GT(image.view().stride, 301 * 3);
    expectSameAsOpenCv(image, path);
}

TEST(ImageFile, GreyImagesBecomeRgb)
{
    const std::string path = testing_support::freshOutputDir("image_file_grey") + "/grey.png";
    cv::Mat grey(4, 6, CV_8UC1, cv::Scalar(77));
    ASSERT_TRUE(cv::imwrite(path, grey));
    const vision::ImageBuffer image = platform::loadImageFile(path);
    const std::uint8_t* p = image.view().row(3) + 5 * 3;
    EXPECT_EQ(p[0], 77);
    EXPECT_EQ(p[1], 77);
    EXPECT_EQ(p[2], 77);
}

TEST(ImageFile, MissingFileIsOneClearLine)
{
    EXPECT_EQ(loadError("/nonexistent/dir/picture.png"),
              "card picture /nonexistent/dir/picture.png: no such file");
}

TEST(ImageFile, NonImageIsOneClearLine)
{
    const std::string dir = testing_support::freshOutputDir("image_file_bad");
    const std::string text = dir + "/notes.png";
    std::ofstream(text) << "this is not a picture\n";
    const std::string notImage = ": not a PNG, JPEG or BMP file (no picture size in its header)";
    EXPECT_EQ(loadError(text), "card picture " + text + notImage);
    const std::string empty = dir + "/empty.jpg";
    std::ofstream{empty};
    EXPECT_EQ(loadError(empty), "card picture " + empty + notImage);
    EXPECT_EQ(loadError(dir), "card picture " + dir + ": cannot read file: Is a directory");
    EXPECT_EQ(loadError("/dev/zero"),
              "card picture /dev/zero: not a regular file (a FIFO, a device or a socket)");
    // A PNG whose header is fine but whose data is not: the decoder's turn.
    const std::string broken = dir + "/broken.png";
    std::ofstream(broken, std::ios::binary)
        << std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\0\x10\0\0\0\x10", 24) << "junk";
    EXPECT_EQ(loadError(broken), "card picture " + broken + ": not an image OpenCV can read");
}

/// `png` (a real file) with the size in its IHDR replaced, its checksum fixed: a "header bomb".
std::string withClaimedSize(const std::string& png, std::uint32_t width, std::uint32_t height)
{
    std::ifstream in(png, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const auto put = [&](std::size_t at, std::uint32_t v) {
        for (int i = 0; i < 4; ++i)
            bytes[at + static_cast<std::size_t>(i)] = static_cast<char>(v >> (24 - 8 * i));
    };
    put(16, width);
    put(20, height);
    std::uint32_t crc = 0xFFFFFFFFu;
    for (std::size_t i = 12; i < 29; ++i) {
        crc ^= static_cast<std::uint8_t>(bytes[i]);
        for (int k = 0; k < 8; ++k)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    put(29, ~crc);
    return bytes;
}

TEST(ImageFile, APictureBeyondTheLimitsIsRefusedFromItsHeader)
{
    const std::string dir = testing_support::freshOutputDir("image_file_bomb");
    const std::string small = dir + "/small.png";
    ASSERT_TRUE(cv::imwrite(small, cv::Mat(8, 8, CV_8UC3, cv::Scalar(10, 20, 30))));
    // 8000x8000 would be 192 MB decoded (and 3.9 GB through the pipeline): refused unread.
    for (const auto& [w, h] :
         {std::pair{8000u, 8000u}, std::pair{7680u, 4321u}, std::pair{0u, 5u}}) {
        const std::string bomb = dir + "/bomb.png";
        std::ofstream(bomb, std::ios::binary) << withClaimedSize(small, w, h);
        EXPECT_EQ(loadError(bomb), "card picture " + bomb + ": its header says " +
                                       std::to_string(w) + "x" + std::to_string(h) +
                                       " (allowed: up to 7680 on a side and 33177600 pixels, "
                                       "7680x4320)");
    }
    // Either way up is fine.
    const std::string portrait = dir + "/portrait.png";
    ASSERT_TRUE(cv::imwrite(portrait, cv::Mat(7680, 16, CV_8UC3, cv::Scalar(1, 2, 3))));
    EXPECT_EQ(platform::loadImageFile(portrait).view().height, 7680);
}

}  // namespace
