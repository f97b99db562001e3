#include "platform/oriented_source.hpp"

#include <cstring>
#include <stdexcept>

namespace platform {

OrientedSource::OrientedSource(std::unique_ptr<FrameSource> inner, Orientation orientation)
    : inner_(std::move(inner)), orientation_(orientation)
{
    const vision::PixelFormat f = inner_->format();
    if (f != vision::PixelFormat::RGB24 && f != vision::PixelFormat::BGR24 &&
        f != vision::PixelFormat::XRGB8888 && f != vision::PixelFormat::Gray8)
        throw std::runtime_error(std::string("camera orientation: cannot flip ") +
                                 vision::pixelFormatName(f) + " frames");
    buffer_ = vision::ImageBuffer(inner_->size().width, inner_->size().height, f);
    description_ = std::string(inner_->description()) + " (" +
                   (orientation.rotation == 180 ? "rotation 180" : "rotation 0") +
                   (orientation.hflip ? ", hflip" : "") + (orientation.vflip ? ", vflip" : "") +
                   ")";
}

SourceStatus OrientedSource::next(vision::Frame& frame) noexcept
{
    const SourceStatus status = inner_->next(frame);
    if (status != SourceStatus::Ok)
        return status;
    const vision::ConstImageView in = frame.image;
    const vision::ImageView out = buffer_.view();
    if (in.size() != out.size() || in.format != out.format)
        return status;  // cannot happen: a source's size and format are fixed
    const int bpp = vision::bytesPerPixel(in.format);
    const auto rowBytes = static_cast<std::size_t>(in.width) * static_cast<std::size_t>(bpp);
    const bool flipX = orientation_.flipsX();
    const bool flipY = orientation_.flipsY();
    for (int y = 0; y < in.height; ++y) {
        const std::uint8_t* src = in.row(flipY ? in.height - 1 - y : y);
        std::uint8_t* dst = out.row(y);
        if (!flipX) {
            std::memcpy(dst, src, rowBytes);
            continue;
        }
        const std::uint8_t* last = src + rowBytes - static_cast<std::size_t>(bpp);
        for (int x = 0; x < in.width; ++x, dst += bpp, last -= bpp)
            std::memcpy(dst, last, static_cast<std::size_t>(bpp));
    }
    frame.image = buffer_.view();
    return status;
}

}  // namespace platform
