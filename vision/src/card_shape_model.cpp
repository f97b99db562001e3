#include "card_shape_model.hpp"

#include <algorithm>
#include <cmath>

namespace vision {

int bestShift(const Quad& a, const Quad& b) noexcept
{
    int shift = 0;
    float best = 1e30f;
    for (int s = 0; s < 4; ++s) {
        float d = 0.f;
        for (int i = 0; i < 4; ++i) {
            const float dx = a[(i + s) % 4].x - b[i].x, dy = a[(i + s) % 4].y - b[i].y;
            d += dx * dx + dy * dy;
        }
        if (d < best) {
            best = d;
            shift = s;
        }
    }
    return shift;
}

namespace {

/// bestShift after moving b's centroid onto a's: the pairing survives a motion of more than half
/// the card's size (a reference quad from many frames ago).
int bestShiftCentred(const Quad& a, const Quad& b) noexcept
{
    float ax = 0.f, ay = 0.f, bx = 0.f, by = 0.f;
    for (int i = 0; i < 4; ++i) {
        ax += 0.25f * a[i].x;
        ay += 0.25f * a[i].y;
        bx += 0.25f * b[i].x;
        by += 0.25f * b[i].y;
    }
    Quad moved;
    for (int i = 0; i < 4; ++i)
        moved[i] = {b[i].x + ax - bx, b[i].y + ay - by};
    return bestShift(a, moved);
}

}  // namespace

float quadDistance(const Quad& a, const Quad& b) noexcept
{
    const int s = bestShift(a, b);
    float worst = 0.f;
    for (int i = 0; i < 4; ++i)
        worst = std::max(worst, std::hypot(a[(i + s) % 4].x - b[i].x, a[(i + s) % 4].y - b[i].y));
    return worst;
}

void CardShapeModel::track(const Quad& raw, float area, float aspect, unsigned missed, bool whole,
                           bool measured) noexcept
{
    velocity_ = {};
    speed_ = 0.f;
    if (haveLast_ && measured && lastMeasured_) {
        // Per frame over the frames since the last track; a jump of a quarter of the card's size
        // is a new track, not motion.
        const int s = bestShift(raw, last_);
        const float frames = static_cast<float>(missed + 1);
        Quad v;
        float fastest = 0.f;
        for (int i = 0; i < 4; ++i) {
            const int j = (i + s) % 4;
            v[j] = {(raw[j].x - last_[i].x) / frames, (raw[j].y - last_[i].y) / frames};
            fastest = std::max(fastest, std::hypot(v[j].x, v[j].y));
        }
        if (fastest < 0.25f * std::sqrt(std::max(area, 1.f))) {
            velocity_ = v;
            speed_ = fastest;
        }
    }
    if (measured) {
        measured_ = raw;
        haveMeasured_ = true;
        sinceMeasured_ = 0;
    } else {
        ++sinceMeasured_;
    }
    last_ = raw;
    lastArea_ = area;
    lastMeasured_ = measured;
    haveLast_ = true;
    // The shape to recover to is one seen whole: not a card half out of the frame.
    if (whole || !haveGood_) {
        goodArea_ = area;
        goodAspect_ = aspect;
        haveGood_ = true;
    }
}

Quad CardShapeModel::predicted(unsigned missed) const noexcept
{
    const float k = static_cast<float>(missed + 1);
    Quad q;
    for (int i = 0; i < 4; ++i)
        q[i] = {last_[i].x + k * velocity_[i].x, last_[i].y + k * velocity_[i].y};
    return q;
}

Rect CardShapeModel::expectedBounds(unsigned missed) const noexcept
{
    const Quad q = predicted(missed);
    const auto [x0, y0, x1, y1] = extentOf(q);
    // A constant-velocity guess is off by about the last motion (the card speeds up, slows
    // down, turns), more the more frames it spans.
    const float margin =
        8.f + 0.06f * std::sqrt(std::max(lastArea_, 1.f)) + static_cast<float>(missed + 1) * speed_;
    const int ix0 = static_cast<int>(std::floor(x0 - margin));
    const int iy0 = static_cast<int>(std::floor(y0 - margin));
    const int ix1 = static_cast<int>(std::ceil(x1 + margin));
    const int iy1 = static_cast<int>(std::ceil(y1 + margin));
    return {ix0, iy0, ix1 - ix0 + 1, iy1 - iy0 + 1};
}

float CardShapeModel::tolerance() const noexcept
{
    return std::max(4.f, 0.04f * std::sqrt(std::max(lastArea_, 1.f)));
}

float CardShapeModel::edgeGuide(unsigned missed) const noexcept
{
    const float k = static_cast<float>(missed + 1);
    return k * (6.f + 0.05f * std::sqrt(std::max(lastArea_, 1.f)) + 0.5f * speed_);
}

namespace {

constexpr float kMaxTurnMismatch = 0.05f;  // sine of about 3 degrees

/// Well inside the frame: 8 px from its border.
bool wellInView(Point2f p, Size frame) noexcept
{
    return p.x >= 8.f && p.y >= 8.f && p.x <= static_cast<float>(frame.width - 9) &&
           p.y <= static_cast<float>(frame.height - 9);
}

/// Where edge k of `r` is when it moved with the card: the two corners between the other three
/// edges and the same two corners of `reference` give the card's motion since then as a
/// similarity; edge k is the reference's one moved by it, cut by its neighbours (p0, p1). False
/// when the motion is implausible or not rigid in the image (the card turned in depth). With
/// `inView`, an end of the reference's edge k must have been well inside the frame (an edge
/// wholly out of view is unknowable; one running out of view is the card's, as its end in view).
bool carriedEdge(const Quad& reference, Size frame, const EdgeRefinement& r, int k, bool inView,
                 Line2f& hidden, Point2f& p0, Point2f& p1) noexcept
{
    // Corner i joins edges i - 1 and i; edge k runs from corner k to corner k + 1, so corners
    // k + 2 and k + 3 are the measured ones.
    Point2f a, b;
    if (!intersectLines(r.lines[(k + 1) % 4], r.lines[(k + 2) % 4], a) ||
        !intersectLines(r.lines[(k + 2) % 4], r.lines[(k + 3) % 4], b))
        return false;
    const int s = bestShiftCentred(r.quad, reference);  // r.quad[(i + s) % 4] is reference[i]
    auto then = [&](int corner) { return reference[(corner - s + 8) % 4]; };
    if (inView && !wellInView(then(k), frame) && !wellInView(then((k + 1) % 4), frame))
        return false;
    // The similarity z -> m z + t taking the reference's two measured corners to a, b (as
    // complex numbers). Anchored to a measured quad, never to a carried one: carried again, an
    // edge drifts by each frame's error.
    const Point2f ra = then((k + 2) % 4), rb = then((k + 3) % 4);
    const float dx = rb.x - ra.x, dy = rb.y - ra.y, ex = b.x - a.x, ey = b.y - a.y;
    const float den = dx * dx + dy * dy;
    if (den < 1.f)
        return false;
    const float mr = (ex * dx + ey * dy) / den, mi = (ey * dx - ex * dy) / den;
    const float scale = std::hypot(mr, mi);
    if (!(scale > 0.8f && scale < 1.25f))
        return false;
    // A rigid motion in the image turns the fitted neighbours as it turns the measured edge; when
    // they turn otherwise the card turned in depth, and the similarity would misplace the edge.
    auto turnsWith = [&](int from, int to, const Line2f& fitted) {
        const Point2f p = then(from), q = then(to);
        const float ux = mr * (q.x - p.x) - mi * (q.y - p.y);
        const float uy = mi * (q.x - p.x) + mr * (q.y - p.y);
        const float len = std::hypot(ux, uy);
        return len > 1.f && std::fabs(ux * fitted.nx + uy * fitted.ny) < kMaxTurnMismatch * len;
    };
    if (!turnsWith((k + 1) % 4, (k + 2) % 4, r.lines[(k + 1) % 4]) ||
        !turnsWith((k + 3) % 4, k, r.lines[(k + 3) % 4]))
        return false;
    auto moved = [&](Point2f p) {
        const float px = p.x - ra.x, py = p.y - ra.y;
        return Point2f{a.x + mr * px - mi * py, a.y + mi * px + mr * py};
    };
    return lineThrough(moved(then(k)), moved(then((k + 1) % 4)), hidden) &&
           intersectLines(r.lines[(k + 3) % 4], hidden, p0) &&
           intersectLines(hidden, r.lines[(k + 1) % 4], p1);
}

/// A hidden corner on its fitted neighbour `line`, as far from the measured corner `from` as
/// the corner was from it (oldFrom to oldTo).
Point2f alongNeighbour(const Line2f& line, Point2f from, Point2f oldFrom, Point2f oldTo) noexcept
{
    float dx = -line.ny, dy = line.nx;
    const float ox = oldTo.x - oldFrom.x, oy = oldTo.y - oldFrom.y;
    if (dx * ox + dy * oy < 0.f) {
        dx = -dx;
        dy = -dy;
    }
    const float len = std::hypot(ox, oy);
    return Point2f{from.x + dx * len, from.y + dy * len};
}

}  // namespace

bool carryHiddenEdge(const Quad& reference, Size frame, EdgeRefinement& r) noexcept
{
    if (r.edgesFitted != 3)
        return false;
    const int k = firstUnfittedEdge(r);
    Line2f hidden;
    Point2f p0, p1;
    if (!carriedEdge(reference, frame, r, k, true, hidden, p0, p1) ||
        (!wellInView(p0, frame) && !wellInView(p1, frame)))
        return false;
    r.lines[k] = hidden;
    r.quad[k] = p0;
    r.quad[(k + 1) % 4] = p1;
    return true;
}

bool keepHiddenEdgeLengths(const Quad& predicted, EdgeRefinement& r) noexcept
{
    if (r.edgesFitted != 3)
        return false;
    const int k = firstUnfittedEdge(r);
    const int s = bestShiftCentred(r.quad, predicted);  // r.quad[(i + s) % 4] is predicted[i]
    auto expected = [&](int corner) { return predicted[(corner - s + 8) % 4]; };
    Point2f a, b;  // the measured corners k + 2 and k + 3
    if (!intersectLines(r.lines[(k + 1) % 4], r.lines[(k + 2) % 4], a) ||
        !intersectLines(r.lines[(k + 2) % 4], r.lines[(k + 3) % 4], b))
        return false;
    const Point2f p1 =
        alongNeighbour(r.lines[(k + 1) % 4], a, expected((k + 2) % 4), expected((k + 1) % 4));
    const Point2f p0 = alongNeighbour(r.lines[(k + 3) % 4], b, expected((k + 3) % 4), expected(k));
    Line2f hidden;
    if (!lineThrough(p0, p1, hidden))
        return false;
    r.lines[k] = hidden;
    r.quad[k] = p0;
    r.quad[(k + 1) % 4] = p1;
    return true;
}

bool predictHiddenEdge(const Quad& predicted, float guide, bool fromPrediction, Size frame,
                       EdgeRefinement& r) noexcept
{
    if (r.edgesFitted != 3)
        return false;
    const int k = firstUnfittedEdge(r);
    const int s = bestShiftCentred(r.quad, predicted);  // r.quad[(i + s) % 4] is predicted[i]
    auto expected = [&](int corner) { return predicted[(corner - s + 8) % 4]; };
    // The edge's kept line, or where it was, reaches the border: the card leaves the view there,
    // no hand hides it.
    if (!wellInView(r.quad[k], frame) || !wellInView(r.quad[(k + 1) % 4], frame) ||
        !wellInView(expected(k), frame) || !wellInView(expected((k + 1) % 4), frame))
        return false;
    Point2f a, b;  // the measured corners k + 2 and k + 3
    if (!intersectLines(r.lines[(k + 1) % 4], r.lines[(k + 2) % 4], a) ||
        !intersectLines(r.lines[(k + 2) % 4], r.lines[(k + 3) % 4], b))
        return false;
    // A hand over a corner cuts the colour's hull short there: a hull's corner nearer its
    // measured neighbour than the card's was. One no nearer (or farther) is the card's.
    auto distance = [](Point2f p, Point2f q) { return std::hypot(p.x - q.x, p.y - q.y); };
    auto lengthThen = [&](int from, int to) { return distance(expected(from), expected(to)); };
    const float cut1 = lengthThen((k + 2) % 4, (k + 1) % 4) - distance(r.quad[(k + 1) % 4], a);
    const float cut0 = lengthThen((k + 3) % 4, k) - distance(r.quad[k], b);
    if (!fromPrediction && (std::max(cut0, cut1) <= guide || std::min(cut0, cut1) < -guide))
        return false;
    EdgeRefinement placed = r;
    if (!keepHiddenEdgeLengths(predicted, placed) || !wellInView(placed.quad[k], frame) ||
        !wellInView(placed.quad[(k + 1) % 4], frame))
        return false;
    r = placed;
    return true;
}

float carriedEdgeSlack(const EdgeRefinement& r, int k) noexcept
{
    auto length = [&](int i) {
        const Point2f a = r.quad[i], b = r.quad[(i + 1) % 4];
        return std::hypot(b.x - a.x, b.y - a.y);
    };
    return 2.f * kMaxTurnMismatch * std::max(length((k + 1) % 4), length((k + 3) % 4));
}

}  // namespace vision
