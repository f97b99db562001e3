// FileSource: replay of a real video, an image folder and a glob; clear start-up errors; skipping
// undecodable frames.

#include "platform/file_source.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using platform::FileSource;
using platform::ReplayRate;
using platform::SourceStatus;
using testing_support::freshOutputDir;
using testing_support::sharedData;

const std::string kVideo = "../shared/data/opencv_samples_video/Megamind.avi";

std::vector<std::uint8_t> copyOf(vision::ConstImageView img)
{
    std::vector<std::uint8_t> bytes;
    for (int y = 0; y < img.height; ++y)
        bytes.insert(bytes.end(), img.row(y), img.row(y) + img.width * bytesPerPixel(img.format));
    return bytes;
}

std::string startupError(const std::string& path)
{
    try {
        FileSource source(path, true, ReplayRate::max(), 30.0);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(no exception)";
}

/// A small BGR test image: a diagonal gradient shifted by `seed`.
cv::Mat testImage(int width, int height, int seed)
{
    cv::Mat img(height, width, CV_8UC3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            img.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<std::uint8_t>((x + seed * 40) & 255),
                                                static_cast<std::uint8_t>((y * 2) & 255),
                                                static_cast<std::uint8_t>((x + y + seed) & 255));
    return img;
}

void writeBytes(const std::string& path, const std::string& bytes)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
}

/// Mean of a channel over the whole frame.
double channelMean(vision::ConstImageView img, int channel)
{
    double sum = 0.0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            sum += img.row(y)[3 * x + channel];
    return sum / (static_cast<double>(img.width) * img.height);
}

TEST(FileSource, VideoPlaysOnceThenEndsOfStream)
{
    FileSource source(kVideo, false, ReplayRate::max(), 30.0);
    EXPECT_TRUE(source.isVideo());
    EXPECT_EQ(source.size(), (vision::Size{720, 528}));
    EXPECT_EQ(source.format(), vision::PixelFormat::BGR24);
    EXPECT_EQ(source.fps(), 0.0);
    EXPECT_EQ(std::string(source.description()),
              "file:" + kVideo + " (720x528 BGR24, max rate, once)");

    vision::Frame frame;
    std::vector<std::uint8_t> previous;
    int frames = 0;
    int changed = 0;
    SourceStatus status;
    while ((status = source.next(frame)) == SourceStatus::Ok) {
        ASSERT_EQ(frame.sequence, static_cast<std::uint64_t>(frames));
        ASSERT_EQ(frame.image.width, 720);
        ASSERT_EQ(frame.image.height, 528);
        ASSERT_EQ(frame.image.format, vision::PixelFormat::BGR24);
        auto bytes = copyOf(frame.image);
        changed += !previous.empty() && bytes != previous;
        previous = std::move(bytes);
        ++frames;
        ASSERT_LT(frames, 10000);
    }
    EXPECT_EQ(status, SourceStatus::EndOfStream);
    EXPECT_GT(frames, 200);
    EXPECT_GT(changed, frames / 2);  // a moving scene, not one picture repeated
    EXPECT_EQ(source.next(frame), SourceStatus::EndOfStream);
    EXPECT_EQ(source.skippedFrames(), 0u);
}

TEST(FileSource, VideoLoopsBackToTheFirstFrame)
{
    int length = 0;
    std::vector<std::uint8_t> first;
    {
        FileSource once(kVideo, false, ReplayRate::max(), 30.0);
        vision::Frame frame;
        while (once.next(frame) == SourceStatus::Ok) {
            if (length == 0)
                first = copyOf(frame.image);
            ++length;
        }
    }
    ASSERT_GT(length, 200);

    FileSource source(kVideo, true, ReplayRate::max(), 30.0);
    EXPECT_NE(std::string(source.description()).find(", loop)"), std::string::npos);
    vision::Frame frame;
    for (int k = 0; k < length; ++k)
        ASSERT_EQ(source.next(frame), SourceStatus::Ok) << "frame " << k;
    // The frame after the last is the first one again, and the sequence keeps counting.
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_EQ(frame.sequence, static_cast<std::uint64_t>(length));
    EXPECT_EQ(copyOf(frame.image), first);
    for (int k = 0; k < 5; ++k)
        ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_EQ(source.skippedFrames(), 0u);
}

TEST(FileSource, NativeRateOfAVideoAndFallbacks)
{
    FileSource video(kVideo, true, ReplayRate::native(), 30.0);
    EXPECT_NEAR(video.fps(), 23.976, 0.001);
    EXPECT_EQ(std::string(video.description()),
              "file:" + kVideo + " (720x528 BGR24, 23.98 fps native, loop)");

    FileSource fixed(kVideo, true, ReplayRate::fixed(12.5), 30.0);
    EXPECT_EQ(fixed.fps(), 12.5);
    EXPECT_NE(std::string(fixed.description()).find("12.5 fps, loop"), std::string::npos);

    const std::string folder = sharedData("fgnet_talking_face/images");
    FileSource images(folder, true, ReplayRate::native(), 25.0);
    EXPECT_EQ(images.fps(), 25.0);

    EXPECT_THROW(FileSource(kVideo, true, ReplayRate::fixed(0.0), 30.0), std::runtime_error);
    EXPECT_THROW(FileSource(folder, true, ReplayRate::native(), 0.0), std::runtime_error);
}

TEST(FileSource, FolderOfJpegsInNameOrder)
{
    const std::string folder = sharedData("fgnet_talking_face/images");
    FileSource source(folder, true, ReplayRate::max(), 25.0);
    EXPECT_FALSE(source.isVideo());
    EXPECT_EQ(source.imageCount(), 1000u);
    EXPECT_EQ(source.size(), (vision::Size{720, 576}));
    EXPECT_EQ(std::string(source.description()),
              "file:" + folder + " (720x576 BGR24, 1000 images, max rate, loop)");

    // The first delivered frame is franck_00000.jpg, the third franck_00002.jpg.
    vision::Frame frame;
    std::vector<std::vector<std::uint8_t>> frames;
    for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(source.next(frame), SourceStatus::Ok);
        frames.push_back(copyOf(frame.image));
    }
    const cv::Mat third = cv::imread(folder + "/franck_00002.jpg", cv::IMREAD_COLOR);
    ASSERT_FALSE(third.empty());
    std::vector<std::uint8_t> expected(third.data, third.data + third.total() * 3);
    EXPECT_EQ(frames[2], expected);
    EXPECT_NE(frames[0], frames[1]);
}

TEST(FileSource, GlobPatternMatchesSortedFiles)
{
    const std::string pattern = sharedData("imm_face_db") + "/01-*.jpg";
    FileSource source(pattern, false, ReplayRate::max(), 30.0);
    EXPECT_EQ(source.size(), (vision::Size{640, 480}));
    ASSERT_GE(source.imageCount(), 2u);
    vision::Frame frame;
    std::size_t frames = 0;
    while (source.next(frame) == SourceStatus::Ok)
        ++frames;
    EXPECT_EQ(frames, source.imageCount());
    EXPECT_EQ(source.next(frame), SourceStatus::EndOfStream);
}

TEST(FileSource, StartupErrorsAreOneClearLine)
{
    const std::string dir = freshOutputDir("file_source_errors");
    EXPECT_EQ(startupError(dir + "/missing.avi"),
              "file:" + dir + "/missing.avi: no such file or directory");
    EXPECT_EQ(startupError(dir), "file:" + dir + ": no PNG/JPEG frames in folder");
    EXPECT_EQ(startupError(dir + "/*.png"), "file:" + dir + "/*.png: no files match");
    writeBytes(dir + "/notes.txt", "these are not frames\n");
    EXPECT_EQ(startupError(dir + "/notes.txt"),
              "file:" + dir + "/notes.txt: cannot decode (not a video or image OpenCV can read)");
    // A folder ignores files that are not frames.
    EXPECT_EQ(startupError(dir), "file:" + dir + ": no PNG/JPEG frames in folder");
    // A folder whose only frames are all undecodable.
    writeBytes(dir + "/a.jpg", "garbage");
    EXPECT_EQ(
        startupError(dir),
        "file:" + dir + ": a.jpg: not a PNG, JPEG or BMP file (no picture size in its header)");
}

TEST(FileSource, SkipsAnUndecodableFrameInAFolder)
{
    const std::string dir = freshOutputDir("file_source_corrupt");
    ASSERT_TRUE(cv::imwrite(dir + "/frame_0.jpg", testImage(96, 64, 0)));
    writeBytes(dir + "/frame_1.jpg", std::string("\xFF\xD8\xFF\xE0 definitely not a JPEG"));
    ASSERT_TRUE(cv::imwrite(dir + "/frame_2.png", testImage(96, 64, 2)));
    // A grey frame of another size: converted to BGR and resized to the first frame's size.
    ASSERT_TRUE(cv::imwrite(dir + "/frame_3.png", cv::Mat(32, 48, CV_8UC1, cv::Scalar(77))));

    FileSource source(dir, false, ReplayRate::max(), 30.0);
    EXPECT_EQ(source.size(), (vision::Size{96, 64}));
    EXPECT_EQ(source.imageCount(), 4u);
    vision::Frame frame;
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_EQ(frame.sequence, 0u);
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);  // frame_1 skipped, frame_2 delivered
    EXPECT_EQ(frame.sequence, 1u);
    EXPECT_EQ(copyOf(frame.image),
              copyOf({testImage(96, 64, 2).data, 96, 64, 96 * 3, vision::PixelFormat::BGR24}));
    EXPECT_EQ(source.skippedFrames(), 1u);
    EXPECT_EQ(std::string(source.lastError()),
              "file:" + dir + "/frame_1.jpg: skipped undecodable frame 1");
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_EQ(frame.image.width, 96);
    EXPECT_EQ(frame.image.height, 64);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(channelMean(frame.image, c), 77.0, 0.5);
    EXPECT_EQ(source.next(frame), SourceStatus::EndOfStream);
}

TEST(FileSource, AFrameWhoseHeaderClaimsAHugePictureIsSkippedUndecoded)
{
    const std::string dir = freshOutputDir("file_source_bomb");
    // A BMP header saying 60000x60000: 10.8 GB as BGR; the file itself is 54 bytes.
    std::string bmp(54, '\0');
    bmp[0] = 'B';
    bmp[1] = 'M';
    for (int at : {18, 22}) {
        bmp[static_cast<std::size_t>(at)] = static_cast<char>(60000 & 0xFF);
        bmp[static_cast<std::size_t>(at + 1)] = static_cast<char>(60000 >> 8);
    }
    writeBytes(dir + "/frame_0.bmp", bmp);
    ASSERT_TRUE(cv::imwrite(dir + "/frame_1.png", testImage(96, 64, 1)));
    writeBytes(dir + "/frame_2.bmp", bmp);

    FileSource source(dir, false, ReplayRate::max(), 30.0);
    EXPECT_EQ(source.size(), (vision::Size{96, 64}));  // the first frame that is one
    vision::Frame frame;
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_EQ(source.next(frame), SourceStatus::EndOfStream);
    EXPECT_EQ(source.skippedFrames(), 2u);
    // A frame too small to scale down is refused at start-up.
    ASSERT_TRUE(cv::imwrite(dir + "/tiny.png", testImage(15, 40, 0)));
    EXPECT_EQ(startupError(dir + "/tiny.png"),
              "file:" + dir + "/tiny.png: frames of 15x40 (allowed: at least 16x16)");
    // Alone, it is one line saying why.
    EXPECT_EQ(startupError(dir + "/frame_0.bmp"),
              "file:" + dir + "/frame_0.bmp: its header says 60000x60000 (allowed: up to 7680 on a "
              "side and 33177600 pixels, 7680x4320)");
}

TEST(FileSource, FirstFrameUndecodableIsSkippedAtStartup)
{
    const std::string dir = freshOutputDir("file_source_corrupt_first");
    writeBytes(dir + "/a.png", "not a png");
    ASSERT_TRUE(cv::imwrite(dir + "/b.png", testImage(40, 30, 1)));
    FileSource source(dir, false, ReplayRate::max(), 30.0);
    EXPECT_EQ(source.size(), (vision::Size{40, 30}));
    EXPECT_EQ(source.skippedFrames(), 1u);
    vision::Frame frame;
    EXPECT_EQ(source.next(frame), SourceStatus::Ok);
    EXPECT_EQ(source.next(frame), SourceStatus::EndOfStream);
}

TEST(FileSource, WholePassWithoutAFrameIsLost)
{
    const std::string dir = freshOutputDir("file_source_lost");
    ASSERT_TRUE(cv::imwrite(dir + "/a.png", testImage(40, 30, 1)));
    ASSERT_TRUE(cv::imwrite(dir + "/b.png", testImage(40, 30, 2)));
    FileSource source(dir, true, ReplayRate::max(), 30.0);
    vision::Frame frame;
    ASSERT_EQ(source.next(frame), SourceStatus::Ok);  // decoded at start-up
    // Both files go bad while replaying.
    writeBytes(dir + "/a.png", "gone");
    writeBytes(dir + "/b.png", "gone");
    EXPECT_EQ(source.next(frame), SourceStatus::Lost);
    EXPECT_EQ(std::string(source.lastError()),
              "file:" + dir + ": no decodable frame in a whole pass");
    // They come back: the source recovers.
    ASSERT_TRUE(cv::imwrite(dir + "/a.png", testImage(40, 30, 1)));
    EXPECT_EQ(source.next(frame), SourceStatus::Ok);
}

TEST(FileSource, TruncatedVideoEndsEarlyAndLoops)
{
    // The first half of the video in the build tree: the container still announces every frame.
    const std::string dir = freshOutputDir("file_source_truncated");
    {
        std::ifstream in(kVideo, std::ios::binary);
        std::string bytes(600000, '\0');
        in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        ASSERT_EQ(in.gcount(), 600000);
        writeBytes(dir + "/half.avi", bytes);
    }
    FileSource once(dir + "/half.avi", false, ReplayRate::max(), 30.0);
    vision::Frame frame;
    int frames = 0;
    while (once.next(frame) == SourceStatus::Ok)
        ASSERT_LT(++frames, 10000);
    EXPECT_GT(frames, 50);
    EXPECT_LT(frames, 260);
    EXPECT_EQ(once.next(frame), SourceStatus::EndOfStream);
    if (once.skippedFrames() > 0) {
        EXPECT_NE(std::string(once.lastError()).find("skipped undecodable frame"),
                  std::string::npos);
    }

    FileSource looping(dir + "/half.avi", true, ReplayRate::max(), 30.0);
    for (int k = 0; k < frames + 10; ++k)
        ASSERT_EQ(looping.next(frame), SourceStatus::Ok) << "frame " << k;
}

TEST(FileSource, SingleImageRepeatsWhenLooping)
{
    const std::string dir = freshOutputDir("file_source_single");
    ASSERT_TRUE(cv::imwrite(dir + "/only.bmp", testImage(50, 20, 3)));
    FileSource looping(dir + "/only.bmp", true, ReplayRate::max(), 30.0);
    EXPECT_EQ(std::string(looping.description()),
              "file:" + dir + "/only.bmp (50x20 BGR24, max rate, loop)");
    vision::Frame frame;
    for (int k = 0; k < 4; ++k)
        ASSERT_EQ(looping.next(frame), SourceStatus::Ok);
    EXPECT_EQ(frame.sequence, 3u);

    FileSource once(dir + "/only.bmp", false, ReplayRate::max(), 30.0);
    EXPECT_EQ(once.next(frame), SourceStatus::Ok);
    EXPECT_EQ(once.next(frame), SourceStatus::EndOfStream);
}

}  // namespace
