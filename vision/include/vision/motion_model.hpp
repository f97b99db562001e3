#pragma once
// Motion model of a tracked face (METHOD.md §3, "Tracking"): a least-squares fit of old -> new
// point pairs about the face centre (xc, yc), as
//   x' = a11 (x - xc) + a12 (y - yc) + xc + b1
//   y' = a21 (x - xc) + a22 (y - yc) + yc + b2
// Translation: a = identity. Similarity: a11 = a22 = a1, a21 = -a12 = a2, so scale =
// hypot(a1, a2) and roll = atan2(a2, a1). Affine: all six free (may overfit on few points).
// Outliers are rejected by RANSAC over minimal samples drawn by a deterministic sampler (every
// sample when there are few points, a fixed-seed sequence otherwise, so a frame always gives the
// same answer), then least squares on the inliers, recounted and refitted. Eigen fixed-size
// matrices only: nothing allocates.

#include "vision/geometry.hpp"

#include <cstdint>

namespace vision {

enum class MotionKind : std::uint8_t { Translation, Similarity, Affine };

struct MotionModel {
    MotionKind kind = MotionKind::Translation;
    Point2f centre{};
    float a11 = 1.f, a12 = 0.f, a21 = 0.f, a22 = 1.f;
    float b1 = 0.f, b2 = 0.f;

    Point2f apply(Point2f p) const noexcept
    {
        const float dx = p.x - centre.x;
        const float dy = p.y - centre.y;
        return {a11 * dx + a12 * dy + centre.x + b1, a21 * dx + a22 * dy + centre.y + b2};
    }
    /// Scale of the similarity part: hypot(a1, a2) with a1, a2 the rotation-scale pair (for an
    /// affine model, of its closest similarity).
    float scale() const noexcept;
    /// Roll in radians, atan2(a2, a1) (positive turns +x towards +y, clockwise on screen).
    float roll() const noexcept;
};

struct MotionFitOptions {
    MotionKind kind = MotionKind::Similarity;
    float inlierDistance = 1.5f;  ///< residual (pixels) under which a pair is an inlier
    int maxIterations = 64;       ///< RANSAC hypotheses at most
};

/// Least squares over the pairs whose `use` entry is non-zero (all when null). False when there
/// are too few pairs (1 translation, 2 similarity, 3 affine) or they are degenerate.
bool fitMotionLeastSquares(const Point2f* from, const Point2f* to, int n, const std::uint8_t* use,
                           Point2f centre, MotionKind kind, MotionModel& model) noexcept;

/// Most pairs fitMotionRobust takes (its inlier marks live on the stack).
constexpr int kMaxMotionPairs = 256;

/// Robust fit: RANSAC then least-squares refits on the inliers. `inliers` (optional, n entries)
/// receives 1 for inliers. Returns the inlier count, 0 when no model was found (also when n
/// exceeds kMaxMotionPairs).
int fitMotionRobust(const Point2f* from, const Point2f* to, int n, Point2f centre,
                    const MotionFitOptions& options, MotionModel& model,
                    std::uint8_t* inliers = nullptr) noexcept;

}  // namespace vision
