// MjpegDecoder on a real JPEG: the same pixels as OpenCV's decoder, and corrupt, truncated,
// foreign-size and non-JPEG frames refused without throwing.

#include "platform/mjpeg_decoder.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <vector>

namespace {

const char* const kJpeg = "dlib_example_faces/2008_001322.jpg";  // 500x375 baseline

std::vector<std::uint8_t> readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(MjpegDecoder, DecodesARealJpegLikeOpenCv)
{
    const std::string path = testing_support::sharedData(kJpeg);
    const std::vector<std::uint8_t> jpeg = readFile(path);
    ASSERT_FALSE(jpeg.empty()) << path;
    const cv::Mat reference = cv::imread(path, cv::IMREAD_COLOR);  // BGR
    ASSERT_FALSE(reference.empty());

    platform::MjpegDecoder decoder(reference.cols, reference.rows);
    ASSERT_TRUE(decoder.decode(jpeg.data(), jpeg.size())) << decoder.lastError();
    const vision::ConstImageView image = decoder.image();
    EXPECT_EQ(image.format, vision::PixelFormat::RGB24);
    EXPECT_EQ(image.width, 500);
    EXPECT_EQ(image.height, 375);
    int worst = 0;
    for (int y = 0; y < image.height; ++y) {
        const std::uint8_t* ours = image.row(y);
        const std::uint8_t* theirs = reference.ptr<std::uint8_t>(y);
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c)  // ours R,G,B; OpenCV's B,G,R
                worst = std::max(worst, std::abs(ours[3 * x + c] - theirs[3 * x + 2 - c]));
    }
    // Both are libjpeg-turbo; allow for a different IDCT or upsampling choice.
    EXPECT_LE(worst, 4);
}

TEST(MjpegDecoder, RefusesBadFramesAndKeepsWorking)
{
    const std::vector<std::uint8_t> jpeg = readFile(testing_support::sharedData(kJpeg));
    ASSERT_FALSE(jpeg.empty());
    platform::MjpegDecoder decoder(500, 375);

    const std::vector<std::uint8_t> noise(4096, 0x5a);
    EXPECT_FALSE(decoder.decode(noise.data(), noise.size()));
    EXPECT_NE(std::string(decoder.lastError()).find("not a JPEG"), std::string::npos);
    EXPECT_FALSE(decoder.decode(nullptr, 0));

    // A JPEG header followed by garbage: libjpeg's error comes back as a message, no exception.
    std::vector<std::uint8_t> corrupt(jpeg.begin(), jpeg.begin() + 200);
    corrupt.resize(4096, 0x00);
    corrupt[2] = 0xff;
    corrupt[3] = 0x01;  // an invalid marker right after SOI
    EXPECT_FALSE(decoder.decode(corrupt.data(), corrupt.size()));
    EXPECT_NE(std::string(decoder.lastError()).find("corrupt JPEG"), std::string::npos)
        << decoder.lastError();

    // Truncated frames decode as far as they go (cameras send them).
    const std::vector<std::uint8_t> truncated(jpeg.begin(), jpeg.begin() + jpeg.size() / 2);
    EXPECT_TRUE(decoder.decode(truncated.data(), truncated.size())) << decoder.lastError();

    platform::MjpegDecoder wrongSize(640, 480);
    EXPECT_FALSE(wrongSize.decode(jpeg.data(), jpeg.size()));
    EXPECT_STREQ(wrongSize.lastError(), "JPEG frame is 500x375, expected 640x480");

    // And the decoder still works after every failure.
    EXPECT_TRUE(decoder.decode(jpeg.data(), jpeg.size())) << decoder.lastError();
    EXPECT_TRUE(wrongSize.decode(jpeg.data(), 0) == false);
}

TEST(MjpegDecoder, RejectsAbsurdSizes)
{
    EXPECT_THROW(platform::MjpegDecoder(0, 480), std::runtime_error);
    EXPECT_THROW(platform::MjpegDecoder(640, 100000), std::runtime_error);
}

}  // namespace
