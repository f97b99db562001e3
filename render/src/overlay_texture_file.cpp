#include "overlay_texture_file.hpp"

#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <png.h>

#include <cstring>
#include <stdexcept>

namespace render {

namespace {

/// Frees libpng's state on every way out, the errors included.
struct PngImage {
    png_image image;
    PngImage()
    {
        std::memset(&image, 0, sizeof(image));
        image.version = PNG_IMAGE_VERSION;
    }
    ~PngImage() { png_image_free(&image); }
    PngImage(const PngImage&) = delete;
    PngImage& operator=(const PngImage&) = delete;
};

}  // namespace

OverlayTexture readTextureFile(const std::string& path)
{
    const auto fail = [&](const std::string& why) {
        throw std::runtime_error("texture " + path + ": " + why);
    };
    const vision::BoundedFile file = vision::readBoundedFile(path, vision::limits::kTextureBytes);
    if (file.status != vision::BoundedFile::Status::Ok)
        fail(file.problem);
    PngImage png;
    if (!png_image_begin_read_from_memory(&png.image, file.text.data(), file.text.size()))
        fail(png.image.message);
    // From the header, before a byte is allocated for the pixels: a small file can claim a
    // picture of gigabytes.
    constexpr auto kSide = static_cast<png_uint_32>(vision::limits::kMaxTextureSide);
    if (png.image.width > kSide || png.image.height > kSide)
        fail(std::to_string(png.image.width) + "x" + std::to_string(png.image.height) +
             " is larger than " + std::to_string(kSide) + "x" + std::to_string(kSide));
    png.image.format = PNG_FORMAT_RGBA;
    OverlayTexture texture;
    texture.width = static_cast<int>(png.image.width);
    texture.height = static_cast<int>(png.image.height);
    texture.rgba.resize(PNG_IMAGE_SIZE(png.image));
    // A negative row stride stores the picture bottom-up, as GL and OBJ texture coordinates want.
    const auto stride = -static_cast<png_int_32>(PNG_IMAGE_ROW_STRIDE(png.image));
    if (!png_image_finish_read(&png.image, nullptr, texture.rgba.data(), stride, nullptr))
        fail(png.image.message);
    return texture;
}

}  // namespace render
