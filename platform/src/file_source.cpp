#include "platform/file_source.hpp"

#include "image_header.hpp"
#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <fcntl.h>
#include <glob.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <opencv2/videoio/registry.hpp>
#include <stdexcept>
#include <vector>

namespace platform {

namespace {

// A video claiming a rate outside this range is treated as having none (some containers report
// their time base, e.g. 1000 fps, or 0).
constexpr double kMinNativeFps = 1.0;
constexpr double kMaxNativeFps = 300.0;
// Consecutive failed reads before the container's frame count that are skipped before the pass is
// considered over (a truncated file never yields its announced frames).
constexpr int kMaxConsecutiveVideoFailures = 8;

std::runtime_error fileError(const std::string& path, const std::string& why)
{
    return std::runtime_error("file:" + path + ": " + why);
}

bool isGlobPattern(const std::string& path)
{
    return path.find_first_of("*?") != std::string::npos;
}

bool hasFrameExtension(const std::filesystem::path& p)
{
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp";
}

bool isRegularFile(const std::string& path)
{
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::vector<std::string> globFiles(const std::string& pattern)
{
    glob_t g{};
    std::vector<std::string> files;
    if (::glob(pattern.c_str(), 0, nullptr, &g) == 0) {
        for (std::size_t i = 0; i < g.gl_pathc; ++i)
            if (isRegularFile(g.gl_pathv[i]))
                files.emplace_back(g.gl_pathv[i]);
    }
    globfree(&g);
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<std::string> folderFrames(const std::string& dir)
{
    std::vector<std::string> files;
    std::error_code ec;
    std::filesystem::directory_iterator it(dir, ec);
    if (ec)
        throw fileError(dir, "cannot list folder (" + ec.message() + ")");
    for (const auto& entry : it) {
        std::error_code typeEc;
        if (entry.is_regular_file(typeEc) && hasFrameExtension(entry.path()))
            files.push_back(entry.path().string());
    }
    // Sorted by file name (byte order), the usual numbering of extracted frames.
    std::sort(files.begin(), files.end(), [](const std::string& a, const std::string& b) {
        return std::filesystem::path(a).filename().string() <
               std::filesystem::path(b).filename().string();
    });
    return files;
}

/// FFmpeg when OpenCV has it: trying every backend (GStreamer, image sequences) on a file that is
/// not a video floods stderr with their warnings and gains nothing for plain files.
int videoBackend()
{
    return cv::videoio_registry::hasBackend(cv::CAP_FFMPEG) ? cv::CAP_FFMPEG : cv::CAP_ANY;
}

/// "23.98" style: two decimals without trailing zeros.
/// Why an image file gave no frame, for the one-line start-up error.
std::string whyNoFrame(const std::string& file)
{
    const vision::BoundedFile read = vision::readBoundedFile(file, vision::limits::kImageFileBytes);
    if (read.status != vision::BoundedFile::Status::Ok)
        return read.problem;
    const std::string wrong = checkImageHeader(
        reinterpret_cast<const std::uint8_t*>(read.text.data()), read.text.size());
    return wrong.empty() ? "cannot decode (not a video or image OpenCV can read)" : wrong;
}

/// A video whose frames are beyond vision/input_limits.hpp is refused at start-up.
void checkVideoSize(const std::string& path, double width, double height)
{
    using vision::limits::kMaxImagePixels;
    using vision::limits::kMaxImageSide;
    if (width > kMaxImageSide || height > kMaxImageSide || width * height > kMaxImagePixels)
        throw fileError(path, "video frames of " + std::to_string(std::llround(width)) + "x" +
                                  std::to_string(std::llround(height)) + " (allowed: up to " +
                                  std::to_string(kMaxImageSide) + " on a side and 7680x4320)");
}

std::string formatFps(double fps)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", fps);
    std::string s = text;
    while (!s.empty() && s.back() == '0')
        s.pop_back();
    if (!s.empty() && s.back() == '.')
        s.pop_back();
    return s;
}

/// Reads one image file into `bytes` (no allocation: it holds the largest file of the pass) and
/// decodes it into `decoded`, unless it is not a regular file, outgrew `bytes`, or its header
/// claims a picture beyond vision/input_limits.hpp. False when there is no frame in it.
bool decodeImageFile(const std::string& file, std::vector<std::uint8_t>& bytes, cv::Mat& decoded)
{
    const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return false;
    struct stat st {};
    bool ok = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
    std::size_t used = 0;
    while (ok) {
        if (used == bytes.size()) {
            // Grew since start-up: reading further would need a larger buffer.
            char probe;
            ok = ::read(fd, &probe, 1) == 0;
            break;
        }
        const ssize_t n = ::read(fd, bytes.data() + used, bytes.size() - used);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            ok = n == 0;
            break;
        }
        used += static_cast<std::size_t>(n);
    }
    ::close(fd);
    if (!ok || used == 0 || !imageHeaderWithinLimits(bytes.data(), used))
        return false;
    const cv::Mat encoded(1, static_cast<int>(used), CV_8UC1, bytes.data());
    cv::imdecode(encoded, cv::IMREAD_COLOR, &decoded);
    return !decoded.empty();
}

}  // namespace

struct FileSource::Impl {
    enum class Step { Frame, Skipped, End };

    std::string path;
    bool loop = false;
    bool video = false;
    std::vector<std::string> images;      ///< image mode: the files of one pass, in order
    std::vector<std::uint8_t> fileBytes;  ///< image mode: read buffer, as large as the largest file
    cv::VideoCapture capture;

    cv::Mat decoded;             ///< what the decoder produced (its size/channels may vary)
    cv::Mat converted;           ///< grey/BGRA decoded frames converted to BGR
    vision::ImageBuffer buffer;  ///< the delivered frame, fixed size, BGR24
    cv::Mat frame;               ///< OpenCV header over `buffer`

    FramePacer pacer;
    std::string description;
    char lastError[512] = {};

    bool pending = false;  ///< `frame` holds a decoded frame not yet delivered
    bool ended = false;
    std::size_t imageIndex = 0;    ///< next image of the pass
    std::uint64_t videoIndex = 0;  ///< next video frame of the pass
    int consecutiveFailures = 0;
    std::uint64_t deliveredInPass = 0;
    std::uint64_t sequence = 0;
    std::uint64_t skipped = 0;

    Impl(double fps, PacerClock& clock) : pacer(fps, clock) {}

    void skippedFrame(const std::string& file, std::uint64_t n) noexcept
    {
        std::snprintf(lastError, sizeof lastError, "file:%s: skipped undecodable frame %llu",
                      file.c_str(), static_cast<unsigned long long>(n));
    }

    void setError(const char* why) noexcept
    {
        std::snprintf(lastError, sizeof lastError, "file:%s: %s", path.c_str(), why);
    }

    /// Converts `src` to BGR and fits it into `frame`; false when the image is unusable.
    bool adopt(const cv::Mat& src)
    {
        if (src.empty() || src.depth() != CV_8U)
            return false;
        const cv::Mat* bgr = &src;
        if (src.channels() == 1) {
            cv::cvtColor(src, converted, cv::COLOR_GRAY2BGR);
            bgr = &converted;
        } else if (src.channels() == 4) {
            cv::cvtColor(src, converted, cv::COLOR_BGRA2BGR);
            bgr = &converted;
        } else if (src.channels() != 3) {
            return false;
        }
        // `frame` wraps `buffer`: both calls write into it because size and type match.
        if (bgr->size() == frame.size())
            bgr->copyTo(frame);
        else
            cv::resize(*bgr, frame, frame.size(), 0.0, 0.0, cv::INTER_AREA);
        return true;
    }

    Step readImage()
    {
        if (imageIndex >= images.size())
            return Step::End;
        const std::size_t index = imageIndex++;
        if (decodeImageFile(images[index], fileBytes, decoded) && adopt(decoded))
            return Step::Frame;
        skippedFrame(images[index], index);
        return Step::Skipped;
    }

    Step readVideo()
    {
        const std::uint64_t index = videoIndex++;
        if (capture.read(decoded)) {
            consecutiveFailures = 0;
            if (adopt(decoded))
                return Step::Frame;
        } else {
            // A failed read at the announced end is the end; before it, a damaged or missing frame.
            const double position = capture.get(cv::CAP_PROP_POS_FRAMES);
            const double count = capture.get(cv::CAP_PROP_FRAME_COUNT);
            if (!(count > 0.0 && position < count) ||
                ++consecutiveFailures > kMaxConsecutiveVideoFailures) {
                consecutiveFailures = 0;
                return Step::End;
            }
        }
        skippedFrame(path, index);
        return Step::Skipped;
    }

    bool rewind()
    {
        imageIndex = 0;
        videoIndex = 0;
        consecutiveFailures = 0;
        deliveredInPass = 0;
        if (!video)
            return true;
        // Seeking is cheap; reopening is the fallback for backends that cannot seek.
        if (capture.set(cv::CAP_PROP_POS_FRAMES, 0.0))
            return true;
        capture.release();
        if (capture.open(path, videoBackend()))
            return true;
        setError("cannot reopen the video to loop");
        return false;
    }

    /// Decodes the next good frame into `frame`.
    SourceStatus decodeNext()
    {
        for (;;) {
            const Step step = video ? readVideo() : readImage();
            if (step == Step::Frame) {
                ++deliveredInPass;
                return SourceStatus::Ok;
            }
            if (step == Step::Skipped) {
                ++skipped;
                continue;
            }
            if (!loop) {
                ended = true;
                return SourceStatus::EndOfStream;
            }
            const bool empty = deliveredInPass == 0;
            if (!rewind())
                return SourceStatus::Lost;
            if (empty) {
                setError("no decodable frame in a whole pass");
                return SourceStatus::Lost;
            }
        }
    }
};

FileSource::FileSource(const std::string& path, bool loop, ReplayRate rate, double fallbackFps,
                       PacerClock& clock)
{
    std::vector<std::string> images;
    bool video = false;
    if (isGlobPattern(path)) {
        images = globFiles(path);
        if (images.empty())
            throw fileError(path, "no files match");
    } else {
        struct stat st {};
        if (::stat(path.c_str(), &st) != 0) {
            const int err = errno;
            throw fileError(path, err == ENOENT || err == ENOTDIR ? "no such file or directory"
                                                                  : std::strerror(err));
        }
        if (S_ISDIR(st.st_mode)) {
            images = folderFrames(path);
            if (images.empty())
                throw fileError(path, "no PNG/JPEG frames in folder");
        } else if (cv::haveImageReader(path)) {
            images.push_back(path);
        } else {
            video = true;
        }
    }

    cv::VideoCapture capture;
    cv::Mat first;
    std::vector<std::uint8_t> fileBytes;
    std::size_t firstIndex = 0;
    std::uint64_t skippedAtStart = 0;
    std::string lastSkipped;
    double nativeFps = 0.0;
    if (video) {
        if (!capture.open(path, videoBackend()))
            throw fileError(path, "cannot decode (not a video or image OpenCV can read)");
        // The container's size, before a frame is decoded; the decoded one is checked below.
        checkVideoSize(path, capture.get(cv::CAP_PROP_FRAME_WIDTH),
                       capture.get(cv::CAP_PROP_FRAME_HEIGHT));
        if (!capture.read(first) || first.empty())
            throw fileError(path, "cannot decode (not a video or image OpenCV can read)");
        checkVideoSize(path, first.cols, first.rows);
        nativeFps = capture.get(cv::CAP_PROP_FPS);
    } else {
        // Files over the bound are left out of the buffer: they are skipped like undecodable ones.
        std::size_t largest = 0;
        for (const auto& file : images) {
            struct stat st {};
            if (::stat(file.c_str(), &st) == 0 &&
                static_cast<std::size_t>(st.st_size) <= vision::limits::kImageFileBytes)
                largest = std::max(largest, static_cast<std::size_t>(st.st_size));
        }
        fileBytes.resize(largest);
        for (; firstIndex < images.size(); ++firstIndex) {
            if (decodeImageFile(images[firstIndex], fileBytes, first))
                break;
            ++skippedAtStart;
            lastSkipped = images[firstIndex];
        }
        if (first.empty()) {
            if (images.size() == 1)
                throw fileError(path, (images[0] == path ? std::string()
                                                         : std::filesystem::path(images[0])
                                                                   .filename()
                                                                   .string() +
                                                               ": ") +
                                          whyNoFrame(images[0]));
            throw fileError(path, "cannot decode any of " + std::to_string(images.size()) +
                                      " files (not images OpenCV can read)");
        }
    }

    // Pacing.
    double fps = 0.0;
    std::string rateText;
    const bool nativeOk =
        std::isfinite(nativeFps) && nativeFps >= kMinNativeFps && nativeFps <= kMaxNativeFps;
    switch (rate.kind) {
        case ReplayRate::Kind::Max:
            rateText = "max rate";
            break;
        case ReplayRate::Kind::Fixed:
            if (!std::isfinite(rate.fps) || rate.fps <= 0.0)
                throw fileError(path,
                                "rate " + std::to_string(rate.fps) + " fps invalid (must be > 0)");
            fps = rate.fps;
            rateText = formatFps(fps) + " fps";
            break;
        case ReplayRate::Kind::Native:
            if (video && nativeOk) {
                fps = nativeFps;
                rateText = formatFps(fps) + " fps native";
            } else {
                if (!std::isfinite(fallbackFps) || fallbackFps <= 0.0)
                    throw fileError(path, "fallback rate " + std::to_string(fallbackFps) +
                                              " fps invalid (must be > 0)");
                fps = fallbackFps;
                rateText = formatFps(fps) + (video ? " fps (file has no rate)" : " fps");
            }
            break;
    }

    // The first frame sizes the pipeline; the stages scale it down, so it needs some pixels.
    if (first.cols < vision::limits::kMinFrameSide || first.rows < vision::limits::kMinFrameSide)
        throw fileError(path, "frames of " + std::to_string(first.cols) + "x" +
                                  std::to_string(first.rows) + " (allowed: at least " +
                                  std::to_string(vision::limits::kMinFrameSide) + "x" +
                                  std::to_string(vision::limits::kMinFrameSide) + ")");
    impl_ = std::make_unique<Impl>(fps, clock);
    Impl& m = *impl_;
    m.path = path;
    m.loop = loop;
    m.video = video;
    m.images = std::move(images);
    m.fileBytes = std::move(fileBytes);
    m.capture = std::move(capture);
    m.buffer = vision::ImageBuffer(first.cols, first.rows, vision::PixelFormat::BGR24);
    const vision::ImageView view = m.buffer.view();
    m.frame =
        cv::Mat(view.height, view.width, CV_8UC3, view.data, static_cast<std::size_t>(view.stride));
    if (!m.adopt(first))
        throw fileError(path, "cannot decode (not a video or image OpenCV can read)");
    m.pending = true;
    m.deliveredInPass = 1;
    m.imageIndex = firstIndex + 1;
    m.videoIndex = 1;
    m.skipped = skippedAtStart;
    if (skippedAtStart > 0)
        m.skippedFrame(lastSkipped, skippedAtStart - 1);

    m.description = "file:" + path + " (" + std::to_string(view.width) + "x" +
                    std::to_string(view.height) + " BGR24, ";
    if (!video && m.images.size() > 1)
        m.description += std::to_string(m.images.size()) + " images, ";
    m.description += rateText + (loop ? ", loop)" : ", once)");
}

FileSource::~FileSource() = default;

const char* FileSource::description() const noexcept
{
    return impl_->description.c_str();
}

vision::Size FileSource::size() const noexcept
{
    return {impl_->buffer.view().width, impl_->buffer.view().height};
}

const char* FileSource::lastError() const noexcept
{
    return impl_->lastError;
}
std::uint64_t FileSource::skippedFrames() const noexcept
{
    return impl_->skipped;
}
double FileSource::fps() const noexcept
{
    return impl_->pacer.fps();
}
bool FileSource::isVideo() const noexcept
{
    return impl_->video;
}
std::size_t FileSource::imageCount() const noexcept
{
    return impl_->images.size();
}

std::int64_t FileSource::lastWaitNs() const noexcept
{
    return impl_->pacer.lastSleepNs();
}

SourceStatus FileSource::next(vision::Frame& frame) noexcept
{
    Impl& m = *impl_;
    if (m.ended)
        return SourceStatus::EndOfStream;
    if (!m.pending) {
        SourceStatus status = SourceStatus::Lost;
        try {
            status = m.decodeNext();
        } catch (const std::exception& e) {
            // OpenCV reports failures (and failed allocations) by exception.
            std::snprintf(m.lastError, sizeof m.lastError, "file:%s: decoder error: %s",
                          m.path.c_str(), e.what());
            status = SourceStatus::Lost;
        }
        if (status != SourceStatus::Ok)
            return status;
    }
    m.pending = false;
    const std::int64_t timestamp = m.pacer.wait();
    frame.image = m.buffer.view();
    frame.sequence = m.sequence++;
    frame.timestampNs = timestamp;
    return SourceStatus::Ok;
}

}  // namespace platform
