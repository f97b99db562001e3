#pragma once
// loadImageFile: reads a picture file (PNG, JPEG or BMP) at start-up.

#include "vision/image.hpp"

#include <string>

namespace platform {

/// Decodes the image file at `path` into RGB24 (bytes R,G,B; rows padded as ImageBuffer pads
/// them). Grey and alpha images become RGB (alpha dropped), 16-bit images 8-bit, and the EXIF
/// orientation of a JPEG is applied. For start-up only: it allocates. The file is read bounded
/// (vision::readBoundedFile) and its header's picture size checked against vision/input_limits.hpp
/// before anything is decoded.
///
/// Throws std::runtime_error with one line naming `what` and the path, e.g.
///   "card picture /x/y.png: no such file"
///   "card picture /x/y.png: its header says 8000x8000 (allowed: up to 7680 on a side ...)"
///   "card picture /x/y.png: not an image OpenCV can read"
vision::ImageBuffer loadImageFile(const std::string& path, const char* what = "image");

}  // namespace platform
