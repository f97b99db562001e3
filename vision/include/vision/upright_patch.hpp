#pragma once
// Roll-warped verification patches (METHOD.md §3, "Integration"; dissertation fig. 89): a track
// that the detector did not find this frame is verified by warping its face upright by the
// tracked roll into a small patch and running first-hit detection on it.

#include "vision/geometry.hpp"
#include "vision/image.hpp"

namespace vision {

/// Samples the square of side `sourceSide` (pixels of `gray`) centred on `centre`, rotated by
/// `rollDegrees`, into the whole of `patch` (Gray8, any size, need not be square), so that a face
/// with that roll comes out upright. Roll has the sense of TrackedFace::rollDegrees and
/// RollEstimate: positive turns the face clockwise on screen (y down), and patch offset (u, v)
/// from the patch centre reads the image at centre + R(roll) (u, v) * sourceSide / patch size.
/// Coordinates are continuous (pixel i covers [i, i + 1), as a box's centre x + width / 2), so
/// with roll 0 and sourceSide equal to the patch size around a whole-pixel centre it is an exact
/// copy. Bilinear in fixed point (positions Q16, weights 8 bits), pixels outside the image repeat
/// its border. Returns false (patch untouched) on a format mismatch, a non-positive or
/// non-finite side, or a square reaching beyond 16384 pixels from the image.
bool warpUpright(const ConstImageView& gray, Point2f centre, float rollDegrees, float sourceSide,
                 ImageView patch) noexcept;

/// The general form (rotated detection scans): patch pixels are `unitX` x `unitY` source pixels
/// along the rotated axes, so patch offset (u, v) from the patch centre reads the image at
/// centre + R(roll) (u * unitX, v * unitY). warpUpright is unitX = sourceSide / patch.width,
/// unitY = sourceSide / patch.height. Same sampling, border and failure rules (non-positive or
/// non-finite units). The units are double so that warpUpright's sourceSide / patch side is
/// not rounded to float on the way.
bool warpRotated(const ConstImageView& gray, Point2f centre, float rollDegrees, double unitX,
                 double unitY, ImageView patch) noexcept;

/// The box a w x h image turned by `degrees` fits in, plus a margin of 16 pixels: the canvas a
/// whole-image scan turned by that angle (warpRotated at unit scale) needs.
Size rotatedCanvas(Size s, float degrees) noexcept;

}  // namespace vision
