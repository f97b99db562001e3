#include "platform/v4l2_source.hpp"

#include "platform/camera_formats.hpp"
#include "platform/mjpeg_decoder.hpp"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <optional>
#include <stdexcept>
#include <string>

namespace platform {

namespace {

std::int64_t monotonicNs() noexcept
{
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

int xioctl(int fd, unsigned long request, void* arg) noexcept
{
    int ret;
    do {
        ret = ioctl(fd, request, arg);
    } while (ret < 0 && errno == EINTR);
    return ret;
}

/// The capabilities of this node (not of the whole physical device).
std::uint32_t nodeCapabilities(const v4l2_capability& cap) noexcept
{
    return (cap.capabilities & V4L2_CAP_DEVICE_CAPS) != 0 ? cap.device_caps : cap.capabilities;
}

std::vector<std::uint32_t> listFormats(int fd)
{
    std::vector<std::uint32_t> codes;
    for (std::uint32_t i = 0; i < 256; ++i) {
        v4l2_fmtdesc desc{};
        desc.index = i;
        desc.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        if (xioctl(fd, VIDIOC_ENUM_FMT, &desc) < 0)
            break;
        codes.push_back(desc.pixelformat);
    }
    return codes;
}

struct Mapping {
    void* address = MAP_FAILED;
    std::size_t length = 0;
};

}  // namespace

struct V4l2Source::Impl {
    std::string device;
    int fd = -1;
    bool streaming = false;
    std::vector<Mapping> buffers;
    std::optional<MjpegDecoder> decoder;
    V4l2FormatChoice choice;
    vision::Size size;
    int stride = 0;
    std::int64_t timeoutNs = 0;
    std::int64_t firstFrameTimeoutNs = 0;

    int held = -1;  ///< buffer index the caller is viewing (raw formats)
    bool lost = false;
    std::uint64_t sequence = 0;
    std::uint64_t failed = 0;
    std::uint64_t dropped = 0;
    std::int64_t lastWaitNs = 0;
    std::string description;
    char error[256] = {};

    [[noreturn]] void fail(const std::string& what) const
    {
        throw std::runtime_error("v4l2:" + device + ": " + what);
    }
    [[noreturn]] void failErrno(const std::string& what) const
    {
        fail(what + ": " + std::strerror(errno));
    }

    void open(const V4l2Options& options);
    void close() noexcept;
    bool queue(int index) noexcept;
    SourceStatus lose(const char* what, int err) noexcept;
    SourceStatus next(vision::Frame& frame) noexcept;
};

void V4l2Source::Impl::open(const V4l2Options& options)
{
    device = options.device;
    if (options.width < 16 || options.height < 16 || options.width > 16384 ||
        options.height > 16384)
        fail("invalid size " + std::to_string(options.width) + "x" +
             std::to_string(options.height));
    timeoutNs = options.timeoutNs > 0 ? options.timeoutNs : 2'000'000'000;
    firstFrameTimeoutNs = std::max(options.firstFrameTimeoutNs, timeoutNs);

    fd = ::open(device.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        failErrno("cannot open");
    v4l2_capability cap{};
    if (xioctl(fd, VIDIOC_QUERYCAP, &cap) < 0)
        failErrno("not a V4L2 device (VIDIOC_QUERYCAP)");
    const std::uint32_t caps = nodeCapabilities(cap);
    if ((caps & V4L2_CAP_VIDEO_CAPTURE) == 0) {
        if ((caps & V4L2_CAP_VIDEO_CAPTURE_MPLANE) != 0)
            fail("multi-planar capture devices are not supported (use libcamera)");
        fail("not a video capture device");
    }
    if ((caps & V4L2_CAP_STREAMING) == 0)
        fail("the driver cannot stream (no V4L2_CAP_STREAMING)");

    const std::vector<std::uint32_t> offered = listFormats(fd);
    const std::vector<vision::PixelFormat> preference =
        options.formats.empty() ? defaultFormatPreference() : options.formats;
    const std::optional<V4l2FormatChoice> chosen =
        chooseV4l2Format(offered, preference, options.allowMjpeg);
    if (!chosen) {
        std::string list;
        char text[16];
        for (const std::uint32_t code : offered)
            list += std::string(list.empty() ? "" : " ") + fourccName(code, text, sizeof text);
        fail("offers none of the formats we take (offered: " + (list.empty() ? "none" : list) +
             ")");
    }
    choice = *chosen;

    v4l2_format fmt{};
    fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    fmt.fmt.pix.width = static_cast<std::uint32_t>(options.width);
    fmt.fmt.pix.height = static_cast<std::uint32_t>(options.height);
    fmt.fmt.pix.pixelformat = choice.fourcc;
    fmt.fmt.pix.field = V4L2_FIELD_NONE;
    if (xioctl(fd, VIDIOC_S_FMT, &fmt) < 0)
        failErrno("cannot set the format (VIDIOC_S_FMT)");
    char want[16];
    char got[16];
    if (fmt.fmt.pix.pixelformat != choice.fourcc)
        fail(std::string("asked for ") + fourccName(choice.fourcc, want, sizeof want) +
             ", the driver set " + fourccName(fmt.fmt.pix.pixelformat, got, sizeof got));
    size = {static_cast<int>(fmt.fmt.pix.width), static_cast<int>(fmt.fmt.pix.height)};
    if (size.width < 16 || size.height < 16)
        fail("the driver set an unusable size " + std::to_string(size.width) + "x" +
             std::to_string(size.height));
    const int minStride = size.width * vision::bytesPerPixel(choice.format);
    stride = choice.mjpeg ? minStride : static_cast<int>(fmt.fmt.pix.bytesperline);
    if (stride == 0)
        stride = minStride;
    if (stride < minStride)
        fail("bytes per line " + std::to_string(stride) + " too small");
    if (!choice.mjpeg) {
        const std::size_t frameBytes = vision::imageBytes(choice.format, size.height, stride);
        if (fmt.fmt.pix.sizeimage != 0 && fmt.fmt.pix.sizeimage < frameBytes)
            fail("image size " + std::to_string(fmt.fmt.pix.sizeimage) + " smaller than a frame");
        if ((choice.format == vision::PixelFormat::YUYV ||
             choice.format == vision::PixelFormat::NV12) &&
            (size.width % 2 != 0 || size.height % 2 != 0))
            fail("odd size for a YUV format");
    }

    // The rate is a wish: drivers without V4L2_CAP_TIMEPERFRAME keep theirs.
    v4l2_streamparm parm{};
    parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (options.fps > 0.0 && std::isfinite(options.fps) && xioctl(fd, VIDIOC_G_PARM, &parm) == 0 &&
        (parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME) != 0) {
        parm.parm.capture.timeperframe.numerator = 1000;
        parm.parm.capture.timeperframe.denominator =
            static_cast<std::uint32_t>(std::lround(options.fps * 1000.0));
        xioctl(fd, VIDIOC_S_PARM, &parm);
    }

    if (options.bufferCount < 2 || options.bufferCount > 32)
        fail("buffer count must be 2..32, not " + std::to_string(options.bufferCount));
    v4l2_requestbuffers request{};
    request.count = static_cast<std::uint32_t>(options.bufferCount);
    request.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    request.memory = V4L2_MEMORY_MMAP;
    if (xioctl(fd, VIDIOC_REQBUFS, &request) < 0)
        failErrno("cannot request buffers (VIDIOC_REQBUFS)");
    if (request.count < 2)
        fail("the driver granted " + std::to_string(request.count) + " buffer(s); 2 are needed");
    for (std::uint32_t i = 0; i < request.count; ++i) {
        v4l2_buffer buf{};
        buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        buf.memory = V4L2_MEMORY_MMAP;
        buf.index = i;
        if (xioctl(fd, VIDIOC_QUERYBUF, &buf) < 0)
            failErrno("cannot query buffer " + std::to_string(i));
        void* address = mmap(nullptr, buf.length, PROT_READ, MAP_SHARED, fd, buf.m.offset);
        if (address == MAP_FAILED)
            failErrno("cannot map buffer " + std::to_string(i));
        buffers.push_back({address, buf.length});
        if (!choice.mjpeg && buf.length < vision::imageBytes(choice.format, size.height, stride))
            fail("buffer " + std::to_string(i) + " smaller than a frame");
    }
    if (choice.mjpeg)
        decoder.emplace(size.width, size.height);

    for (std::size_t i = 0; i < buffers.size(); ++i)
        if (!queue(static_cast<int>(i)))
            fail(error);
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(fd, VIDIOC_STREAMON, &type) < 0)
        failErrno("cannot start streaming (VIDIOC_STREAMON)");
    streaming = true;

    const char* card = reinterpret_cast<const char*>(cap.card);
    char text[16];
    description =
        "v4l2:" + device + " " + std::string(card, strnlen(card, sizeof cap.card)) + " (" +
        std::to_string(size.width) + "x" + std::to_string(size.height) + " " +
        (choice.mjpeg ? std::string(fourccName(choice.fourcc, text, sizeof text)) + " -> RGB24"
                      : std::string(vision::pixelFormatName(choice.format))) +
        ")";
}

void V4l2Source::Impl::close() noexcept
{
    if (fd >= 0 && streaming) {
        int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        xioctl(fd, VIDIOC_STREAMOFF, &type);
    }
    for (const Mapping& m : buffers)
        munmap(m.address, m.length);
    buffers.clear();
    if (fd >= 0) {
        // Frees the driver's buffers now rather than at close (some drivers keep them otherwise).
        v4l2_requestbuffers request{};
        request.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        request.memory = V4L2_MEMORY_MMAP;
        xioctl(fd, VIDIOC_REQBUFS, &request);
        ::close(fd);
    }
    fd = -1;
    streaming = false;
}

bool V4l2Source::Impl::queue(int index) noexcept
{
    v4l2_buffer buf{};
    buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buf.memory = V4L2_MEMORY_MMAP;
    buf.index = static_cast<std::uint32_t>(index);
    if (xioctl(fd, VIDIOC_QBUF, &buf) < 0) {
        std::snprintf(error, sizeof error, "v4l2:%s: cannot queue buffer %d: %s", device.c_str(),
                      index, std::strerror(errno));
        return false;
    }
    return true;
}

SourceStatus V4l2Source::Impl::lose(const char* what, int err) noexcept
{
    lost = true;
    if (err == ENODEV)
        std::snprintf(error, sizeof error, "v4l2:%.120s: device unplugged", device.c_str());
    else if (err != 0)
        std::snprintf(error, sizeof error, "v4l2:%.120s: %.60s: %.60s", device.c_str(), what,
                      std::strerror(err));
    else
        std::snprintf(error, sizeof error, "v4l2:%.120s: %.120s", device.c_str(), what);
    return SourceStatus::Lost;
}

SourceStatus V4l2Source::Impl::next(vision::Frame& frame) noexcept
{
    lastWaitNs = 0;
    if (lost)
        return SourceStatus::Lost;
    if (held >= 0) {
        const int index = held;
        held = -1;
        if (!queue(index)) {
            lost = true;
            return SourceStatus::Lost;
        }
    }

    const std::int64_t startNs = monotonicNs();
    const std::int64_t deadlineNs = startNs + (sequence == 0 ? firstFrameTimeoutNs : timeoutNs);
    std::int64_t waitedNs = 0;
    for (;;) {
        // Take every filled buffer; keep the newest good one.
        v4l2_buffer newest{};
        bool have = false;
        for (;;) {
            v4l2_buffer buf{};
            buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
            buf.memory = V4L2_MEMORY_MMAP;
            if (xioctl(fd, VIDIOC_DQBUF, &buf) < 0) {
                if (errno == EAGAIN)
                    break;
                const int err = errno;
                if (have)
                    queue(static_cast<int>(newest.index));
                lastWaitNs = waitedNs;
                return lose("cannot dequeue a buffer", err);
            }
            if ((buf.flags & V4L2_BUF_FLAG_ERROR) != 0 || buf.index >= buffers.size() ||
                buf.bytesused == 0) {
                ++failed;
                if (buf.index < buffers.size() && !queue(static_cast<int>(buf.index))) {
                    lost = true;  // queue() said why
                    return SourceStatus::Lost;
                }
                continue;
            }
            if (have) {
                ++dropped;
                if (!queue(static_cast<int>(newest.index))) {
                    lost = true;
                    return SourceStatus::Lost;
                }
            }
            newest = buf;
            have = true;
        }

        if (have) {
            const std::uint8_t* data =
                static_cast<const std::uint8_t*>(buffers[newest.index].address);
            const bool monotonic =
                (newest.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;
            const std::int64_t timestampNs =
                monotonic ? static_cast<std::int64_t>(newest.timestamp.tv_sec) * 1'000'000'000 +
                                static_cast<std::int64_t>(newest.timestamp.tv_usec) * 1000
                          : monotonicNs();
            lastWaitNs = waitedNs;
            if (decoder) {
                const bool decoded = decoder->decode(data, newest.bytesused);
                if (!queue(static_cast<int>(newest.index))) {
                    lost = true;
                    return SourceStatus::Lost;
                }
                if (!decoded) {
                    ++failed;
                    if (monotonicNs() >= deadlineNs)
                        return lose(decoder->lastError(), 0);
                    continue;
                }
                frame.image = decoder->image();
            } else {
                held = static_cast<int>(newest.index);
                frame.image = {data, size.width, size.height, stride, choice.format};
            }
            frame.sequence = sequence++;
            frame.timestampNs = timestampNs;
            return SourceStatus::Ok;
        }

        const std::int64_t nowNs = monotonicNs();
        if (nowNs >= deadlineNs) {
            lastWaitNs = waitedNs;
            char why[64];
            std::snprintf(why, sizeof why, "no frame for %.1f s (camera stalled)",
                          static_cast<double>(deadlineNs - startNs) / 1e9);
            return lose(why, 0);
        }
        pollfd pfd{fd, POLLIN, 0};
        const int timeoutMs = static_cast<int>((deadlineNs - nowNs + 999'999) / 1'000'000);
        const int ready = poll(&pfd, 1, timeoutMs);
        waitedNs += monotonicNs() - nowNs;
        if (ready < 0 && errno != EINTR)
            return lose("poll failed", errno);
        if (ready > 0 && (pfd.revents & (POLLERR | POLLHUP | POLLNVAL)) != 0 &&
            (pfd.revents & POLLIN) == 0) {
            // Unplugged devices report POLLERR; DQBUF then says ENODEV.
            v4l2_buffer buf{};
            buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
            buf.memory = V4L2_MEMORY_MMAP;
            if (xioctl(fd, VIDIOC_DQBUF, &buf) < 0 && errno != EAGAIN)
                return lose("device error", errno);
            if (buf.index < buffers.size())
                queue(static_cast<int>(buf.index));
            return lose("device error (POLLERR)", 0);
        }
    }
}

V4l2Source::V4l2Source(const V4l2Options& options) : impl_(std::make_unique<Impl>())
{
    try {
        impl_->open(options);
    } catch (...) {
        impl_->close();
        throw;
    }
}

V4l2Source::~V4l2Source()
{
    impl_->close();
}

const char* V4l2Source::description() const noexcept
{
    return impl_->description.c_str();
}

vision::Size V4l2Source::size() const noexcept
{
    return impl_->size;
}

vision::PixelFormat V4l2Source::format() const noexcept
{
    return impl_->choice.format;
}

SourceStatus V4l2Source::next(vision::Frame& frame) noexcept
{
    return impl_->next(frame);
}

std::int64_t V4l2Source::lastWaitNs() const noexcept
{
    return impl_->lastWaitNs;
}

const char* V4l2Source::lastError() const noexcept
{
    return impl_->error;
}

bool V4l2Source::decodesMjpeg() const noexcept
{
    return impl_->choice.mjpeg;
}

std::uint64_t V4l2Source::failedFrames() const noexcept
{
    return impl_->failed;
}

std::uint64_t V4l2Source::droppedFrames() const noexcept
{
    return impl_->dropped;
}

std::string findV4l2CaptureDevice()
{
    const std::vector<vision::PixelFormat> preference = defaultFormatPreference();
    for (int n = 0; n < 64; ++n) {
        const std::string path = "/dev/video" + std::to_string(n);
        const int fd = ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0)
            continue;
        v4l2_capability cap{};
        bool usable = false;
        if (xioctl(fd, VIDIOC_QUERYCAP, &cap) == 0) {
            const std::uint32_t caps = nodeCapabilities(cap);
            if ((caps & V4L2_CAP_VIDEO_CAPTURE) != 0 && (caps & V4L2_CAP_STREAMING) != 0)
                usable = chooseV4l2Format(listFormats(fd), preference, true).has_value();
        }
        ::close(fd);
        if (usable)
            return path;
    }
    return {};
}

bool v4l2CaptureDeviceAvailable() noexcept
{
    try {
        return !findV4l2CaptureDevice().empty();
    } catch (...) {
        return false;
    }
}

}  // namespace platform
