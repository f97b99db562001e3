#pragma once
// Fast deinterlacer of 4.2.4 (METHOD.md §2). An interlaced camera exposes odd lines later than
// even ones, so moving edges "tear" into combs. For every even line i and every byte j of the row:
//
//   if |p(i+2, j) - p(i, j)| < |p(i+1, j) - p(i, j)|  then  p(i+1, j) = (p(i, j) + p(i+2, j)) / 2
//
// (integer division, i.e. rounded down). Each byte (colour channel, or Y/U/V sample) is decided
// on its own. Where the odd line agrees with its even neighbours at least as well as they agree
// with each other (static detail) the condition is false and the odd line is left bit-exact;
// where it stands out (motion between the fields) it is replaced by the interpolation. Even lines
// never change; the last odd line of an even-height image has no line below and is kept.
//
// Formats: Gray8, RGB24, BGR24, XRGB8888, YUYV (bytes of packed rows) and NV12 (the Y plane; the
// half-height chroma plane is copied unchanged).

#include "vision/image.hpp"

namespace vision {

/// In place: only odd rows are written. Returns false on an unsupported (empty) image.
bool deinterlace(const ImageView& image) noexcept;

/// From input to output (same size and format; strides may differ). Returns false and writes
/// nothing on a mismatch.
bool deinterlace(const ConstImageView& input, const ImageView& output) noexcept;

}  // namespace vision
