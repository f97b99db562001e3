#pragma once
// What the AAM fit precomputes from the model once, at start-up (§5, dissertation 5.3.2 and
// 5.3.4). Private to vision/src.
//
// The frame's pixels are stored as row spans: each row of the mean shape's frame from its first to
// its last model pixel, rows one after another (5.3.4: loop bounds at the first and last pixel of
// each row, no mask tests). Pixels of a span that are not in the model (the mouth opening) carry
// zero in every steepest-descent image and a zero mask, so they add nothing to any sum.

#include "vision/aam_fitter.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace vision::aam {

/// Pixels of one row of the frame that lie in one triangle (or a model gap after it): the warp
/// steps along a run with one affine transform.
struct WarpRun {
    std::uint16_t y = 0, x0 = 0, count = 0, triangle = 0;
    std::uint32_t offset = 0;  ///< index of (x0, y) in the span arrays
};

/// A triangle of the mean shape s0: its first vertex and the inverse of its edge matrix
/// [v1 - v0, v2 - v0], so any shape's affine map from it is two products (closed form, 5.3.4).
struct FrameTriangle {
    std::array<int, 3> v{};
    Eigen::Vector2f origin;
    Eigen::Matrix2f inverseEdges;
};

/// An integer image's scale: value = integer / scale.
struct Quantised {
    std::vector<std::int16_t> values;
    float scale = 1.f;
};

struct Tables {
    int vertices = 0, triangles = 0, shapeModeCount = 0, appearanceModeCount = 0;
    int spanPixels = 0;  ///< pixels in all row spans (model pixels and the gaps between them)
    int modelPixels = 0;

    // Shapes, (x0 y0 x1 y1 ...) in frame pixels.
    Eigen::VectorXf meanShape;        ///< s0
    Eigen::Vector2f centre;           ///< s0's centroid: N scales and turns about it
    float similarityNorm = 1.f;       ///< |s0 - centre|: N's q1, q2 in these units
    Eigen::MatrixXf similarity;       ///< 2V x 4, orthonormal s*_1..4 (eq. 76)
    Eigen::MatrixXf shapeModes;       ///< 2V x m, orthonormal, orthogonal to `similarity`
    std::vector<float> shapeLimits;   ///< 3 standard deviations of each mode
    Eigen::Vector2f boxLow, boxSize;  ///< s0's bounding box (AamStart's width is its width)

    std::vector<FrameTriangle> frameTriangles;
    std::vector<int> vertexTriangleStart;  ///< vertex v's triangles: [start[v], start[v + 1])
    std::vector<int> vertexTriangles;      ///< 5.3.4: the vertex -> triangles table
    std::vector<WarpRun> runs;

    // Per span pixel.
    std::vector<std::int16_t> mask;            ///< -1 (all bits) on model pixels, 0 in gaps
    std::vector<std::int16_t> meanAppearance;  ///< A0 * kAppearanceOne
    /// The 2D steepest-descent images (alpha, beta, q1..4, p1..m), projected out of the span of
    /// the appearance modes (eq. 74), each quantised to +-kSteepestMax.
    std::vector<Quantised> steepest;
    std::vector<Quantised> appearanceModes;  ///< A_i quantised (the fit error's projection)
    /// Each kept mode's standard deviation over the training faces (the model's variances
    /// projected on it): the unit of a signature's appearance parameters (§6).
    std::vector<float> appearanceModeStd;
    Eigen::MatrixXd hessian2d;  ///< of `steepest` as quantised

    // The CANDIDE head.
    std::vector<Eigen::Vector3f> headVertices;  ///< g0
    /// Per vertex, the 3D displacement of every unit: [sigma 0..9, tau 0..5], 3 x 16 each.
    std::vector<Eigen::Matrix<float, 3, kAamShapeUnits + kAamAnimationUnits>> headUnits;
};

inline constexpr int kAppearanceOne = 256;  ///< A0 in q8: the mean appearance's std is 256
inline constexpr int kSteepestMax = 2047;   ///< a steepest-descent image's largest |value|
inline constexpr int kErrorOne = 16;        ///< the error image in 1/16 grey levels

/// Every table from the model; throws std::invalid_argument (one line) for a model the fitter
/// cannot take (sizes beyond aam_fitter.hpp's bounds, units missing).
Tables buildTables(const AamModel& model);

/// Similarity basis at a frame point (x, y): the 2 x 4 block of s*_1..4 there.
Eigen::Matrix<float, 2, 4> similarityAt(const Tables& t, float x, float y);

}  // namespace vision::aam
