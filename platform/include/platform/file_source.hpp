#pragma once
// FileSource: replays a video file, a folder of images or a glob of images as a camera.

#include "platform/frame_pacer.hpp"
#include "platform/frame_source.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <memory>
#include <string>

namespace platform {

/// How fast a replayed file delivers frames.
struct ReplayRate {
    enum class Kind {
        Native,  ///< the video's own frame rate; image folders and rateless files use a fallback
        Max,     ///< as fast as the caller asks (tests, benchmarks)
        Fixed,   ///< `fps`
    };
    Kind kind = Kind::Native;
    double fps = 0.0;  ///< for Fixed

    static constexpr ReplayRate native() noexcept { return {Kind::Native, 0.0}; }
    static constexpr ReplayRate max() noexcept { return {Kind::Max, 0.0}; }
    static constexpr ReplayRate fixed(double f) noexcept { return {Kind::Fixed, f}; }
};

/// Frames decoded by OpenCV from a file, delivered in BGR24 (OpenCV's order, no conversion).
///
/// `path` (without any "file:" prefix) is one of:
///  - a video file OpenCV can open (cv::VideoCapture, usually the FFmpeg backend);
///  - a single image file (one frame; repeated when looping);
///  - a folder: every *.png, *.jpg, *.jpeg, *.bmp in it (not recursive), sorted by file name;
///  - a glob pattern containing * or ?: every matching regular file, sorted by path.
///
/// All frames have the size of the first decodable frame; a later frame of another size is resized
/// into the same buffer, grey images are converted to BGR. Rows are padded to 16 bytes.
///
/// When the stream ends, a looping source starts again from the first frame; otherwise next()
/// returns EndOfStream (and keeps doing so). A frame that fails to decode (a corrupt image in a
/// folder, a damaged or truncated video) is skipped: skippedFrames() counts it, lastError() names
/// it, and the next good frame is delivered. When a whole pass yields no frame, next() returns
/// Lost.
///
/// Allocation: our per-frame code reuses buffers sized at construction (decode scratch, the file
/// read buffer, the delivered frame). Decoding itself allocates inside OpenCV and FFmpeg (codec
/// state, temporary images), and a scratch image is reallocated when the decoded size changes or
/// after a video pass ends. This source is for development and replay, not the camera path.
class FileSource final : public FrameSource {
public:
    /// Opens the file(s) and decodes the first frame. Throws std::runtime_error with one line:
    /// "file:PATH: no such file or directory", "file:PATH: cannot decode (not a video or image
    /// OpenCV can read)", "file:DIR: no PNG/JPEG frames in folder", "file:PATTERN: no files
    /// match". `fallbackFps` paces native rate where the file has none (image folders, or a video
    /// whose rate is missing or absurd).
    FileSource(const std::string& path, bool loop, ReplayRate rate, double fallbackFps,
               PacerClock& clock = monotonicPacerClock());
    ~FileSource() override;

    /// E.g. "file:PATH (720x528 BGR24, 23.98 fps native, loop)".
    const char* description() const noexcept override;
    vision::Size size() const noexcept override;
    vision::PixelFormat format() const noexcept override { return vision::PixelFormat::BGR24; }
    SourceStatus next(vision::Frame& frame) noexcept override;
    std::int64_t lastWaitNs() const noexcept override;
    /// The last skipped frame ("file:PATH: skipped undecodable frame N") or the reason for Lost.
    const char* lastError() const noexcept override;

    /// Frames skipped because they could not be decoded, since construction.
    std::uint64_t skippedFrames() const noexcept;
    /// Delivery rate in frames per second; 0 when unpaced (ReplayRate::max()).
    double fps() const noexcept;
    /// True for a video file, false for images (single file, folder or glob).
    bool isVideo() const noexcept;
    /// Number of image files for folders and globs (1 for a single image, 0 for a video).
    std::size_t imageCount() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace platform
