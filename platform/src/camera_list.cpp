#include "platform/camera_list.hpp"

#include "platform/camera_formats.hpp"

#include <fcntl.h>
#include <libcamera/libcamera.h>
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

namespace platform {

namespace {

int ioctlRetry(int fd, unsigned long request, void* arg)
{
    int r;
    do {
        r = ::ioctl(fd, request, arg);
    } while (r < 0 && errno == EINTR);
    return r;
}

/// libcamera: each camera's id and model, and what its viewfinder stream offers.
int listLibcameraCameras(std::FILE* out)
{
    // Its own INFO lines would drown the list (LIBCAMERA_LOG_LEVELS still turns them on).
    if (std::getenv("LIBCAMERA_LOG_LEVELS") == nullptr)
        libcamera::logSetTarget(libcamera::LoggingTargetNone);
    libcamera::CameraManager manager;
    if (const int r = manager.start(); r < 0) {
        std::fprintf(out, "libcamera: cannot start the camera manager (error %d)\n", r);
        return 0;
    }
    const auto cameras = manager.cameras();
    std::fprintf(out, "libcamera cameras: %zu\n", cameras.size());
    int index = 0;
    for (const auto& camera : cameras) {
        const auto model = camera->properties().get(libcamera::properties::Model);
        std::fprintf(out, "%d : %s [libcamera:%d]\n    id %s\n", index,
                     model ? model->c_str() : "?", index, camera->id().c_str());
        ++index;
        const auto config = camera->generateConfiguration({libcamera::StreamRole::Viewfinder});
        if (!config || config->empty()) {
            std::fprintf(out, "    no viewfinder configuration\n");
            continue;
        }
        const libcamera::StreamFormats& formats = config->at(0).formats();
        for (const libcamera::PixelFormat& format : formats.pixelformats()) {
            std::fprintf(out, "    '%s':", format.toString().c_str());
            for (const libcamera::Size& size : formats.sizes(format))
                std::fprintf(out, " %ux%u", size.width, size.height);
            std::fprintf(out, "\n");
        }
    }
    manager.stop();
    return static_cast<int>(cameras.size());
}

/// One V4L2 node: false when it is not a video capture device.
bool listV4l2Device(std::FILE* out, const std::string& path, int fd)
{
    v4l2_capability cap{};
    if (ioctlRetry(fd, VIDIOC_QUERYCAP, &cap) != 0)
        return false;
    const std::uint32_t caps =
        (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
    if ((caps & V4L2_CAP_VIDEO_CAPTURE) == 0)
        return false;
    std::fprintf(out, "%s : %s (%s, %s)%s [v4l2:%s]\n", path.c_str(),
                 reinterpret_cast<const char*>(cap.card), reinterpret_cast<const char*>(cap.driver),
                 reinterpret_cast<const char*>(cap.bus_info),
                 (caps & V4L2_CAP_STREAMING) ? "" : " (no streaming: not usable)", path.c_str());
    v4l2_fmtdesc desc{};
    desc.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    for (desc.index = 0; ioctlRetry(fd, VIDIOC_ENUM_FMT, &desc) == 0; ++desc.index) {
        char name[16];
        std::fprintf(out, "    '%s' %s:", fourccName(desc.pixelformat, name, sizeof name),
                     reinterpret_cast<const char*>(desc.description));
        v4l2_frmsizeenum size{};
        size.pixel_format = desc.pixelformat;
        for (size.index = 0; ioctlRetry(fd, VIDIOC_ENUM_FRAMESIZES, &size) == 0; ++size.index) {
            if (size.type == V4L2_FRMSIZE_TYPE_DISCRETE) {
                std::fprintf(out, " %ux%u", size.discrete.width, size.discrete.height);
            } else {
                std::fprintf(out, " %ux%u..%ux%u", size.stepwise.min_width,
                             size.stepwise.min_height, size.stepwise.max_width,
                             size.stepwise.max_height);
                break;
            }
        }
        std::fprintf(out, "\n");
    }
    return true;
}

int listV4l2Cameras(std::FILE* out)
{
    int found = 0;
    std::fprintf(out, "V4L2 capture devices:\n");
    for (int n = 0; n < 64; ++n) {
        const std::string path = "/dev/video" + std::to_string(n);
        const int fd = ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0) {
            if (errno != ENOENT)
                std::fprintf(out, "%s : cannot open: %s\n", path.c_str(), std::strerror(errno));
            continue;
        }
        found += listV4l2Device(out, path, fd);
        ::close(fd);
    }
    if (found == 0)
        std::fprintf(out, "    none\n");
    return found;
}

}  // namespace

int listCameras(std::FILE* out)
{
    int found = 0;
    try {
        found += listLibcameraCameras(out);
    } catch (const std::exception& e) {
        std::fprintf(out, "libcamera: %s\n", e.what());
    }
    found += listV4l2Cameras(out);
    return found;
}

}  // namespace platform
