#pragma once
// The hidden edge weighed between two placements, beyond the dissertation (§2 step 5 fits lines
// in the image; §2 future work, recovery from the shape model). With three edges fitted, the card
// in 3D (CardCameraEstimate) places the hidden edge exactly from exact lines but through the
// neighbours' vanishing point: near parallel neighbours, a fraction of a degree of fitting error
// moves it far. The image-plane placements (carryHiddenEdge, predictHiddenEdge) drift instead as
// frames pass without the edge measured. Both put each hidden corner on its fitted neighbour
// line, so the choice is one distance along each line: weighed by each placement's uncertainty,
// the better-conditioned one wins, and neither threshold nor seed decides. Private to vision/src.

#include "vision/edge_refinement.hpp"

namespace vision {

/// With exactly one edge k of `r` not fitted, `r` placed in 3D with an uncertainty of
/// `depthSigma` pixels and `image` the same fit placed in the image with `imageSigma`: each hidden
/// corner of `r` moved toward `image`'s by imageSigma's share of the weight, the inverse-variance
/// mean. `r.lines[k]` and `r.quad` are updated. False (r unchanged) when degenerate.
bool blendHiddenEdge(const EdgeRefinement& image, float imageSigma, float depthSigma,
                     EdgeRefinement& r) noexcept;

}  // namespace vision
