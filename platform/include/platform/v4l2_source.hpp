#pragma once
// V4l2Source: frames from a Video4Linux2 capture device (USB webcams, vivid) by mmap streaming.

#include "platform/frame_source.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace platform {

struct V4l2Options {
    std::string device = "/dev/video0";
    int width = 640;
    int height = 480;
    double fps = 30.0;  ///< asked by VIDIOC_S_PARM where the driver supports it; 0 = the driver's
    std::vector<vision::PixelFormat> formats;  ///< best first (empty: defaultFormatPreference())
    bool allowMjpeg = true;  ///< no raw format of `formats`: capture MJPEG, decode to RGB24
    int bufferCount = 4;     ///< driver buffers asked for (it may grant more); at least 2
    std::int64_t timeoutNs = 2'000'000'000;  ///< no frame within this: next() is Lost ("stalled")
    std::int64_t firstFrameTimeoutNs = 5'000'000'000;  ///< for the first frame (webcams are slow)
};

/// \class V4l2Source
/// A single-planar V4L2 capture device streaming into driver buffers mapped once at start.
///
/// The constructor opens the device, checks it can capture and stream, negotiates the format with
/// chooseV4l2Format (a raw format of `formats` the device lists, else MJPEG), sets it at the
/// requested size (the driver may adjust it: size() says what was granted), requests and maps the
/// buffers, queues them all and starts streaming. It throws std::runtime_error with one line
/// ("v4l2:/dev/video0: ...") when any step fails.
///
/// next() waits for a filled buffer with poll() (a timeout, no busy loop, no FD_SETSIZE limit),
/// dequeues every buffer that is ready and keeps the newest, queueing the older ones again at once.
/// Raw formats are delivered as a view into the mapped buffer, which stays dequeued until the
/// following next(); MJPEG frames are decoded (MjpegDecoder) into one preallocated RGB24 image and
/// their buffer is queued again at once. Buffers the driver marks as erroneous and frames that do
/// not decode are skipped (failedFrames()). Timestamps are the driver's when it says they are
/// CLOCK_MONOTONIC, else the time of dequeueing.
///
/// next() returns Lost, with lastError() set, when the device is unplugged (ENODEV), fails, or
/// delivers nothing within the timeout; the source then stays Lost (ReconnectingSource reopens
/// it). next() never throws and never allocates (libjpeg's own working memory aside, see
/// MjpegDecoder).
class V4l2Source final : public FrameSource {
public:
    explicit V4l2Source(const V4l2Options& options);
    ~V4l2Source() override;

    /// E.g. "v4l2:/dev/video0 vivid (640x480 YUYV)" or "... (640x480 MJPEG -> RGB24)".
    const char* description() const noexcept override;
    vision::Size size() const noexcept override;
    vision::PixelFormat format() const noexcept override;
    SourceStatus next(vision::Frame& frame) noexcept override;
    std::int64_t lastWaitNs() const noexcept override;
    const char* lastError() const noexcept override;

    /// Whether frames are MJPEG decoded by us.
    bool decodesMjpeg() const noexcept;
    /// Frames skipped: marked erroneous by the driver, or not decodable.
    std::uint64_t failedFrames() const noexcept;
    /// Filled buffers requeued unseen because a newer one was ready.
    std::uint64_t droppedFrames() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// The first /dev/videoN (N = 0..63) that can capture and stream single-planar video in a format
/// V4l2Source takes (a raw format or MJPEG); "" when there is none.
std::string findV4l2CaptureDevice();
/// Whether findV4l2CaptureDevice() finds one.
bool v4l2CaptureDeviceAvailable() noexcept;

}  // namespace platform
