#include "vision/image.hpp"

#include <stdexcept>

namespace vision {

const char* pixelFormatName(PixelFormat f) noexcept
{
    switch (f) {
        case PixelFormat::Gray8:
            return "GRAY8";
        case PixelFormat::RGB24:
            return "RGB24";
        case PixelFormat::BGR24:
            return "BGR24";
        case PixelFormat::XRGB8888:
            return "XRGB8888";
        case PixelFormat::YUYV:
            return "YUYV";
        case PixelFormat::NV12:
            return "NV12";
    }
    return "?";
}

ImageBuffer::ImageBuffer(int width, int height, PixelFormat format)
    : width_(width), height_(height), format_(format)
{
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        throw std::invalid_argument("image size out of range");
    if ((format == PixelFormat::YUYV || format == PixelFormat::NV12) && (width % 2 || height % 2))
        throw std::invalid_argument("YUV images need even width and height");
    // Rows padded to 16 bytes so SIMD loops may load whole vectors at a row's start.
    stride_ = (width * bytesPerPixel(format) + 15) & ~15;
    data_ = std::make_unique<std::uint8_t[]>(imageBytes(format, height, stride_));
}

}  // namespace vision
