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
/// Before it judges a quad (aspectMismatch): over the hard seeds, the estimate from 11-13 frames
/// still differed from right quads by up to 0.08, from 15 frames on by at most 0.033.
constexpr double kSettledAspectFrames = 15.0;
/// ... and while its quads agree on one focal length this well (a fifth of kMaxDisagreement): in
/// a run started mid-sequence, the image centre taken at 0.026-0.032 saw the card's own quads'
/// sides 3 degrees off a right angle.
constexpr double kSettledDisagreement = 0.01;
/// Passes that move the principal point to the card's centre as the hidden edge settles.
constexpr int kCentrePasses = 4;
/// The least angle error (radians, 0.02 degrees) a fitted line is taken to have.
constexpr float kMinLineTurn = 0.02f * 3.14159265f / 180.f;

/// A line turned by `turn` radians about a point on it.
Line2f turned(const Line2f& l, Point2f about, float turn) noexcept
{
    const float c = std::cos(turn), s = std::sin(turn);
    Line2f out{c * l.nx - s * l.ny, s * l.nx + c * l.ny, 0.f};
    out.c = out.nx * about.x + out.ny * about.y;
    return out;
}

float squared(float x) noexcept
{
    return x * x;
}

/// Neighbour `side` of hidden edge k turned by its angle standard error about its measured
/// corner (where it meets the opposite edge k + 2).
bool turnedAtMeasuredCorner(const EdgeRefinement& r, int k, int side, Line2f& out) noexcept
{
    Point2f corner;
    if (!intersectLines(r.lines[side], r.lines[(k + 2) % 4], corner))
        return false;
    out = turned(r.lines[side], corner, std::max(r.turnSigma[side], kMinLineTurn));
    return true;
}

Point2f centroid(const Quad& q) noexcept
{
    return {0.25f * (q[0].x + q[1].x + q[2].x + q[3].x),
            0.25f * (q[0].y + q[1].y + q[2].y + q[3].y)};
}

}  // namespace

double CardCameraEstimate::Hypothesis::disagreement() const noexcept
{
    // sum (b - a F)^2 over sum (a F)^2 at the least-squares F = ab / aa.
    if (!(aa > 0.0) || !(ab > 0.0))
        return 1e9;
    return std::max(bb * aa / (ab * ab) - 1.0, 0.0);
}

double CardCameraEstimate::Hypothesis::focalError() const noexcept
{
    // f = sqrt(F): its relative error is half F's, the residual's variance over sum a^2.
    const double F = focalSquared();
    if (!(F > 0.0))
        return 1.0;
    const double residual = std::max(bb - ab * ab / aa, 0.0) / std::max(weight - 1.0, 1.0);
    return 0.5 * std::sqrt(residual / aa) / F;
}

double CardCameraEstimate::Hypothesis::aspectError() const noexcept
{
    if (!(aspectWeight > 0.0))
        return 1.0;
    const double mean = logAspect / aspectWeight;
    const double variance = std::max(logAspect2 / aspectWeight - mean * mean, 0.0);
    return std::sqrt(variance / std::max(aspectWeight - 1.0, 1.0));
}

void CardCameraEstimate::add(Hypothesis& h, const Quad& q, Point2f principal) noexcept
{
    const FocalConstraint c = rectangleFocalConstraint(q, principal, scale_);
    h.weight = kForget * h.weight + 1.0;
    h.aa = kForget * h.aa + c.a * c.a;
    h.ab = kForget * h.ab + c.a * c.b;
    h.bb = kForget * h.bb + c.b * c.b;
    const double f2 = h.focalSquared();
    if (!(f2 > 0.0))
        return;
    const double ratio = rectangleSideRatio(q, {std::sqrt(f2) * scale_, principal});
    if (!(ratio > 0.0))
        return;
    const double logRatio = std::fabs(std::log(ratio));
    h.logAspect = kForget * h.logAspect + logRatio;
    h.logAspect2 = kForget * h.logAspect2 + logRatio * logRatio;
    h.aspectWeight = kForget * h.aspectWeight + 1.0;
}

void CardCameraEstimate::measure(const Quad& q, Size frame) noexcept
{
    scale_ = static_cast<double>(std::max(frame.width, frame.height));
    centre_ = {0.5f * static_cast<float>(frame.width - 1),
               0.5f * static_cast<float>(frame.height - 1)};
    add(imageCentre_, q, centre_);
    Point2f cardCentre;
    if (diagonalsMeet(q, cardCentre))
        add(cardCentre_, q, cardCentre);
}

bool CardCameraEstimate::trusted(const Hypothesis& h) const noexcept
{
    const double f = std::sqrt(std::max(h.focalSquared(), 0.0));
    return h.aa >= kMinInformation && h.disagreement() <= kMaxDisagreement && f > 0.2 && f < 10.0 &&
           h.aspectWeight >= kMinAspectFrames;
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
bool CardCameraEstimate::place(const Line2f lines[4], int k, double ratio, double f,
                               Point2f principal, bool atCard, Point2f inside, Point2f& p0,
                               Point2f& p1) const noexcept
{
    Point2f a, b;  // the measured corners k + 2 and k + 3
    if (!intersectLines(lines[(k + 1) % 4], lines[(k + 2) % 4], a) ||
        !intersectLines(lines[(k + 2) % 4], lines[(k + 3) % 4], b))
        return false;
    const int passes = atCard ? kCentrePasses : 1;
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

/// How far the placed corners p0, p1 move when each fitted neighbour of edge k is turned by its
/// angle standard error about its measured corner, when the focal length and the aspect are moved
/// by theirs, and, while the other principal point is trusted too (the quads do not yet tell
/// which is the camera's), to where that one places them, that move weighed by the ratio of the
/// two residuals (1: the quads agree as well on either): the moves added in quadrature.
float CardCameraEstimate::spreadOf(const EdgeRefinement& r, int k, const Placement& at,
                                   const Quad& expected, Point2f p0, Point2f p1) const noexcept
{
    float sum = 0.f;
    bool placed = true;
    auto move = [&](const Line2f lines[4], double ratio, double f, Point2f principal, bool atCard,
                    float weight) {
        Point2f q0, q1;
        if (!place(lines, k, ratio, f, principal, atCard, at.inside, q0, q1))
            return false;
        sum += squared(weight * std::max(std::hypot(q0.x - p0.x, q0.y - p0.y),
                                         std::hypot(q1.x - p1.x, q1.y - p1.y)));
        return true;
    };
    auto add = [&](const Line2f lines[4], double ratio, double f, Point2f principal, bool atCard) {
        placed = placed && move(lines, ratio, f, principal, atCard, 1.f);
    };
    const bool atCard = principalAtCard();
    for (const int side : {(k + 1) % 4, (k + 3) % 4}) {
        Line2f moved[4] = {r.lines[0], r.lines[1], r.lines[2], r.lines[3]};
        if (!turnedAtMeasuredCorner(r, k, side, moved[side]))
            return 1e30f;
        add(moved, at.ratio, focal(), at.principal, atCard);
    }
    add(r.lines, at.ratio, focal() * (1.0 + used().focalError()), at.principal, atCard);
    add(r.lines, at.ratio * std::exp(used().aspectError()), focal(), at.principal, atCard);
    const Hypothesis& other = atCard ? imageCentre_ : cardCentre_;
    Point2f otherPrincipal = centre_;
    if (trusted(other) && (atCard || diagonalsMeet(expected, otherPrincipal))) {
        const double aspect = std::exp(other.logAspect / other.aspectWeight);
        // Weighed by how nearly the other's quads agree as well as the used one's.
        const double plausible = used().disagreement() / std::max(other.disagreement(), 1e-12);
        move(r.lines, at.ratio >= 1.0 ? aspect : 1.0 / aspect,
             std::sqrt(other.focalSquared()) * scale_, otherPrincipal, !atCard,
             static_cast<float>(std::min(plausible, 1.0)));
    }
    return placed ? std::sqrt(sum) : 1e30f;
}

bool CardCameraEstimate::settledView(const Quad& q, PinholeView& view) const noexcept
{
    if (!trusted() || used().aspectWeight < kSettledAspectFrames ||
        used().disagreement() > kSettledDisagreement)
        return false;
    view = {focal(), centre_};
    return !principalAtCard() || diagonalsMeet(q, view.principal);
}

double CardCameraEstimate::rightAngleMismatch(const Quad& q) const noexcept
{
    PinholeView view;
    return settledView(q, view) ? rectangleSkew(q, view) : 0.0;
}

double CardCameraEstimate::aspectMismatch(const Quad& q) const noexcept
{
    PinholeView view;
    if (!settledView(q, view))
        return 0.0;
    const double ratio = rectangleSideRatio(q, view);
    if (!(ratio > 0.0))
        return 0.0;
    return std::fabs(std::log(std::max(ratio, 1.0 / ratio) / aspect()));
}

bool CardCameraEstimate::placeHiddenEdge(const Quad& expected, EdgeRefinement& r,
                                         float& spread) const noexcept
{
    if (r.edgesFitted != 3 || !trusted())
        return false;
    const int k = firstUnfittedEdge(r);
    Point2f principal = centre_;
    if (principalAtCard() && !diagonalsMeet(expected, principal))
        return false;
    // The card's long side along the neighbours or along the opposite edge: the one nearer the
    // expected quad.
    const double ratios[2] = {aspect(), 1.0 / aspect()};
    Placement at{0.0, principal, centroid(r.quad)};
    Quad best{};
    float bestDistance = 1e30f;
    for (const double ratio : ratios) {
        Quad q = r.quad;
        if (!place(r.lines, k, ratio, focal(), principal, principalAtCard(), at.inside, q[k],
                   q[(k + 1) % 4]))
            continue;
        const float d = quadDistance(q, expected);
        if (d < bestDistance) {
            bestDistance = d;
            best = q;
            at.ratio = ratio;
        }
    }
    Line2f hidden;
    if (!(bestDistance < 1e30f) || !lineThrough(best[k], best[(k + 1) % 4], hidden))
        return false;
    spread = spreadOf(r, k, at, expected, best[k], best[(k + 1) % 4]);
    r.lines[k] = hidden;
    r.quad = best;
    return true;
}

}  // namespace vision
