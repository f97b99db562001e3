#pragma once
// PngWriter: encodes 8-bit RGB images to PNG files without touching the heap per image.

#include <cstddef>
#include <cstdint>
#include <memory>

namespace platform {

/// Byte layout of the pixels handed to PngWriter::write().
enum class PngInputLayout {
    Rgb,   ///< bytes R,G,B per pixel
    Rgbx,  ///< bytes R,G,B,X per pixel (e.g. GL RGBA readback); the fourth byte is dropped
};

/// Order of the rows in memory.
enum class PngRowOrder {
    TopDown,   ///< first row in memory is the top of the image
    BottomUp,  ///< first row in memory is the bottom (OpenGL's glReadPixels origin)
};

/// \class PngWriter
/// Writes RGB PNG files (8 bits per channel) with libpng and zlib, serving every allocation they
/// make from a fixed arena allocated by the constructor (a bump allocator rewound after each
/// image), so writing a snapshot in the frame loop never calls malloc. If the arena runs out the
/// image is abandoned and write() returns false: it never falls back to the heap.
///
/// A file is written under a temporary name beside the target and renamed into place when
/// complete, so a reader never sees a partial PNG. Not thread-safe: one image at a time.
class PngWriter {
public:
    /// Generous for any image size: libpng + zlib need about 0.3 MiB plus a few rows.
    static constexpr std::size_t kDefaultArenaBytes = std::size_t{4} << 20;
    /// zlib level; 1-3 are fast and still shrink rendered frames well.
    static constexpr int kDefaultCompressionLevel = 2;

    /// Allocates the arena. Throws std::runtime_error when it cannot.
    explicit PngWriter(std::size_t arenaBytes = kDefaultArenaBytes,
                       int compressionLevel = kDefaultCompressionLevel);
    ~PngWriter();
    PngWriter(const PngWriter&) = delete;
    PngWriter& operator=(const PngWriter&) = delete;

    /// Writes `pixels` (width x height, `stride` bytes from one row in memory to the next) as an
    /// RGB PNG at `path`. False on any failure (file, libpng, arena exhausted); lastError() says
    /// why and no file is left at `path` or under the temporary name.
    bool write(const char* path, const std::uint8_t* pixels, int width, int height,
               std::size_t stride, PngInputLayout layout = PngInputLayout::Rgb,
               PngRowOrder order = PngRowOrder::TopDown) noexcept;

    /// Reason for the last failed write(); "" after a success.
    const char* lastError() const noexcept { return error_; }
    std::size_t arenaBytes() const noexcept { return arenaSize_; }
    /// Most arena bytes used by one image so far (to size the arena with evidence).
    std::size_t arenaHighWater() const noexcept { return highWater_; }

private:
    struct Session;
    friend struct PngWriterCallbacks;  // libpng's C callbacks (png_writer.cpp)

    void* arenaAllocate(std::size_t bytes) noexcept;
    bool encode(Session& session) noexcept;
    void setError(const char* format, ...) noexcept __attribute__((format(printf, 2, 3)));

    std::unique_ptr<unsigned char[]> arena_;
    std::size_t arenaSize_ = 0;
    std::size_t arenaUsed_ = 0;
    std::size_t highWater_ = 0;
    bool arenaExhausted_ = false;
    int level_ = kDefaultCompressionLevel;
    char error_[512] = {};
    char tempPath_[4096] = {};
};

}  // namespace platform
