#pragma once
// Camera shake for facegen: the whole view (background, its static faces and the moving heads)
// shifted by a few pixels and turned by a fraction of a degree, frame by frame, as a mirror on a
// wall that trembles (a door closing, steps on the floor) or a hand-held camera sees it. A print
// on the wall then moves in the image as much as a calm head does; what tells them apart is that
// the print moves with the background (LivenessCue, vision/src/liveness_cue.cpp).

#include "scenarios.hpp"

#include <cstdint>
#include <opencv2/core.hpp>

namespace facegen {

/// The view's motion in one frame: a turn by `rollDeg` (clockwise on screen) about the frame's
/// centre, then a shift by (dx, dy) pixels.
struct CameraShake {
    double dx = 0, dy = 0;
    double rollDeg = 0;
};

/// Degrees of turn per pixel of shift amplitude (3 px of shake: +-0.45 degrees).
inline constexpr double kShakeRollPerPixel = 0.15;

/// The shake of frame `index` with amplitude `amplitudePx` (0: none): a smooth tremble (three
/// sines per axis, 1.5-7 Hz at 30 frames per second) plus a jolt of up to a third of it per
/// frame, repeatable from `seed`.
CameraShake shakeAt(std::uint32_t seed, int index, double amplitudePx) noexcept;

/// Moves the view of `frame` (any type) by `shake`; the borders it uncovers repeat the image.
void applyShake(cv::Mat& frame, const CameraShake& shake);

/// The face as the shaken view shows it: its centre moved, its roll turned.
FaceState shaken(FaceState face, const CameraShake& shake, cv::Size frameSize) noexcept;

}  // namespace facegen
