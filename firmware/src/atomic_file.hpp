#pragma once
// writeFileAtomically: replaces a small state file so that a crash or power cut leaves either
// the old file or the new one, never half of one: write a temp file beside it, fsync, rename over
// the target, fsync the folder (the rename is durable only once the folder's entry is on disk).
// Used from the frame loop (a button press saves the overlay), so it never allocates.

#include <sys/types.h>

#include <cstddef>

namespace firmware {

/// Writes `size` bytes of `data` to `path` through `tempPath` (same folder) and syncs `dir`.
/// False on failure, with "PATH: strerror" in `error` (the temp file is removed). The file gets
/// `mode` (a person's file is only the service's: 0600).
bool writeFileAtomically(const char* dir, const char* path, const char* tempPath, const char* data,
                         std::size_t size, char* error, std::size_t errorCapacity,
                         mode_t mode = 0644) noexcept;

}  // namespace firmware
