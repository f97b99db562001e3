#pragma once
// Initial roll of a detected face from the bilateral symmetry of its corner points (METHOD.md §4,
// dissertation 5.2.2): rotate the points about the box centre by each candidate angle, reflect
// them across the vertical axis through the centre, and score how far each reflected point lands
// from its nearest original point. The most symmetric angle is the roll. Plus the least-squares
// line-fit baseline the dissertation compares with (§4; 5.2.3). Points only: the corners come from
// whichever detector the caller runs. No allocation, no exceptions.

#include "vision/geometry.hpp"

#include <span>

namespace vision {

/// Roll of a face in degrees. Positive roll turns the face's upright axes from +x towards +y, i.e.
/// clockwise on screen (y down), the same sense as the tracker's th = atan2(a2, a1) (METHOD §3):
/// an upright point set rotated about the centre by `rollDegrees` gives the observed points.
struct RollEstimate {
    float rollDegrees = 0.f;
    /// 0 (no information: too few points, or every angle scores alike) .. 1 (one clear minimum).
    float confidence = 0.f;
    /// The best symmetry score as a fraction of the box size (0 = perfectly symmetric).
    float symmetryDistance = 0.f;
    /// Points actually used (at most kMaxRollPoints).
    int points = 0;
};

/// Points beyond this are ignored (the caller samples ~20-60 corners per face).
inline constexpr int kMaxRollPoints = 128;

/// Knobs of estimateRollBySymmetry; the defaults are the ones measured on the IMM faces
/// (tests/peer/roll_landmarks_peer_test.cpp; why each, in roll_estimator.cpp).
struct RollEstimatorOptions {
    float minDegrees = -30.f;              ///< whole-step search of the angles from here ...
    float maxDegrees = 30.f;               ///< ... to here
    float stepDegrees = 1.f;               ///< in these steps
    float refineToleranceDegrees = 0.02f;  ///< then golden section to this (0: whole steps)
    float trimFraction = 0.1f;             ///< largest nearest-point distances dropped
    float capFraction = 0.06f;             ///< each distance capped at this x the box size
    float maxAxisOffsetFraction = 0.06f;   ///< the axis may sit this x the box size off centre
    int axisOffsetSteps = 3;               ///< searched in this many steps each side
};

/// Symmetry score of `points` about the axis through `centre + offset * (cos a, sin a)` at angle
/// `rollDegrees` from vertical: the (trimmed, capped) mean distance from each reflected point to
/// its nearest original point, in pixels. `offset` is across the axis, in pixels; `cap` <= 0 is
/// no cap.
float symmetryDistance(std::span<const Point2f> points, Point2f centre, float rollDegrees,
                       float offset, float trimFraction, float cap) noexcept;

/// Roll of the face whose corners are `points`, detected in a box centred at `centre` with side
/// `boxSize` (pixels; scales the trimming cap and axis offsets). Fewer than 3 points, or a
/// non-positive box size, give confidence 0 and roll 0.
RollEstimate estimateRollBySymmetry(std::span<const Point2f> points, Point2f centre, float boxSize,
                                    const RollEstimatorOptions& options = {}) noexcept;

/// The dissertation's baseline (§4; 5.2.3): the least-squares (orthogonal) line through the points,
/// its slope offset by a multiple of 90 degrees into [-45, 45). Confidence is the elongation of
/// the point cloud, (l1 - l2) / (l1 + l2) of its scatter matrix; fewer than 2 points give 0.
RollEstimate estimateRollByLineFit(std::span<const Point2f> points) noexcept;

}  // namespace vision
