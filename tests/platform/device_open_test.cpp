// Real devices that are not there: every constructor fails with one clear line, and a
// ReconnectingSource over a missing camera starts anyway and keeps its reason. Runs on machines
// without /dev/dri, /dev/video* or a libcamera camera (skips the checks that assume absence where
// such a device exists).

#include "platform/drm_display.hpp"
#include "platform/libcamera_source.hpp"
#include "platform/reconnecting_source.hpp"
#include "platform/v4l2_source.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace {

/// The message of the std::runtime_error `f` throws ("" when it does not throw).
std::string failure(const std::function<void()>& f)
{
    try {
        f();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

void expectOneLine(const std::string& message, const std::string& contains)
{
    EXPECT_NE(message.find(contains), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(DeviceOpen, V4l2MissingDeviceSaysWhich)
{
    platform::V4l2Options options;
    options.device = "/dev/video-not-here";
    expectOneLine(failure([&] { platform::V4l2Source source(options); }),
                  "v4l2:/dev/video-not-here: cannot open: No such file or directory");
    options.device = "/dev/null";
    expectOneLine(failure([&] { platform::V4l2Source source(options); }),
                  "v4l2:/dev/null: not a V4L2 device (VIDIOC_QUERYCAP)");
}

TEST(DeviceOpen, LibcameraWithoutCamera)
{
    if (platform::libcameraCameraAvailable())
        GTEST_SKIP() << "this machine has a libcamera camera";
    platform::LibcameraOptions options;
    expectOneLine(failure([&] { platform::LibcameraSource source(options); }),
                  "libcamera: camera 0: no camera found");
    options.camera = "platform/vimc.0 Sensor B";
    expectOneLine(failure([&] { platform::LibcameraSource source(options); }),
                  "libcamera: platform/vimc.0 Sensor B: no camera found");
    // The CameraManager of a failed open is gone: another can start (only one may exist).
    EXPECT_FALSE(platform::libcameraCameraAvailable());
}

TEST(DeviceOpen, DrmWithoutDisplay)
{
    platform::DrmOptions options;
    options.card = "/dev/dri/card-not-here";
    expectOneLine(failure([&] { platform::DrmDisplay display(options); }),
                  "drm: /dev/dri/card-not-here: No such file or directory");
    options.card = "/dev/null";
    expectOneLine(failure([&] { platform::DrmDisplay display(options); }),
                  "drm: /dev/null: not a KMS device");
    options.card.clear();
    options.mode = "1280x720@fast";
    expectOneLine(failure([&] { platform::DrmDisplay display(options); }),
                  "drm: display mode 1280x720@fast: refresh rate");
    if (platform::drmDisplayAvailable())
        GTEST_SKIP() << "this machine has a connected display";
    options.mode.clear();
    const std::string message = failure([&] { platform::DrmDisplay display(options); });
    EXPECT_TRUE(message.find("drm: no /dev/dri/card*") == 0 ||
                message.find("drm: no card with a connected display") == 0)
        << message;
}

TEST(DeviceOpen, ProbesAnswerWithoutThrowing)
{
    // Whatever the machine has; they must simply answer.
    (void)platform::drmDisplayAvailable();
    (void)platform::v4l2CaptureDeviceAvailable();
    (void)platform::libcameraCameraAvailable();
    const std::string device = platform::findV4l2CaptureDevice();
    EXPECT_TRUE(device.empty() || device.rfind("/dev/video", 0) == 0) << device;
}

TEST(DeviceOpen, ReconnectingSourceStartsWithoutItsCamera)
{
    platform::V4l2Options options;
    options.device = "/dev/video-not-here";
    platform::ReconnectingSource source(
        "v4l2:/dev/video-not-here",
        [options] { return std::make_unique<platform::V4l2Source>(options); }, {640, 480},
        vision::PixelFormat::RGB24);
    EXPECT_EQ(source.state(), platform::CameraState::Lost);
    EXPECT_STREQ(source.description(), "v4l2:/dev/video-not-here (unavailable)");
    expectOneLine(source.lastError(), "cannot open: No such file or directory");
    vision::Frame frame;
    EXPECT_EQ(source.next(frame), platform::SourceStatus::Lost);
    EXPECT_EQ(source.size(), (vision::Size{640, 480}));
}

}  // namespace
