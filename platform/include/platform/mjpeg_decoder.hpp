#pragma once
// MjpegDecoder: decodes the JPEG frames of an MJPEG camera into one preallocated RGB24 image.

#include "vision/image.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace platform {

/// \class MjpegDecoder
/// libjpeg-turbo (the libjpeg API of libjpeg62-turbo) decoding straight into an RGB24 ImageBuffer
/// sized at construction (bytes R,G,B; libjpeg-turbo's JCS_EXT_RGB, no conversion pass). UVC
/// cameras often leave out the Huffman tables; libjpeg-turbo supplies the standard ones.
///
/// decode() never throws: a corrupt frame, a frame of another size or data that is not a JPEG
/// returns false with lastError() set, and the image keeps its previous content. A truncated
/// frame (libjpeg's "premature end of data" warning) is decoded as far as it goes: cameras do send
/// those. Our code allocates nothing per frame; libjpeg itself takes its per-image working memory
/// from malloc inside jpeg_start_decompress (counted as foreign by tests/support/alloc_counter).
class MjpegDecoder {
public:
    /// Throws std::runtime_error for a size outside 16..16384.
    MjpegDecoder(int width, int height);
    ~MjpegDecoder();
    MjpegDecoder(const MjpegDecoder&) = delete;
    MjpegDecoder& operator=(const MjpegDecoder&) = delete;

    /// Decodes one JPEG of exactly width x height into image().
    bool decode(const std::uint8_t* data, std::size_t size) noexcept;

    vision::ConstImageView image() const noexcept { return image_.view(); }
    const char* lastError() const noexcept { return error_; }

private:
    struct Jpeg;
    std::unique_ptr<Jpeg> jpeg_;
    vision::ImageBuffer image_;
    char error_[256] = {};
};

}  // namespace platform
