#pragma once
// The cameras this machine has, as `mirror --list-cameras` prints them (like rpicam-apps'
// --list-cameras): libcamera's cameras with their stream formats and sizes, then the V4L2 capture
// devices with theirs. For a technician and a bug report, not for the frame loop.

#include <cstdio>

namespace platform {

/// Writes the list to `out`. Returns how many cameras were found (libcamera and V4L2 together).
/// Creates a libcamera CameraManager: call it only in a process that has no other (only one may
/// exist per process), e.g. `mirror --list-cameras` before any source is opened.
int listCameras(std::FILE* out);

}  // namespace platform
