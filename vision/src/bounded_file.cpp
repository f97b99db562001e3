#include "vision/bounded_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace vision {

BoundedFile readBoundedFile(const std::string& path, std::size_t maxBytes)
{
    BoundedFile result;
    const auto fail = [&](int error) {
        result.status =
            error == ENOENT ? BoundedFile::Status::Missing : BoundedFile::Status::Unreadable;
        result.problem = std::string("cannot read file: ") + std::strerror(error);
        result.text.clear();
        return result;
    };
    const auto tooLarge = [&](std::size_t bytes, bool atLeast) {
        result.status = BoundedFile::Status::TooLarge;
        result.problem = "file is too large: " + std::string(atLeast ? "over " : "") +
                         std::to_string(bytes) + " bytes (allowed: up to " +
                         std::to_string(maxBytes) + " bytes)";
        result.text.clear();
        return result;
    };

    // O_NONBLOCK: opening a FIFO with no writer would otherwise wait for one for ever.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return fail(errno);
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};

    struct stat info {};
    if (::fstat(fd, &info) != 0)
        return fail(errno);
    if (S_ISDIR(info.st_mode))
        return fail(EISDIR);
    if (!S_ISREG(info.st_mode)) {
        result.status = BoundedFile::Status::Unreadable;
        result.problem = "not a regular file (a FIFO, a device or a socket)";
        return result;
    }
    if (static_cast<std::size_t>(info.st_size) > maxBytes)
        return tooLarge(static_cast<std::size_t>(info.st_size), false);
    // Still bounded while reading: the file may grow between fstat and read.
    char buffer[16384];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0) {
            if (errno == EINTR || errno == EAGAIN)
                continue;
            return fail(errno);
        }
        if (n == 0)
            break;
        result.text.append(buffer, static_cast<std::size_t>(n));
        if (result.text.size() > maxBytes)
            return tooLarge(maxBytes, true);
    }
    return result;
}

}  // namespace vision
