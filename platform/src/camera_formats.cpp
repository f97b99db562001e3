#include "platform/camera_formats.hpp"

#include <algorithm>
#include <cstdio>

namespace platform {

namespace {

bool offers(std::span<const std::uint32_t> offered, std::uint32_t code)
{
    return std::find(offered.begin(), offered.end(), code) != offered.end();
}

}  // namespace

const char* fourccName(std::uint32_t code, char* out, std::size_t size) noexcept
{
    bool printable = true;
    char text[5] = {};
    for (int i = 0; i < 4; ++i) {
        const char c = static_cast<char>((code >> (8 * i)) & 0xff);
        printable = printable && c >= 0x20 && c < 0x7f;
        text[i] = c;
    }
    if (printable)
        std::snprintf(out, size, "%s", text);
    else
        std::snprintf(out, size, "0x%08x", static_cast<unsigned>(code));
    return out;
}

std::optional<vision::PixelFormat> pixelFormatFromLibcamera(std::uint32_t code) noexcept
{
    switch (code) {
        case libcameraFourcc::BGR888:
            return vision::PixelFormat::RGB24;
        case libcameraFourcc::RGB888:
            return vision::PixelFormat::BGR24;
        case libcameraFourcc::XRGB8888:
            return vision::PixelFormat::XRGB8888;
        case libcameraFourcc::YUYV:
            return vision::PixelFormat::YUYV;
        case libcameraFourcc::NV12:
            return vision::PixelFormat::NV12;
        default:
            return std::nullopt;
    }
}

std::uint32_t libcameraFourccFor(vision::PixelFormat format) noexcept
{
    switch (format) {
        case vision::PixelFormat::RGB24:
            return libcameraFourcc::BGR888;
        case vision::PixelFormat::BGR24:
            return libcameraFourcc::RGB888;
        case vision::PixelFormat::XRGB8888:
            return libcameraFourcc::XRGB8888;
        case vision::PixelFormat::YUYV:
            return libcameraFourcc::YUYV;
        case vision::PixelFormat::NV12:
            return libcameraFourcc::NV12;
        case vision::PixelFormat::Gray8:
            return 0;
    }
    return 0;
}

std::optional<vision::PixelFormat> pixelFormatFromV4l2(std::uint32_t code) noexcept
{
    switch (code) {
        case v4l2Fourcc::RGB24:
            return vision::PixelFormat::RGB24;
        case v4l2Fourcc::BGR24:
            return vision::PixelFormat::BGR24;
        case v4l2Fourcc::XBGR32:
        case v4l2Fourcc::BGR32:
            return vision::PixelFormat::XRGB8888;
        case v4l2Fourcc::YUYV:
            return vision::PixelFormat::YUYV;
        case v4l2Fourcc::NV12:
            return vision::PixelFormat::NV12;
        default:
            return std::nullopt;
    }
}

std::vector<vision::PixelFormat> defaultFormatPreference()
{
    return {vision::PixelFormat::RGB24, vision::PixelFormat::BGR24, vision::PixelFormat::XRGB8888,
            vision::PixelFormat::YUYV, vision::PixelFormat::NV12};
}

std::optional<vision::PixelFormat> chooseLibcameraFormat(
    std::span<const std::uint32_t> offered, std::span<const vision::PixelFormat> preference)
{
    for (const vision::PixelFormat format : preference) {
        const std::uint32_t code = libcameraFourccFor(format);
        if (code != 0 && offers(offered, code))
            return format;
    }
    return std::nullopt;
}

std::optional<V4l2FormatChoice> chooseV4l2Format(std::span<const std::uint32_t> offered,
                                                 std::span<const vision::PixelFormat> preference,
                                                 bool allowMjpeg)
{
    for (const vision::PixelFormat format : preference) {
        // The first code in the device's own order that maps to this format (XR24 before BGR4).
        for (const std::uint32_t code : offered) {
            const std::optional<vision::PixelFormat> mapped = pixelFormatFromV4l2(code);
            if (mapped && *mapped == format)
                return V4l2FormatChoice{code, format, false};
        }
    }
    if (allowMjpeg) {
        for (const std::uint32_t code : {v4l2Fourcc::MJPEG, v4l2Fourcc::JPEG}) {
            if (offers(offered, code))
                return V4l2FormatChoice{code, vision::PixelFormat::RGB24, true};
        }
    }
    return std::nullopt;
}

}  // namespace platform
