#pragma once
// CardShapeModel: the card's shape over time, beyond the dissertation (§2's future work: "recover
// ... using the shape model and the original trained colour"). It keeps the last tracked quad and
// how it moved, so the next frame's quad can be predicted (a second seed for the edge refinement
// when the colour's quad is cut by an occluder or joined by background, and where to look for the
// card's pieces), and the last quad seen whole, which a recovered quad must resemble. Private to
// vision/src.

#include "vision/edge_refinement.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

namespace vision {

class CardShapeModel {
public:
    void reset() noexcept { *this = CardShapeModel{}; }

    /// A tracked frame's raw quad (clockwise from the top-left), its area and aspect, `missed`
    /// frames after the last tracked one; `whole` when all four corners are in view; `measured`
    /// when every edge was fitted to the image (a quad with an edge kept from its seed does not
    /// tell how the card moved: extrapolating it would run away).
    void track(const Quad& raw, float area, float aspect, unsigned missed, bool whole,
               bool measured) noexcept;

    bool haveLast() const noexcept { return haveLast_; }
    /// The last tracked frame's edge without image evidence (its two corners), or null: a hand
    /// was over it.
    void setHidden(bool hidden, Point2f a, Point2f b) noexcept
    {
        hidden_ = hidden;
        hiddenEdge_[0] = a;
        hiddenEdge_[1] = b;
    }
    const Point2f* lastHidden() const noexcept { return hidden_ ? hiddenEdge_ : nullptr; }
    /// The last quad with all four edges fitted to the image (null: none since the reset): the
    /// card's measured shape that a hidden edge is carried from (carryHiddenEdge).
    const Quad* lastMeasured() const noexcept { return haveMeasured_ ? &measured_ : nullptr; }
    /// Tracked frames since the last one measured on all four edges (0: the last one was).
    unsigned sinceMeasured() const noexcept { return sinceMeasured_; }
    float lastArea() const noexcept { return lastArea_; }
    /// Where the card is expected `missed` frames after the last tracked one: moving on as it
    /// last moved.
    Quad predicted(unsigned missed) const noexcept;
    /// The predicted quad's bounding box grown by the uncertainty of the prediction: where the
    /// card and the pieces an occluder cut off it can be.
    Rect expectedBounds(unsigned missed) const noexcept;
    /// How far the prediction may be from the card's quad before the prediction is tried too.
    float tolerance() const noexcept;
    /// How far an edge may be from its predicted place, `missed` frames on.
    float edgeGuide(unsigned missed) const noexcept;

    /// The last quad seen whole (the shape a recovery must resemble).
    bool haveGood() const noexcept { return haveGood_; }
    float goodArea() const noexcept { return goodArea_; }
    float goodAspect() const noexcept { return goodAspect_; }

private:
    Quad last_{};
    Quad velocity_{};  // per corner of last_, pixels per frame
    float lastArea_ = 0.f;
    float speed_ = 0.f;  // largest corner displacement of velocity_
    bool haveLast_ = false;
    bool lastMeasured_ = false;
    bool haveGood_ = false;
    Quad measured_{};
    bool haveMeasured_ = false;
    unsigned sinceMeasured_ = 0;
    bool hidden_ = false;
    Point2f hiddenEdge_[2] = {};
    float goodArea_ = 0.f;
    float goodAspect_ = 1.f;
};

/// Largest corner distance between two quads, their corners paired by the best cyclic shift (the
/// top-left corner can change when the card turns through 45 degrees).
float quadDistance(const Quad& a, const Quad& b) noexcept;
/// The cyclic shift s pairing a[(i + s) % 4] with b[i] at the least summed squared distance.
int bestShift(const Quad& a, const Quad& b) noexcept;

/// An edge in view but without image evidence (under a hand) moves with the card: with exactly
/// one edge of `r` not fitted, the two corners between its fitted edges and the same two corners
/// of `reference` (the last quad measured on all four edges) give the card's motion since then as
/// a similarity; the hidden edge is the reference's one moved by it, cut by its fitted neighbours.
/// `r.lines` and `r.quad` are updated. False (r unchanged) when no edge or more than one is
/// hidden, the motion is implausible, or the hidden edge is wholly at or beyond the border of a
/// frame of `frame` (then or now): an edge out of view is unknowable, while one running out of
/// view is still the card's where it is in view (kept there, it would follow a hand's outline).
bool carryHiddenEdge(const Quad& reference, Size frame, EdgeRefinement& r) noexcept;

/// The same edge when the similarity cannot carry it (the card turned in depth: its fitted
/// neighbours turned otherwise than its measured edge), §2 future work (recovery from the shape
/// model): each hidden corner on its fitted neighbour line, as far from the measured corner at
/// the neighbour's other end as in `predicted` (the shape model's quad for this frame: the last
/// one, moved on as it last moved). A neighbour's length changes little from frame to frame as
/// the card turns, where the similarity's turn or the last frame's place does not. Only for a
/// hidden edge well in view, then and now (an edge at the border is the card leaving the view).
/// `fromPrediction`: `r` was refined from `predicted` (the edge's kept line is the last frame's,
/// standing still); otherwise from the colour's quad, whose kept line is the hull's, replaced only
/// where a hand cut the hull short (a hull's corner nearer its measured neighbour than `guide`
/// shorter than the card's was, none farther). False (r unchanged) otherwise.
bool predictHiddenEdge(const Quad& predicted, float guide, bool fromPrediction, Size frame,
                       EdgeRefinement& r) noexcept;
/// predictHiddenEdge's placement without its tests of view and of a cut hull: each hidden corner
/// on its fitted neighbour line as far from the measured corner as in `predicted`, wherever that
/// is (the image-plane placement a placement in 3D is weighed against, card_hidden_edge_blend).
bool keepHiddenEdgeLengths(const Quad& predicted, EdgeRefinement& r) noexcept;
/// How far a corner of edge k carried by carryHiddenEdge may be from the card's: the carry takes
/// the card as turning in the image within about 3 degrees of its measured edge, so a corner at
/// the far end of a neighbour edge may be off by that turn over the neighbour's length, and by as
/// much again along it (the similarity's scale is the measured edge's, foreshortened otherwise).
float carriedEdgeSlack(const EdgeRefinement& r, int k) noexcept;

}  // namespace vision
