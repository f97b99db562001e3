#pragma once
// The size a PNG, JPEG or BMP file says its picture has, read from its header alone: so a small
// file claiming a picture of gigabytes is refused before a decoder allocates for it. Private to
// platform's image readers (file replay, pictures).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace platform {

struct ImageHeaderSize {
    std::int64_t width = 0;
    std::int64_t height = 0;
};

/// The picture size in the header of `bytes`, or nothing when they are not a PNG, JPEG or BMP
/// header (or are cut short before the size).
std::optional<ImageHeaderSize> imageHeaderSize(const std::uint8_t* bytes, std::size_t size);

/// Whether the header of `bytes` gives a size within vision::limits::kMaxImageSide and
/// kMaxImagePixels. Allocation-free, for the frame loop.
bool imageHeaderWithinLimits(const std::uint8_t* bytes, std::size_t size) noexcept;

/// "" when the header of `bytes` gives a size within vision::limits::kMaxImageSide and
/// kMaxImagePixels, else what is wrong (one line, without the file name).
std::string checkImageHeader(const std::uint8_t* bytes, std::size_t size);

}  // namespace platform
