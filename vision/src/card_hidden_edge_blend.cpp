#include "card_hidden_edge_blend.hpp"

#include <algorithm>

namespace vision {

bool blendHiddenEdge(const EdgeRefinement& image, float imageSigma, float depthSigma,
                     EdgeRefinement& r) noexcept
{
    if (r.edgesFitted != 3)
        return false;
    const int k = firstUnfittedEdge(r);
    const float vi = std::max(imageSigma * imageSigma, 1e-6f);
    const float vd = std::max(depthSigma * depthSigma, 1e-6f);
    const float toImage = vd / (vi + vd);
    Quad q = r.quad;
    for (const int i : {k, (k + 1) % 4}) {
        const Point2f d = r.quad[i], m = image.quad[i];
        q[i] = {d.x + toImage * (m.x - d.x), d.y + toImage * (m.y - d.y)};
    }
    Line2f hidden;
    if (!lineThrough(q[k], q[(k + 1) % 4], hidden))
        return false;
    r.lines[k] = hidden;
    r.quad = q;
    return true;
}

}  // namespace vision
