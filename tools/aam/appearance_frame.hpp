#pragma once
// The frame the appearance model lives in (§5, dissertation 5.3.1: "warp each input image to the
// mean 2D shape"): the mean shape s0 scaled so its width fills the frame's width less a pixel each
// side, and the pixel->triangle table: every frame pixel inside a triangle of s0, with the
// triangle and the pixel's barycentric coordinates in it. A pixel's place in an image of shape s is
// then the same barycentric combination of the triangle's vertices in s: the piecewise affine warp.
//
// The width is the model's resolution (the text's 256; ours a build option, see
// docs/aam-model-format.md for the choice). Pixels are sampled at their integer coordinates.

#include "shape_synthesis.hpp"
#include "vision/candide_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace aam {

struct FramePixel {
    int x = 0, y = 0;
    int triangle = 0;             ///< index into the mesh's triangles
    Eigen::Vector3d barycentric;  ///< of (x, y) in that triangle of the mean shape
};

struct AppearanceFrame {
    int width = 0, height = 0;
    double scale = 1;                               ///< frame pixels per unit of the aligned shapes
    Eigen::Vector2d low = Eigen::Vector2d::Zero();  ///< the aligned mean's bounding-box corner
    Shape2d meanShape;                              ///< s0 in frame pixels
    std::vector<FramePixel> pixels;                 ///< row by row, left to right

    /// A point of the aligned shapes' frame in frame pixels.
    Eigen::Vector2d toFrame(const Eigen::Vector2d& aligned) const
    {
        return (aligned - low) * scale + Eigen::Vector2d(1, 1);
    }
};

/// The frame `width` pixels across for the aligned mean shape `mean` (of `face`'s vertices).
/// Throws std::invalid_argument (one line) for a width outside [16, 1024]. A pixel on an edge two
/// triangles share belongs to the first (the tracked mesh's triangles do not overlap: tested).
AppearanceFrame appearanceFrame(const vision::CandideMesh& face, const Shape2d& mean, int width);

}  // namespace aam
