#include "platform/mjpeg_decoder.hpp"

#include <csetjmp>
#include <cstdio>
// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>

#include <stdexcept>
#include <string>

namespace platform {

namespace {

struct ErrorManager {
    jpeg_error_mgr base;  // first member: libjpeg hands us a pointer to it
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void onError(j_common_ptr cinfo)
{
    auto* errors = reinterpret_cast<ErrorManager*>(cinfo->err);
    (*cinfo->err->format_message)(cinfo, errors->message);
    std::longjmp(errors->jump, 1);
}

// Warnings (a truncated frame, extraneous bytes) are normal for cameras; the default handler
// would print them to stderr.
void onMessage(j_common_ptr, int) {}

}  // namespace

struct MjpegDecoder::Jpeg {
    jpeg_decompress_struct cinfo{};
    ErrorManager errors{};
};

MjpegDecoder::MjpegDecoder(int width, int height)
{
    if (width < 16 || height < 16 || width > 16384 || height > 16384)
        throw std::runtime_error("MJPEG decoder: invalid size " + std::to_string(width) + "x" +
                                 std::to_string(height));
    image_ = vision::ImageBuffer(width, height, vision::PixelFormat::RGB24);
    jpeg_ = std::make_unique<Jpeg>();
    jpeg_->cinfo.err = jpeg_std_error(&jpeg_->errors.base);
    jpeg_->errors.base.error_exit = onError;
    jpeg_->errors.base.emit_message = onMessage;
    if (setjmp(jpeg_->errors.jump)) {
        const std::string message = jpeg_->errors.message;
        throw std::runtime_error("MJPEG decoder: " + message);
    }
    jpeg_create_decompress(&jpeg_->cinfo);
}

MjpegDecoder::~MjpegDecoder()
{
    jpeg_destroy_decompress(&jpeg_->cinfo);
}

bool MjpegDecoder::decode(const std::uint8_t* data, std::size_t size) noexcept
{
    jpeg_decompress_struct& cinfo = jpeg_->cinfo;
    const vision::ImageView out = image_.view();
    if (data == nullptr || size < 4 || data[0] != 0xff || data[1] != 0xd8) {
        std::snprintf(error_, sizeof error_, "not a JPEG frame (%zu bytes)", size);
        return false;
    }
    // Nothing with a destructor lives in this function: longjmp skips destructors.
    if (setjmp(jpeg_->errors.jump)) {
        jpeg_abort_decompress(&cinfo);
        std::snprintf(error_, sizeof error_, "corrupt JPEG frame: %s", jpeg_->errors.message);
        return false;
    }
    // The source manager is allocated in the permanent pool on the first call and reused.
    jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
    jpeg_read_header(&cinfo, TRUE);
    if (static_cast<int>(cinfo.image_width) != out.width ||
        static_cast<int>(cinfo.image_height) != out.height) {
        std::snprintf(error_, sizeof error_, "JPEG frame is %ux%u, expected %dx%d",
                      cinfo.image_width, cinfo.image_height, out.width, out.height);
        jpeg_abort_decompress(&cinfo);
        return false;
    }
    cinfo.out_color_space = JCS_EXT_RGB;
    jpeg_start_decompress(&cinfo);
    while (cinfo.output_scanline < cinfo.output_height) {
        JSAMPROW row = out.row(static_cast<int>(cinfo.output_scanline));
        jpeg_read_scanlines(&cinfo, &row, 1);
    }
    jpeg_finish_decompress(&cinfo);
    error_[0] = '\0';
    return true;
}

}  // namespace platform
