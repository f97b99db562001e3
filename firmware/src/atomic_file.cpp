#include "atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace firmware {

namespace {

bool writeAll(int fd, const char* data, std::size_t size) noexcept
{
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return false;
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

}  // namespace

bool writeFileAtomically(const char* dir, const char* path, const char* tempPath, const char* data,
                         std::size_t size, char* error, std::size_t errorCapacity,
                         mode_t mode) noexcept
{
    const int fd = ::open(tempPath, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, mode);
    if (fd < 0) {
        std::snprintf(error, errorCapacity, "%s: %s", tempPath, std::strerror(errno));
        return false;
    }
    // The umask cannot widen it, but a temp file left by an older run may have kept its mode.
    const bool written = ::fchmod(fd, mode) == 0 && writeAll(fd, data, size) && ::fsync(fd) == 0;
    const int writeErrno = errno;
    ::close(fd);
    if (!written || ::rename(tempPath, path) != 0) {
        std::snprintf(error, errorCapacity, "%s: %s", path,
                      std::strerror(written ? errno : writeErrno));
        ::unlink(tempPath);
        return false;
    }
    const int dirFd = ::open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dirFd >= 0) {
        ::fsync(dirFd);
        ::close(dirFd);
    }
    if (errorCapacity > 0)
        error[0] = '\0';
    return true;
}

}  // namespace firmware
