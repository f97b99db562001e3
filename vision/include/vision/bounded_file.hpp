#pragma once
// How the mirror reads a file it is given (the config, the state files, the face cascade, ...):
// opened without blocking, a regular file only, read up to a bound. A FIFO, a device (/dev/zero)
// or a folder in a file's place is one clear problem instead of a start-up that hangs or fills the
// memory. Start-up and tools only: it allocates. Every module reads files this one way, so it is
// the one part of vision beside its image, geometry and pose types that the others use.

#include <cstddef>
#include <string>

namespace vision {

struct BoundedFile {
    enum class Status { Ok, Missing, Unreadable, TooLarge } status = Status::Ok;
    std::string text;     ///< the contents when Ok
    std::string problem;  ///< when not Ok: what is wrong, one line without the path
};

/// The contents of `path` if it is a regular file of at most `maxBytes`.
BoundedFile readBoundedFile(const std::string& path, std::size_t maxBytes);

}  // namespace vision
