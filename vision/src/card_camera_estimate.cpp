#include "card_camera_estimate.hpp"

#include "card_shape_model.hpp"

#include <algorithm>
#include <cmath>

namespace vision {

namespace {

/// Each frame's weight in the sums falls by this per later frame (a time constant of 50 frames):
/// the focal length is the lens's, the aspect the card's, both constant; forgetting lets a wrong
/// start fade.
constexpr double kForget = 0.98;
/// The sums of a^2 that make a focal length trusted: a few quads with both pairs of sides clearly
/// converging (a card facing the camera has a near 0 and tells nothing).
constexpr double kMinInformation = 0.1;
/// Trusted while the quads' residual is under this share of what the focal length explains.
constexpr double kMaxDisagreement = 0.05;
/// Frames of aspect, at full weight, before it is trusted.
constexpr double kMinAspectFrames = 5.0;
/// Passes that move the principal point to the card's centre as the hidden edge settles.
constexpr int kCentrePasses = 4;

Point2f centroid(const Quad& q) noexcept
{
    return {0.25f * (q[0].x + q[1].x + q[2].x + q[3].x), 0.25f * (q[0].y + q[1].y + q[2].y + q[3].y)};
}

}  // namespace

double CardCameraEstimate::Hypothesis::disagreement() const noexcept
{
    // sum (b - a F)^2 over sum (a F)^2 at the least-squares F = ab / aa.
    if (!(aa > 0.0) || !(ab > 0.0))
        return 1e9;
    return std::max(bb * aa / (ab * ab) - 1.0, 0.0);
}

void CardCameraEstimate::add(Hypothesis& h, const Quad& q, Point2f principal) noexcept
{
    const FocalConstraint c = rectangleFocalConstraint(q, principal, scale_);
    h.aa = kForget * h.aa + c.a * c.a;
    h.ab = kForget * h.ab + c.a * c.b;
    h.bb = kForget * h.bb + c.b * c.b;
    const double f2 = h.focalSquared();
    if (!(f2 > 0.0))
        return;
    const double ratio = rectangleSideRatio(q, {std::sqrt(f2) * scale_, principal});
    if (!(ratio > 0.0))
        return;
    h.logAspect = kForget * h.logAspect + std::fabs(std::log(ratio));
    h.aspectWeight = kForget * h.aspectWeight + 1.0;
}

void CardCameraEstimate::measure(const Quad& q, Size frame) noexcept
{
    scale_ = static_cast<double>(std::max(frame.width, frame.height));
    centre_ = {0.5f * static_cast<float>(frame.width - 1), 0.5f * static_cast<float>(frame.height - 1)};
    add(imageCentre_, q, centre_);
    Point2f cardCentre;
    if (diagonalsMeet(q, cardCentre))
        add(cardCentre_, q, cardCentre);
}

bool CardCameraEstimate::trusted(const Hypothesis& h) const noexcept
{
    const double f = std::sqrt(std::max(h.focalSquared(), 0.0));
    return h.aa >= kMinInformation && h.disagreement() <= kMaxDisagreement && f > 0.2 &&
           f < 10.0 && h.aspectWeight >= kMinAspectFrames;
}

const CardCameraEstimate::Hypothesis& CardCameraEstimate::used() const noexcept
{
    return cardCentre_.disagreement() < imageCentre_.disagreement() ? cardCentre_ : imageCentre_;
}

bool CardCameraEstimate::trusted() const noexcept
{
    return trusted(used());
}

double CardCameraEstimate::focal() const noexcept
{
    return std::sqrt(std::max(used().focalSquared(), 0.0)) * scale_;
}

double CardCameraEstimate::aspect() const noexcept
{
    const Hypothesis& h = used();
    return h.aspectWeight > 0.0 ? std::exp(h.logAspect / h.aspectWeight) : 1.0;
}

bool CardCameraEstimate::principalAtCard() const noexcept
{
    return &used() == &cardCentre_;
}

/// placeHiddenRectangleEdge at `principal`; at the card's centre, that centre is where the
/// diagonals of the quad being placed meet, so it is moved there and the edge placed again.
bool CardCameraEstimate::place(const Line2f lines[4], int k, double ratio, Point2f principal,
                               Point2f inside, Point2f& p0, Point2f& p1) const noexcept
{
    const double f = focal();
    Point2f a, b;  // the measured corners k + 2 and k + 3
    if (!intersectLines(lines[(k + 1) % 4], lines[(k + 2) % 4], a) ||
        !intersectLines(lines[(k + 2) % 4], lines[(k + 3) % 4], b))
        return false;
    const int passes = principalAtCard() ? kCentrePasses : 1;
    for (int pass = 0; pass < passes; ++pass) {
        if (!placeHiddenRectangleEdge(lines, k, {f, principal}, ratio, inside, p0, p1))
            return false;
        Quad q;
        q[k] = p0;
        q[(k + 1) % 4] = p1;
        q[(k + 2) % 4] = a;
        q[(k + 3) % 4] = b;
        if (!diagonalsMeet(q, principal))
            return false;
    }
    return true;
}

bool CardCameraEstimate::placeHiddenEdge(const Quad& expected, EdgeRefinement& r) const noexcept
{
    if (r.edgesFitted != 3 || !trusted())
        return false;
    int k = 0;
    while (r.fitted[k])
        ++k;
    Point2f principal = centre_;
    if (principalAtCard() && !diagonalsMeet(expected, principal))
        return false;
    // The card's long side along the neighbours or along the opposite edge: the one nearer the
    // expected quad.
    const double ratios[2] = {aspect(), 1.0 / aspect()};
    Quad best{};
    float bestDistance = 1e30f;
    for (const double ratio : ratios) {
        Quad q = r.quad;
        if (!place(r.lines, k, ratio, principal, centroid(r.quad), q[k], q[(k + 1) % 4]))
            continue;
        const float d = quadDistance(q, expected);
        if (d < bestDistance) {
            bestDistance = d;
            best = q;
        }
    }
    Line2f hidden;
    if (!(bestDistance < 1e30f) || !lineThrough(best[k], best[(k + 1) % 4], hidden))
        return false;
    r.lines[k] = hidden;
    r.quad = best;
    return true;
}

}  // namespace vision
