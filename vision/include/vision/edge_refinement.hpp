#pragma once
// Edge refinement of the card's quad (step 5 of METHOD.md §2 and 4.3).
//
// Along a sparse set of sample lines across each quad edge, walk from inside the quad to the
// outside; the edge is where the gradient of saturation S = (max - min) / max first exceeds a
// threshold. Near-vertical edges are crossed along a row (horizontal gradient), near-horizontal
// ones along a column (vertical gradient). Saturation is computed only on those sample lines
// (§2, dissertation 4.3: touch only the pixels needed). Each edge gets a RANSAC line; corners are
// the intersections of adjacent lines, so a corner outside the frame is extrapolated from the
// visible parts of its two edges.
//
// Beyond the dissertation (the reasons beside the code in edge_refinement.cpp): each sample is the
// mean over a short band along the edge, the sub-pixel position comes from the colour blend across
// the edge, walks see only the current field of interlaced video, near-black pixels have their
// saturation computed against a floor (kSaturationDarkFloor), optionally a change of chromaticity
// marks an edge too and, where neither cue finds one, a change of brightness, an edge whose
// inliers bunch on a short piece is not fitted, and a refinement can be guided by where the shape
// model expects the edges.

#include "vision/geometry.hpp"
#include "vision/image.hpp"
#include "vision/line_fit.hpp"

namespace vision {

struct EdgeRefinementOptions {
    int normalsPerEdge = 12;           ///< sample lines per edge (at most kMaxNormalsPerEdge)
    float saturationGradient = 0.12f;  ///< S step (S in 0..1) that marks the edge
    float searchInside = 8.f;          ///< walk starts this far inside the edge (pixels, normal)
    float searchOutside = 8.f;         ///< and ends this far outside
    /// Walks start at most 0.35 of the shortest edge inside (never past the card's middle: the
    /// far edge would be found); when > 0, at most this share of the quad's depth from each
    /// edge instead (a seed much wider than the card, one edge far outside it)
    float deepFraction = 0.f;
    float inlierDistance = 1.0f;       ///< RANSAC inlier band (pixels)
    int ransacIterations = 80;
    float minInlierShare = 0.4f;  ///< an edge needs this share of its sample lines as inliers
    float endMargin = 0.1f;       ///< sample lines avoid this share of the edge at each end
    int band = 2;                 ///< saturation averaged over 2 band + 1 pixels along the edge
    /// Departure of chromaticity from the walk's start (L1 of r, g, b in 0..1) that marks the
    /// edge too; 0: saturation only
    float chromaticityStep = 0.f;
    /// Beyond §2: a departure of brightness (the mean of R, G and B, over 255) from the walk's
    /// start that marks the edge on a walk where neither saturation nor chromaticity marks one
    /// anywhere (a card over a background of its own colour differs from it only in brightness,
    /// which both cues ignore); 0: never
    float brightnessStep = 0.f;
    /// An edge is fitted only when its inliers (and its part in view) span this share of it
    /// (at least 8 pixels): points bunched on a short piece do not fix its direction
    float minEdgeSpan = 0.1f;
    /// When > 0, the input quad is where the edges are expected: edge points farther than this
    /// from their input edge are dropped before the line fit (an occluder's outline nearby)
    float maxSeedDistance = 0.f;
    /// With maxSeedDistance: a fitted line turned from its input edge by more than this (sine of
    /// the angle) is not taken; the edge keeps its input line
    float maxSeedTurn = 0.14f;
};

inline constexpr int kMaxNormalsPerEdge = 64;

struct EdgeRefinement {
    Quad quad{};          ///< refined corners (an edge without a good fit keeps its input line)
    Line2f lines[4];      ///< edge i runs from corner i to corner i + 1
    bool fitted[4] = {};  ///< edge i was fitted to image evidence
    /// A fitted edge's angle standard error (radians): its inliers' residual over their spread
    /// along it (a line fitted on a short piece beside a hand is turned more easily)
    float turnSigma[4] = {};
    int normals = 0;  ///< sample lines walked (inside the image)
    int samples = 0;  ///< edge points found
    int inliers = 0;  ///< of those, inliers of their edge's line
    int edgesFitted = 0;
    int brightnessSamples = 0;  ///< edge points found by brightness alone (brightnessStep)
};

/// The first edge of `r` without a fit (4 when all four are fitted).
inline int firstUnfittedEdge(const EdgeRefinement& r) noexcept
{
    int k = 0;
    while (k < 4 && r.fitted[k])
        ++k;
    return k;
}

/// 8-bit saturation 255 (max - min) / max of a pixel's first three bytes (order-independent).
/// The denominator is at least kSaturationDarkFloor: the saturation of near-black pixels is pure
/// noise ((0, 0, 1) would be fully saturated) and would read as edges next to dark backgrounds.
inline constexpr int kSaturationDarkFloor = 32;
inline int saturation8(const std::uint8_t* p) noexcept
{
    int mx = p[0], mn = p[0];
    mx = p[1] > mx ? p[1] : mx;
    mn = p[1] < mn ? p[1] : mn;
    mx = p[2] > mx ? p[2] : mx;
    mn = p[2] < mn ? p[2] : mn;
    const int den = mx > kSaturationDarkFloor ? mx : kSaturationDarkFloor;
    return (255 * (mx - mn) + den / 2) / den;
}

/// Refines `quad` (clockwise on screen) in `rgb` (RGB24, BGR24 or XRGB8888). False when the image
/// format is unsupported or the quad degenerate; `out.quad` is then the input.
bool refineQuad(const ConstImageView& rgb, const Quad& quad, const EdgeRefinementOptions& options,
                EdgeRefinement& out) noexcept;

}  // namespace vision
