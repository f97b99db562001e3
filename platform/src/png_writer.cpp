#include "platform/png_writer.hpp"

#include <fcntl.h>
#include <png.h>
#include <unistd.h>

#include <cerrno>
#include <csetjmp>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

namespace platform {

// Everything one image needs, kept outside the setjmp frame so nothing is lost on longjmp.
struct PngWriter::Session {
    PngWriter* writer = nullptr;
    int fd = -1;
    const std::uint8_t* pixels = nullptr;
    int width = 0;
    int height = 0;
    std::size_t stride = 0;
    PngInputLayout layout = PngInputLayout::Rgb;
    PngRowOrder order = PngRowOrder::TopDown;
    png_structp png = nullptr;
    png_infop info = nullptr;
    std::size_t arenaNeeded = 0;
};

namespace {

constexpr std::size_t kArenaAlignment = alignof(std::max_align_t);

void arenaFree(png_structp, png_voidp) noexcept
{
    // Bump allocator: memory comes back all at once when the image is done.
}

void onWarning(png_structp, png_const_charp) noexcept
{
    // Warnings (e.g. about ancillary chunks) do not fail an image, and platform code does not log.
}

}  // namespace

PngWriter::PngWriter(std::size_t arenaBytes, int compressionLevel)
    : arenaSize_(arenaBytes), level_(compressionLevel)
{
    if (compressionLevel < 0 || compressionLevel > 9)
        throw std::runtime_error("png writer: compression level " +
                                 std::to_string(compressionLevel) + " is not in 0..9");
    // Zeroed so the pages are mapped now, not during the first snapshot.
    arena_ = std::make_unique<unsigned char[]>(arenaBytes > 0 ? arenaBytes : 1);
}

PngWriter::~PngWriter() = default;

void PngWriter::setError(const char* format, ...) noexcept
{
    va_list args;
    va_start(args, format);
    std::vsnprintf(error_, sizeof error_, format, args);
    va_end(args);
}

void* PngWriter::arenaAllocate(std::size_t bytes) noexcept
{
    const std::size_t start = (arenaUsed_ + kArenaAlignment - 1) & ~(kArenaAlignment - 1);
    if (bytes > arenaSize_ || start > arenaSize_ - bytes) {
        arenaExhausted_ = true;
        return nullptr;  // libpng turns this into an error; never fall back to malloc
    }
    arenaUsed_ = start + bytes;
    if (arenaUsed_ > highWater_)
        highWater_ = arenaUsed_;
    return arena_.get() + start;
}

// libpng's C callbacks need access to the private arena; they forward through these hooks.
struct PngWriterCallbacks {
    static png_voidp alloc(png_structp png, png_alloc_size_t bytes) noexcept
    {
        return static_cast<PngWriter*>(png_get_mem_ptr(png))->arenaAllocate(bytes);
    }

    static void error(png_structp png, png_const_charp message) noexcept
    {
        auto* session = static_cast<PngWriter::Session*>(png_get_error_ptr(png));
        PngWriter* w = session->writer;
        // The first reason wins: a failed write() or an exhausted arena explains libpng's error.
        if (w->error_[0] == '\0') {
            if (w->arenaExhausted_)
                w->setError("PNG arena of %zu bytes exhausted (libpng: %s)", w->arenaSize_,
                            message);
            else
                w->setError("libpng: %s", message);
        }
        png_longjmp(png, 1);
    }

    static void writeData(png_structp png, png_bytep data, size_t length) noexcept
    {
        auto* session = static_cast<PngWriter::Session*>(png_get_io_ptr(png));
        std::size_t done = 0;
        while (done < length) {
            const ssize_t n = ::write(session->fd, data + done, length - done);
            if (n < 0 && errno == EINTR)
                continue;
            if (n <= 0) {
                const char* why = n < 0 ? std::strerror(errno) : "nothing written";
                session->writer->setError("cannot write %s: %s", session->writer->tempPath_, why);
                png_error(png, "write failed");
            }
            done += static_cast<std::size_t>(n);
        }
    }

    static void flush(png_structp) noexcept {}
};

bool PngWriter::encode(Session& s) noexcept
{
    s.png = png_create_write_struct_2(PNG_LIBPNG_VER_STRING, &s, PngWriterCallbacks::error,
                                      onWarning, this, PngWriterCallbacks::alloc, arenaFree);
    if (s.png == nullptr) {
        if (arenaExhausted_)
            setError("PNG arena of %zu bytes exhausted (libpng write struct)", arenaSize_);
        else
            setError("libpng: cannot create a write struct (version mismatch?)");
        return false;
    }
    // Every libpng error below lands here via PngWriterCallbacks::error. Only `s` (which lives in
    // the caller's frame) is used after the jump, so no local is clobbered.
    if (setjmp(png_jmpbuf(s.png))) {
        png_destroy_write_struct(&s.png, &s.info);
        return false;
    }
    s.info = png_create_info_struct(s.png);
    if (s.info == nullptr)
        png_error(s.png, "cannot create an info struct");

    png_set_write_fn(s.png, &s, PngWriterCallbacks::writeData, PngWriterCallbacks::flush);
    png_set_compression_level(s.png, level_);
    // SUB and UP are cheap and suit camera images and flat overlays; the full adaptive search
    // (Paeth, average) costs more time than the few percent of size it saves.
    png_set_filter(s.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB | PNG_FILTER_UP);
    png_set_IHDR(s.png, s.info, static_cast<png_uint_32>(s.width),
                 static_cast<png_uint_32>(s.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(s.png, s.info);
    // Write transformations are set after png_write_info (libpng manual): drop the 4th byte.
    if (s.layout == PngInputLayout::Rgbx)
        png_set_filler(s.png, 0, PNG_FILLER_AFTER);

    for (int y = 0; y < s.height; ++y) {
        const int memoryRow = s.order == PngRowOrder::BottomUp ? s.height - 1 - y : y;
        png_write_row(s.png, s.pixels + static_cast<std::size_t>(memoryRow) * s.stride);
    }
    png_write_end(s.png, nullptr);
    png_destroy_write_struct(&s.png, &s.info);
    return true;
}

bool PngWriter::write(const char* path, const std::uint8_t* pixels, int width, int height,
                      std::size_t stride, PngInputLayout layout, PngRowOrder order) noexcept
{
    error_[0] = '\0';
    const std::size_t pixelBytes = layout == PngInputLayout::Rgbx ? 4 : 3;
    if (path == nullptr || path[0] == '\0') {
        setError("png writer: empty path");
        return false;
    }
    if (pixels == nullptr || width <= 0 || height <= 0 ||
        stride < static_cast<std::size_t>(width) * pixelBytes) {
        setError("png writer: invalid image for %s (%dx%d, stride %zu)", path, width, height,
                 stride);
        return false;
    }
    const int n = std::snprintf(tempPath_, sizeof tempPath_, "%s.tmp", path);
    if (n < 0 || static_cast<std::size_t>(n) >= sizeof tempPath_) {
        setError("png writer: path too long: %s", path);
        return false;
    }
    const int fd = ::open(tempPath_, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
        setError("cannot create %s: %s", tempPath_, std::strerror(errno));
        return false;
    }

    Session session;
    session.writer = this;
    session.fd = fd;
    session.pixels = pixels;
    session.width = width;
    session.height = height;
    session.stride = stride;
    session.layout = layout;
    session.order = order;
    arenaUsed_ = 0;
    arenaExhausted_ = false;
    bool ok = encode(session);
    arenaUsed_ = 0;

    if (::close(fd) != 0 && ok) {
        setError("cannot write %s: %s", tempPath_, std::strerror(errno));
        ok = false;
    }
    if (ok && ::rename(tempPath_, path) != 0) {
        setError("cannot rename %s to %s: %s", tempPath_, path, std::strerror(errno));
        ok = false;
    }
    if (!ok)
        ::unlink(tempPath_);
    return ok;
}

}  // namespace platform
