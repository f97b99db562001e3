#pragma once
// Camera pixel formats: libcamera/DRM and V4L2 four-character codes mapped to vision::PixelFormat
// by byte order in memory, and the negotiation of one format from what a camera offers. Pure
// functions, no device headers, so they are tested on machines without a camera.

#include "vision/image.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace platform {

/// A four-character code as DRM, libcamera and V4L2 build it: 'a' | 'b' << 8 | 'c' << 16 | 'd'
/// << 24.
constexpr std::uint32_t fourcc(char a, char b, char c, char d) noexcept
{
    return static_cast<std::uint32_t>(static_cast<unsigned char>(a)) |
           static_cast<std::uint32_t>(static_cast<unsigned char>(b)) << 8 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(c)) << 16 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(d)) << 24;
}

/// "BG24" for a printable code, else "0x%08x"; into `out` (at least 11 bytes).
const char* fourccName(std::uint32_t code, char* out, std::size_t size) noexcept;

/// libcamera (= DRM) formats the vision core takes. DRM names a packed format by its
/// little-endian word, so "BGR888" has the bytes R,G,B in memory: it is our RGB24.
namespace libcameraFourcc {
inline constexpr std::uint32_t BGR888 = fourcc('B', 'G', '2', '4');    ///< bytes R,G,B
inline constexpr std::uint32_t RGB888 = fourcc('R', 'G', '2', '4');    ///< bytes B,G,R
inline constexpr std::uint32_t XRGB8888 = fourcc('X', 'R', '2', '4');  ///< bytes B,G,R,X
inline constexpr std::uint32_t YUYV = fourcc('Y', 'U', 'Y', 'V');
inline constexpr std::uint32_t NV12 = fourcc('N', 'V', '1', '2');
}  // namespace libcameraFourcc

/// V4L2 formats we capture. V4L2 names packed RGB by byte order: RGB24 is bytes R,G,B.
namespace v4l2Fourcc {
inline constexpr std::uint32_t RGB24 = fourcc('R', 'G', 'B', '3');   ///< bytes R,G,B
inline constexpr std::uint32_t BGR24 = fourcc('B', 'G', 'R', '3');   ///< bytes B,G,R
inline constexpr std::uint32_t XBGR32 = fourcc('X', 'R', '2', '4');  ///< bytes B,G,R,X
inline constexpr std::uint32_t BGR32 = fourcc('B', 'G', 'R', '4');   ///< bytes B,G,R,X (deprecated)
inline constexpr std::uint32_t YUYV = fourcc('Y', 'U', 'Y', 'V');
inline constexpr std::uint32_t NV12 = fourcc('N', 'V', '1', '2');
inline constexpr std::uint32_t MJPEG = fourcc('M', 'J', 'P', 'G');
inline constexpr std::uint32_t JPEG = fourcc('J', 'P', 'E', 'G');
}  // namespace v4l2Fourcc

/// Our format for a libcamera/DRM fourcc; nullopt when the vision core does not take it.
std::optional<vision::PixelFormat> pixelFormatFromLibcamera(std::uint32_t code) noexcept;
/// The libcamera fourcc with the same memory layout (0 for Gray8, which we never request).
std::uint32_t libcameraFourccFor(vision::PixelFormat format) noexcept;
/// Our format for a raw V4L2 fourcc (MJPEG/JPEG are not raw: nullopt).
std::optional<vision::PixelFormat> pixelFormatFromV4l2(std::uint32_t code) noexcept;

/// The formats a consumer takes, best first. The default puts the packed RGB formats the renderer
/// uploads directly before the YUV formats only the vision core converts.
std::vector<vision::PixelFormat> defaultFormatPreference();

/// The first format of `preference` that libcamera offers in `offered`; nullopt when none.
std::optional<vision::PixelFormat> chooseLibcameraFormat(
    std::span<const std::uint32_t> offered, std::span<const vision::PixelFormat> preference);

/// What a V4L2 device is asked for, and what the frame loop then sees.
struct V4l2FormatChoice {
    std::uint32_t fourcc = 0;                                 ///< requested from the driver
    vision::PixelFormat format = vision::PixelFormat::RGB24;  ///< delivered to the caller
    bool mjpeg = false;  ///< compressed: decoded to RGB24 by the source
};

/// The first raw format of `preference` the device offers; else MJPEG (or JPEG) decoded to RGB24
/// when offered and `allowMjpeg`; else nullopt.
std::optional<V4l2FormatChoice> chooseV4l2Format(std::span<const std::uint32_t> offered,
                                                 std::span<const vision::PixelFormat> preference,
                                                 bool allowMjpeg);

}  // namespace platform
