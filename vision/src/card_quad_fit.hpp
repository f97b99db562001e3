#pragma once
// Fitting the card's quad and judging it (METHOD.md §2 step 5, and the lost-track test beyond the
// dissertation): from a seed quad, two refinement passes along the edge normals (a wide one from
// the seed, a narrow one from its result), then whether the result is plausible as the card. The
// seed is the colour's coarse quad (§2 step 4) or the quad the shape model predicts
// (card_shape_model.hpp). Also the small quad helpers the tracker shares. Private to vision/src.

#include "card_camera_estimate.hpp"
#include "vision/card_tracker.hpp"
#include "vision/edge_refinement.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

namespace vision {

float quadArea(const Quad& q) noexcept;
/// Clockwise on screen, starting at the corner with the smallest x + y (the top-left one).
Quad canonicalOrder(const Quad& in) noexcept;
/// Convex, clockwise and simple: every turn is clockwise (a self-intersecting or concave quad has
/// a turn the other way).
bool isConvexClockwise(const Quad& q) noexcept;
/// Mean long side over mean short side.
float aspectOf(const Quad& q) noexcept;
/// Within 2 pixels of the frame's border, or outside it.
bool nearBorder(Point2f p, Size size) noexcept;
/// The quad's bounding box, grown by `grow` of its size on each side.
Rect boundsOf(const Quad& q, float grow) noexcept;

/// What a fitted quad is judged against: the frame, the options, the card-coloured pixels found
/// and the card's recent shape.
struct QuadJudge {
    Size frame;
    const CardTrackerOptions* options = nullptr;
    int componentArea = 0;  ///< the selected component's pixels
    bool tracking = false;  ///< the last frame was tracked
    unsigned missed = 0;    ///< frames since the last tracked one
    float lastArea = 0.f;   ///< the last tracked quad's area (0: none)
    bool haveGood = false;  ///< a quad seen whole before
    float goodArea = 0.f;   ///< its area and aspect
    float goodAspect = 1.f;
    /// While tracking, the last quad measured on all four edges (null otherwise): an edge without
    /// evidence moves with the card from there (carryHiddenEdge)
    const Quad* measured = nullptr;
    /// While tracking, where the shape model expects the card (null otherwise): a hidden edge
    /// the similarity cannot carry keeps its neighbours' lengths from there (predictHiddenEdge)
    const Quad* predicted = nullptr;
    float predictedGuide = 0.f;  ///< how far the card's edges may be from `predicted`
    /// While tracking, the last frame's edge without evidence (two corners), or null
    const Point2f* hidden = nullptr;
    /// The focal length and the card's aspect from the quads measured on all four edges: a hidden
    /// edge is placed so the quad is the image of the card in 3D (CardCameraEstimate), or null
    const CardCameraEstimate* camera = nullptr;
    /// Tracked frames since the last quad measured on all four edges (`measured`)
    unsigned sinceMeasured = 0;
};

struct QuadFit {
    Quad raw{};                 ///< the refined corners, clockwise from the top-left
    EdgeRefinement refinement;  ///< the pass that gave `raw`
    float area = 0.f;
    float aspect = 1.f;
    float inlierRatio = 0.f;  ///< edge inliers per sample line
    float shape = 1.f;        ///< 0..1: likeness to the last quad seen whole
    float fill = 0.f;         ///< component pixels per quad pixel
    int carried = -1;  ///< the edge without evidence carried with the card (carryHiddenEdge or the
                       ///< card in 3D, CardCameraEstimate), or -1
    int inDepth = -1;  ///< the edge without evidence placed with the card in 3D, or -1
    const char* why = "degenerate component";  ///< null when plausible
};

/// Step 5 from `seed` (clockwise on screen), then the plausibility test. With `guide` > 0 the
/// seed is where the edges are expected: edge points farther than `guide` pixels from it are
/// not fitted.
QuadFit fitQuad(const ConstImageView& rgb, const Quad& seed, const QuadJudge& judge,
                float guide = 0.f) noexcept;

/// Whether `a` is the better fit: a plausible one over an implausible one, then more edges
/// fitted, then more edge inliers.
bool betterFit(const QuadFit& a, const QuadFit& b) noexcept;

}  // namespace vision
