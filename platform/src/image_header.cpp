#include "image_header.hpp"

#include "vision/input_limits.hpp"

#include <cstring>

namespace platform {

namespace {

std::uint32_t bigEndian16(const std::uint8_t* p)
{
    return (std::uint32_t{p[0]} << 8) | p[1];
}

std::uint32_t bigEndian32(const std::uint8_t* p)
{
    return (bigEndian16(p) << 16) | bigEndian16(p + 2);
}

std::int32_t littleEndian32(const std::uint8_t* p)
{
    const std::uint32_t u = std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) |
                            (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
    return static_cast<std::int32_t>(u);
}

/// PNG: the signature, then the IHDR chunk: width and height, 4 bytes each, big-endian.
std::optional<ImageHeaderSize> pngSize(const std::uint8_t* b, std::size_t size)
{
    static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size < 24 || std::memcmp(b, kSignature, 8) != 0 || std::memcmp(b + 12, "IHDR", 4) != 0)
        return std::nullopt;
    return ImageHeaderSize{bigEndian32(b + 16), bigEndian32(b + 20)};
}

/// JPEG: markers from SOI on; the first start-of-frame (SOF0-SOF15 but DHT, JPG and DAC) holds
/// height then width, 2 bytes each.
std::optional<ImageHeaderSize> jpegSize(const std::uint8_t* b, std::size_t size)
{
    if (size < 4 || b[0] != 0xFF || b[1] != 0xD8)
        return std::nullopt;
    std::size_t at = 2;
    while (at + 4 <= size) {
        if (b[at] != 0xFF)
            return std::nullopt;
        const std::uint8_t marker = b[at + 1];
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        if (marker == 0xD8 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {
            at += 2;  // markers without a length
            continue;
        }
        const std::size_t length = bigEndian16(b + at + 2);
        if (length < 2)
            return std::nullopt;
        const bool sof =
            marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (sof) {
            if (at + 9 > size)
                return std::nullopt;
            return ImageHeaderSize{bigEndian16(b + at + 7), bigEndian16(b + at + 5)};
        }
        if (marker == 0xDA || marker == 0xD9)  // scan data or end before any frame header
            return std::nullopt;
        at += 2 + length;
    }
    return std::nullopt;
}

/// BMP: "BM", then at 18 and 22 the width and height, 4 bytes each, little-endian (a negative
/// height means top-down rows).
std::optional<ImageHeaderSize> bmpSize(const std::uint8_t* b, std::size_t size)
{
    if (size < 26 || b[0] != 'B' || b[1] != 'M')
        return std::nullopt;
    const std::int64_t height = littleEndian32(b + 22);
    return ImageHeaderSize{littleEndian32(b + 18), height < 0 ? -height : height};
}

}  // namespace

std::optional<ImageHeaderSize> imageHeaderSize(const std::uint8_t* bytes, std::size_t size)
{
    if (auto png = pngSize(bytes, size))
        return png;
    if (auto jpeg = jpegSize(bytes, size))
        return jpeg;
    return bmpSize(bytes, size);
}

namespace {

bool withinLimits(const ImageHeaderSize& header) noexcept
{
    using vision::limits::kMaxImagePixels;
    using vision::limits::kMaxImageSide;
    const std::int64_t w = header.width;
    const std::int64_t h = header.height;
    return w >= 1 && h >= 1 && w <= kMaxImageSide && h <= kMaxImageSide && w * h <= kMaxImagePixels;
}

}  // namespace

bool imageHeaderWithinLimits(const std::uint8_t* bytes, std::size_t size) noexcept
{
    const auto header = imageHeaderSize(bytes, size);
    return header && withinLimits(*header);
}

std::string checkImageHeader(const std::uint8_t* bytes, std::size_t size)
{
    const auto header = imageHeaderSize(bytes, size);
    if (!header)
        return "not a PNG, JPEG or BMP file (no picture size in its header)";
    using vision::limits::kMaxImagePixels;
    using vision::limits::kMaxImageSide;
    const std::int64_t w = header->width;
    const std::int64_t h = header->height;
    if (!withinLimits(*header))
        return "its header says " + std::to_string(w) + "x" + std::to_string(h) +
               " (allowed: up to " + std::to_string(kMaxImageSide) + " on a side and " +
               std::to_string(kMaxImagePixels) + " pixels, 7680x4320)";
    return {};
}

}  // namespace platform
