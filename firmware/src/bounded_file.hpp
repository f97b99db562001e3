#pragma once
// How the firmware reads the files it is given (the config, the state files): opened without
// blocking, a regular file only, read up to a bound. A FIFO, a device (/dev/zero) or a folder in
// a file's place is one clear problem instead of a start-up that hangs or fills the memory.

#include <cstddef>
#include <string>

namespace firmware {

struct BoundedFile {
    enum class Status { Ok, Missing, Unreadable, TooLarge } status = Status::Ok;
    std::string text;     ///< the contents when Ok
    std::string problem;  ///< when not Ok: what is wrong, one line without the path
};

/// The contents of `path` if it is a regular file of at most `maxBytes`.
BoundedFile readBoundedFile(const std::string& path, std::size_t maxBytes);

}  // namespace firmware
