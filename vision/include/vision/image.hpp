#pragma once
// Image types of the vision core.
//
// ImageView / ConstImageView are non-owning (pointer, width, height, stride, format): every stage
// reads and writes through them and never allocates. ImageBuffer owns pixels and is created only
// at start-up, sized from the configured resolution, then reused for every frame.

#include <cstddef>
#include <cstdint>
#include <memory>

namespace vision {

/// Pixel layouts, named by their byte order in memory (not by a 32-bit word's bit order).
enum class PixelFormat : std::uint8_t {
    Gray8,     ///< one byte per pixel
    RGB24,     ///< bytes R,G,B (libcamera calls this "BGR888")
    BGR24,     ///< bytes B,G,R (OpenCV's default; libcamera "RGB888")
    XRGB8888,  ///< bytes B,G,R,X (DRM/libcamera XRGB8888, little-endian word)
    YUYV,      ///< 4:2:2 packed, bytes Y0,U,Y1,V
    NV12,      ///< 4:2:0, Y plane then interleaved U,V plane at data + stride * height
};

/// Bytes per pixel of the first plane.
constexpr int bytesPerPixel(PixelFormat f) noexcept
{
    switch (f) {
        case PixelFormat::Gray8:
            return 1;
        case PixelFormat::RGB24:
            return 3;
        case PixelFormat::BGR24:
            return 3;
        case PixelFormat::XRGB8888:
            return 4;
        case PixelFormat::YUYV:
            return 2;
        case PixelFormat::NV12:
            return 1;
    }
    return 0;
}

/// Bytes needed for an image of this size and stride (all planes).
constexpr std::size_t imageBytes(PixelFormat f, int height, int stride) noexcept
{
    const std::size_t plane = static_cast<std::size_t>(stride) * static_cast<std::size_t>(height);
    return f == PixelFormat::NV12 ? plane + plane / 2 : plane;
}

/// Byte offsets of R, G and B within one pixel of a packed RGB-like format (RGB24, BGR24,
/// XRGB8888). bytesPerPixel is 0 for the other formats.
struct RgbLayout {
    int bytesPerPixel;
    int r, g, b;
};

constexpr RgbLayout rgbLayout(PixelFormat f) noexcept
{
    switch (f) {
        case PixelFormat::RGB24:
            return {3, 0, 1, 2};
        case PixelFormat::BGR24:
            return {3, 2, 1, 0};
        case PixelFormat::XRGB8888:
            return {4, 2, 1, 0};
        default:
            return {0, 0, 0, 0};
    }
}

const char* pixelFormatName(PixelFormat f) noexcept;

struct Size {
    int width = 0;
    int height = 0;
    friend constexpr bool operator==(Size, Size) = default;
};

/// Non-owning view of an image. T is std::uint8_t (writable) or const std::uint8_t.
template <typename T>
struct BasicImageView {
    T* data = nullptr;
    int width = 0;
    int height = 0;
    int stride = 0;  ///< bytes from one row to the next
    PixelFormat format = PixelFormat::Gray8;

    constexpr bool empty() const noexcept { return data == nullptr || width <= 0 || height <= 0; }
    constexpr Size size() const noexcept { return {width, height}; }
    constexpr T* row(int y) const noexcept
    {
        return data + static_cast<std::ptrdiff_t>(y) * stride;
    }

    /// A writable view converts to a read-only one.
    constexpr operator BasicImageView<const std::uint8_t>() const noexcept
    {
        return {data, width, height, stride, format};
    }
};

using ImageView = BasicImageView<std::uint8_t>;
using ConstImageView = BasicImageView<const std::uint8_t>;

/// Owning image storage. Allocate at start-up only; the frame loop uses view().
class ImageBuffer {
public:
    ImageBuffer() = default;
    ImageBuffer(int width, int height, PixelFormat format);

    ImageBuffer(ImageBuffer&&) noexcept = default;
    ImageBuffer& operator=(ImageBuffer&&) noexcept = default;
    ImageBuffer(const ImageBuffer&) = delete;
    ImageBuffer& operator=(const ImageBuffer&) = delete;

    ImageView view() noexcept { return {data_.get(), width_, height_, stride_, format_}; }
    ConstImageView view() const noexcept
    {
        return {data_.get(), width_, height_, stride_, format_};
    }
    bool empty() const noexcept { return !data_; }
    std::size_t bytes() const noexcept { return imageBytes(format_, height_, stride_); }

private:
    std::unique_ptr<std::uint8_t[]> data_;
    int width_ = 0;
    int height_ = 0;
    int stride_ = 0;
    PixelFormat format_ = PixelFormat::Gray8;
};

/// One captured frame as the pipeline sees it. The view is valid until the source's next call.
struct Frame {
    ConstImageView image;
    std::uint64_t sequence = 0;    ///< counts frames delivered by the source, from 0
    std::int64_t timestampNs = 0;  ///< capture time, CLOCK_MONOTONIC (sensor time where known)
};

}  // namespace vision
