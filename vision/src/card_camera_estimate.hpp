#pragma once
// CardCameraEstimate: the camera's focal length and the card's aspect in 3D, estimated over the
// frames whose quad was fitted on all four edges (card_rectangle_3d.hpp), and the hidden edge of a
// quad with three edges fitted placed with them. Beyond the dissertation (§2 step 5 fits lines in
// the image; §2 future work, recovery from the shape model). Private to vision/src.
//
// The principal point is not measured: two places are weighed, the image's centre (a lens centred
// on the sensor) and the image of the card's centre (the camera's axis through the card, as
// cardgen renders it: its card poses are projected about the card's centre, then moved in the
// image). Each keeps its own least-squares focal length; the one whose quads agree on one focal
// length (the smaller residual) is used.

#include "card_rectangle_3d.hpp"
#include "vision/edge_refinement.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

namespace vision {

class CardCameraEstimate {
public:
    void reset() noexcept { *this = CardCameraEstimate{}; }

    /// A quad fitted on all four edges, in a frame of `frame`.
    void measure(const Quad& q, Size frame) noexcept;

    /// Enough quads agree on a focal length and an aspect.
    bool trusted() const noexcept;
    /// The focal length (pixels) and the card's long side over its short side, of the principal
    /// point used.
    double focal() const noexcept;
    double aspect() const noexcept;
    /// The principal point is the card's centre (else the image's).
    bool principalAtCard() const noexcept;

    /// With exactly one edge of `r` not fitted, that edge placed so the quad is the image of a
    /// rectangle of the card's aspect (its long side along whichever pair puts the quad nearer
    /// `expected`, the shape model's quad for this frame) seen with the focal length. `r.lines` and
    /// `r.quad` are updated. `spread`: how far (pixels) the hidden corners move when each fitted
    /// neighbour line is turned by its angle standard error (EdgeRefinement::turnSigma) and when
    /// the focal length and the aspect are moved by theirs, and, while the other principal point
    /// is trusted too, to where it places them, the moves added in quadrature: large when the
    /// neighbours are near parallel in the image and their vanishing point, which sets the
    /// foreshortening, is ill-determined. False (r unchanged) when not trusted or degenerate.
    bool placeHiddenEdge(const Quad& expected, EdgeRefinement& r, float& spread) const noexcept;
    /// How far a quad fitted on all four edges is from the image of the card: |log| of its sides'
    /// ratio in 3D (long over short, seen with the focal length) over the card's aspect. 0 when
    /// not trusted, not yet settled (15 frames of aspect, the quads agreeing on the focal length
    /// within 0.01) or degenerate.
    double aspectMismatch(const Quad& q) const noexcept;
    /// The same quad's sides' angle in 3D: |cos| of it (rectangleSkew), 0 for the card's right
    /// angle; 0 when not trusted, not yet settled or degenerate.
    double rightAngleMismatch(const Quad& q) const noexcept;

private:
    /// One principal point's least squares a f^2 = b (forgetting old frames) and its aspect.
    struct Hypothesis {
        double aa = 0.0, ab = 0.0, bb = 0.0;
        double weight = 0.0;  // the quads' count, forgetting
        double logAspect = 0.0, logAspect2 = 0.0, aspectWeight = 0.0;
        double focalSquared() const noexcept { return aa > 0.0 ? ab / aa : 0.0; }
        /// Residual over explained: how far the quads disagree on one focal length.
        double disagreement() const noexcept;
        /// The focal length's relative standard error, the log aspect's standard error.
        double focalError() const noexcept;
        double aspectError() const noexcept;
    };
    void add(Hypothesis& h, const Quad& q, Point2f principal) noexcept;
    const Hypothesis& used() const noexcept;
    /// The camera a settled estimate sees `q` with (its principal point at q's centre when that
    /// hypothesis is used); false when not trusted, not yet settled or degenerate.
    bool settledView(const Quad& q, PinholeView& view) const noexcept;
    bool trusted(const Hypothesis& h) const noexcept;
    bool place(const Line2f lines[4], int k, double ratio, double focal, Point2f principal,
               bool atCard, Point2f inside, Point2f& p0, Point2f& p1) const noexcept;
    /// A placement's choices: the sides' ratio, the principal point, a point inside the card.
    struct Placement {
        double ratio = 1.0;
        Point2f principal{};
        Point2f inside{};
    };
    float spreadOf(const EdgeRefinement& r, int k, const Placement& at, const Quad& expected,
                   Point2f p0, Point2f p1) const noexcept;

    Hypothesis imageCentre_, cardCentre_;
    double scale_ = 1.0;  // the frame's larger side: a and b of order 1
    Point2f centre_{};
};

}  // namespace vision
