#include "card_quad_fit.hpp"

#include "card_hidden_edge_blend.hpp"
#include "card_shape_model.hpp"
#include "vision/convex_hull.hpp"

#include <algorithm>
#include <cmath>

namespace vision {

namespace {

/// Sine of the turn (about 11.5 degrees) beyond which a line fitted for an edge hidden in the last
/// frame is an outline across the card rather than the card's edge coming back.
constexpr float kHiddenOutlineTurn = 0.2f;
/// How far (pixels) an image-plane placement of a hidden edge drifts per frame since the edge was
/// last measured: a neighbour's length changes about 1 px a frame while the card turns in depth;
/// the drift over n frames grows as sqrt(n).
constexpr float kLengthDrift = 1.f;
/// An edge's line (or a hidden edge's placement in 3D, from the image-plane one) this many times
/// farther from where the edge is expected than the card's edges may be (the shape model's
/// guide): not the card's edge, which the guide allows for.
constexpr float kOutlineFar = 2.f;
/// The most a quad fitted on four edges may differ from the card's aspect in 3D (|log| of the
/// ratio): over the 72 hard and unseen seeds, with 15 frames of aspect in the estimate, 7276
/// quads within 2 px of the card differed by at most 0.033; 11 of 17 more than 6 px off by more
/// than 0.05.
constexpr double kMaxAspectMismatch = 0.05;
/// The most |cos| of the angle in 3D between a quad's pairs of sides may be (about 3 degrees from
/// a right angle): over the same seeds, right quads at most 0.048; 11 of the 17 far off above.
constexpr double kMaxRightAngleMismatch = 0.05;

float edgeLength(const Quad& q, int i) noexcept
{
    const Point2f a = q[i], b = q[(i + 1) % 4];
    return std::hypot(b.x - a.x, b.y - a.y);
}

/// Two passes, a wide one from the seed and a narrow one from its result.
/// With `deep`, the wide pass starts its walks as deep inside the card as the refinement allows
/// (0.35 of the shortest edge): the first step from there is the card's own edge, not the
/// outline of something of its colour that joined the component and pushed the seed out.
/// `brightness`: EdgeRefinementOptions::brightnessStep (0: the colour cues of §2 alone).
void refineTwice(const ConstImageView& rgb, const Quad& seed, const CardTrackerOptions& o,
                 float guide, QuadFit& fit, bool deep = false, float brightness = 0.f) noexcept
{
    EdgeRefinementOptions eo;
    eo.brightnessStep = brightness;
    eo.maxSeedDistance = guide;
    eo.normalsPerEdge = o.normalsPerEdge;
    eo.saturationGradient = o.saturationGradient;
    eo.chromaticityStep = o.chromaticityStep;
    eo.inlierDistance = o.inlierDistance;
    const float scale = std::sqrt(std::max(quadArea(seed), 1.f));
    eo.searchInside = eo.searchOutside = std::clamp(o.coarseSearch * scale, 6.f, 48.f);
    if (deep) {
        eo.searchInside = scale;
        eo.deepFraction = 0.45f;
    }
    refineQuad(rgb, seed, eo, fit.refinement);
    fit.raw = canonicalOrder(fit.refinement.quad);
    eo.searchInside = eo.searchOutside = o.fineSearch;
    eo.normalsPerEdge = o.fineNormalsPerEdge;
    if (guide > 0.f)
        eo.maxSeedDistance = o.fineSearch + 1.f;  // the wide pass's lines are the guide now
    // An edge the narrow pass does not confirm is not taken as fitted (a hand's outline within
    // the wide walk), unless the narrow pass keeps too few edges to judge the quad by.
    EdgeRefinement fine;
    if (isConvexClockwise(fit.raw) && refineQuad(rgb, fit.raw, eo, fine) &&
        fine.edgesFitted >= std::min(fit.refinement.edgesFitted, 3)) {
        fit.raw = canonicalOrder(fine.quad);
        fit.refinement = fine;
    }
}

/// The quad's own plausibility: convex, a sane size, aspect and perspective, edge evidence.
const char* implausibleQuad(const QuadFit& f, const QuadJudge& j) noexcept
{
    const CardTrackerOptions& o = *j.options;
    const float frameArea = static_cast<float>(j.frame.width) * static_cast<float>(j.frame.height);
    if (!isConvexClockwise(f.raw))
        return "quad not convex";
    if (f.area < o.minAreaFraction * frameArea || f.area > frameArea * 1.5f)
        return "quad area implausible";
    if (f.aspect > o.maxAspect)
        return "absurd aspect";
    if (f.refinement.edgesFitted < 3 || f.inlierRatio < o.minInlierRatio)
        return "too few edge inliers";
    for (int i = 0; i < 2; ++i) {
        const float a = edgeLength(f.raw, i), b = edgeLength(f.raw, i + 2);
        if (std::min(a, b) < 4.f || std::max(a, b) > o.maxOppositeEdgeRatio * std::min(a, b))
            return "absurd perspective";
    }
    return nullptr;
}

/// How far (pixels) `p` lies outside the frame; negative inside it.
float outsideFrame(Point2f p, Size frame) noexcept
{
    return std::max({-p.x, -p.y, p.x - static_cast<float>(frame.width - 1),
                     p.y - static_cast<float>(frame.height - 1)});
}

/// Out of view farther than this (0.35 of the card's size), a corner or an edge without evidence
/// is a guess from too little of the card.
float farOutOfView(const QuadFit& f) noexcept
{
    return 0.35f * std::sqrt(std::max(f.area, 1.f));
}

/// Plausibility against the card's recent shape and the evidence around it.
const char* unlikeTheCard(QuadFit& f, const QuadJudge& j) noexcept
{
    const CardTrackerOptions& o = *j.options;
    if (j.haveGood) {
        const float ratio = f.area / std::max(j.goodArea, 1.f);
        const float aspectRatio = f.aspect / std::max(j.goodAspect, 1e-3f);
        f.shape = std::exp(-2.f * (std::fabs(std::log(ratio)) + std::fabs(std::log(aspectRatio))));
        if (!j.tracking && j.missed <= o.shapeMemoryFrames) {
            if (ratio > o.maxRecoveryAreaChange || ratio < 1.f / o.maxRecoveryAreaChange ||
                aspectRatio > 2.f || aspectRatio < 0.5f)
                return "shape unlike the last good one";
        }
    }
    // A corner out of view is extrapolated from the visible parts of its edges; found afresh
    // (no track to follow it out), one far outside is a guess from too little of them.
    const float far = farOutOfView(f);
    if (!j.tracking) {
        for (const Point2f& p : f.raw)
            if (outsideFrame(p, j.frame) > far)
                return "corner far out of view";
    }
    // Beyond §2: a quad fitted on four edges is the image of the card's rectangle
    // (CardCameraEstimate): its sides' ratio in 3D far from the card's, or its sides' angle in 3D
    // far from a right angle, is an outline taken for an edge.
    if (j.camera && f.refinement.edgesFitted == 4 &&
        (j.camera->aspectMismatch(f.raw) > kMaxAspectMismatch ||
         j.camera->rightAngleMismatch(f.raw) > kMaxRightAngleMismatch))
        return "not the card's shape in 3D";
    if (j.tracking) {
        const float jump = f.area / std::max(j.lastArea, 1.f);
        if (jump > o.maxAreaJump || jump < 1.f / o.maxAreaJump)
            return "area jump";
    }

    // An edge without image evidence lying on the frame border: the card is leaving the view and
    // that edge is unknowable. One that runs out of view from inside it, not carried with the
    // card, is the seed's line: the colour's hull clipped by the border, not the card's edge.
    for (int i = 0; i < 4; ++i) {
        if (f.refinement.fitted[i])
            continue;
        const Point2f a = f.refinement.quad[i], b = f.refinement.quad[(i + 1) % 4];
        if (nearBorder(a, j.frame) && nearBorder(b, j.frame) && i != f.inDepth)
            return "card leaving the frame";
        if (i != f.carried && std::max(outsideFrame(a, j.frame), outsideFrame(b, j.frame)) > far)
            return "card leaving the frame";
    }
    if (f.fill < o.minFill)
        return "component does not fill the quad";
    return nullptr;
}

/// §2 future work (lost-track detection): an edge hidden in the last frame (judge.hidden) and
/// fitted now far from where its neighbours' last lengths put it (predictHiddenEdge), turned from
/// there by more than the card turns in a frame, is an occluder's outline across the card (a hand
/// of nearly the card's colour), not the card's edge coming back, which comes back near parallel
/// to where it is expected. Then `r` has that edge placed by predictHiddenEdge, not fitted.
bool hiddenEdgeOutline(const QuadJudge& judge, EdgeRefinement& r) noexcept
{
    auto dist = [](Point2f p, Point2f q) { return std::hypot(p.x - q.x, p.y - q.y); };
    const Point2f a = judge.hidden[0], b = judge.hidden[1];
    int j = 0;  // the edge that was hidden: its corners nearest the hidden one's
    float nearest = 1e30f;
    for (int i = 0; i < 4; ++i) {
        const Point2f p = r.quad[i], q = r.quad[(i + 1) % 4];
        const float d = std::min(dist(p, a) + dist(q, b), dist(p, b) + dist(q, a));
        if (d < nearest) {
            nearest = d;
            j = i;
        }
    }
    EdgeRefinement placed = r;
    placed.fitted[j] = false;
    placed.edgesFitted = 3;
    if (!predictHiddenEdge(*judge.predicted, judge.predictedGuide, true, judge.frame, placed))
        return false;
    const Point2f p0 = r.quad[j], p1 = r.quad[(j + 1) % 4];
    const Point2f q0 = placed.quad[j], q1 = placed.quad[(j + 1) % 4];
    if (std::max(dist(p0, q0), dist(p1, q1)) <= judge.predictedGuide)
        return false;
    const float ux = p1.x - p0.x, uy = p1.y - p0.y, vx = q1.x - q0.x, vy = q1.y - q0.y;
    const float turn =
        std::fabs(ux * vy - uy * vx) / std::max(std::hypot(ux, uy) * std::hypot(vx, vy), 1e-6f);
    if (turn <= kHiddenOutlineTurn)
        return false;
    r = placed;
    return true;
}

/// §2 future work (lost-track detection): while tracking, one edge of a four-edge fit whose line
/// passes farther from where that edge is expected than the card moves (twice the shape model's
/// guide), the other three as expected, is an occluder's outline (an arm across the card, a
/// hand's side beside an edge out of view), not the card's edge: a rigid card's edges move
/// together. That edge is marked without evidence, for the hidden edge's placements. Returns the
/// edge, or -1.
int outlineAcrossTheCard(const QuadJudge& judge, EdgeRefinement& r) noexcept
{
    const Quad& e = *judge.predicted;
    auto dist = [](Point2f p, Point2f q) { return std::hypot(p.x - q.x, p.y - q.y); };
    const int s = bestShift(r.quad, e);  // r.quad[(i + s) % 4] is e[i]
    auto expected = [&](int i) { return e[(i - s + 8) % 4]; };
    int outline = -1;
    for (int i = 0; i < 4; ++i) {
        const Point2f p0 = r.quad[i], p1 = r.quad[(i + 1) % 4];
        const float len = std::max(dist(p0, p1), 1e-6f);
        auto offLine = [&](Point2f q) {
            return std::fabs((p1.x - p0.x) * (q.y - p0.y) - (p1.y - p0.y) * (q.x - p0.x)) / len;
        };
        if (std::max(offLine(expected(i)), offLine(expected(i + 1))) <=
            kOutlineFar * judge.predictedGuide)
            continue;
        if (outline >= 0)
            return -1;  // more than one edge far: the card is not where it is expected
        outline = i;
    }
    if (outline < 0)
        return -1;
    r.fitted[outline] = false;
    r.edgesFitted = 3;
    return outline;
}

/// Beyond §2 step 5: with three edges fitted, the hidden one placed so the quad is the image of
/// the card in 3D (CardCameraEstimate), when the focal length and the card's aspect are trusted;
/// wholly out of view (the rest of the card in view) only where an image-plane placement agrees.
/// Weighed against the image-plane placement (the similarity carry, else the neighbours' lengths)
/// by each one's uncertainty (blendHiddenEdge): the 3D one's spread under the lines' fitting
/// error and the estimate's (near parallel neighbours make it large), the image one's drift since
/// the edge was last measured. The image placement is the carry, else the expected quad's
/// neighbour lengths wherever the edge is (in view or not).
bool placedInDepth(const QuadJudge& judge, EdgeRefinement& r) noexcept
{
    if (!judge.camera)
        return false;
    const Quad& expected = judge.predicted ? *judge.predicted : *judge.measured;
    EdgeRefinement placed = r;
    float spread = 0.f;
    if (!judge.camera->placeHiddenEdge(expected, placed, spread))
        return false;
    const int k = firstUnfittedEdge(r);
    const bool outOfView = nearBorder(placed.quad[k], judge.frame) &&
                           nearBorder(placed.quad[(k + 1) % 4], judge.frame);
    EdgeRefinement image = r;
    const bool haveImage = carryHiddenEdge(*judge.measured, judge.frame, image) ||
                           keepHiddenEdgeLengths(expected, image);
    // Out of view, only where the card's recent shape agrees (no image evidence is possible).
    if (outOfView && !haveImage)
        return false;
    // Farther from the image placement than twice the card moves from where it is expected, the
    // 3D one is a wrong solution of the lines (its spread measures how unsure a right one is, not
    // whether it is right); within that, the image placement (the similarity carry, blind to the
    // card turning) may be the one that drifted, and the blend weighs the two.
    auto apart = [&](int i) {
        return std::hypot(placed.quad[i].x - image.quad[i].x, placed.quad[i].y - image.quad[i].y);
    };
    if (haveImage && std::max(apart(k), apart((k + 1) % 4)) > kOutlineFar * judge.predictedGuide)
        return false;
    const float drift = kLengthDrift * std::sqrt(static_cast<float>(judge.sinceMeasured + 1));
    if (haveImage && !blendHiddenEdge(image, drift, spread, placed))
        return false;
    r = placed;
    return true;
}

}  // namespace

float quadArea(const Quad& q) noexcept
{
    return static_cast<float>(0.5 * signedArea2(q.data(), 4));
}

Quad canonicalOrder(const Quad& in) noexcept
{
    Quad q = in;
    if (signedArea2(q.data(), 4) < 0.0)
        std::swap(q[1], q[3]);
    int first = 0;
    for (int i = 1; i < 4; ++i)
        if (q[i].x + q[i].y < q[first].x + q[first].y)
            first = i;
    Quad out;
    for (int i = 0; i < 4; ++i)
        out[i] = q[(first + i) % 4];
    return out;
}

bool isConvexClockwise(const Quad& q) noexcept
{
    for (int i = 0; i < 4; ++i) {
        const Point2f a = q[i], b = q[(i + 1) % 4], c = q[(i + 2) % 4];
        const double cr = (static_cast<double>(b.x) - a.x) * (static_cast<double>(c.y) - b.y) -
                          (static_cast<double>(b.y) - a.y) * (static_cast<double>(c.x) - b.x);
        if (!(cr > 0.0))
            return false;
    }
    return true;
}

float aspectOf(const Quad& q) noexcept
{
    const float w = 0.5f * (edgeLength(q, 0) + edgeLength(q, 2));
    const float h = 0.5f * (edgeLength(q, 1) + edgeLength(q, 3));
    if (!(w > 0.f) || !(h > 0.f))
        return 1e9f;
    return std::max(w, h) / std::min(w, h);
}

bool nearBorder(Point2f p, Size size) noexcept
{
    constexpr float kMargin = 2.f;
    return p.x < kMargin || p.y < kMargin || p.x > static_cast<float>(size.width - 1) - kMargin ||
           p.y > static_cast<float>(size.height - 1) - kMargin;
}

Rect boundsOf(const Quad& q, float grow) noexcept
{
    const auto [x0, y0, x1, y1] = extentOf(q);
    const float gx = grow * (x1 - x0), gy = grow * (y1 - y0);
    const int ix0 = static_cast<int>(std::floor(x0 - gx)),
              iy0 = static_cast<int>(std::floor(y0 - gy));
    const int ix1 = static_cast<int>(std::ceil(x1 + gx)),
              iy1 = static_cast<int>(std::ceil(y1 + gy));
    return {ix0, iy0, ix1 - ix0 + 1, iy1 - iy0 + 1};
}

QuadFit fitQuad(const ConstImageView& rgb, const Quad& seed, const QuadJudge& judge,
                float guide) noexcept
{
    QuadFit f;
    bool unfoundEdge = false;
    refineTwice(rgb, seed, *judge.options, guide, f);
    // Beyond §2: over a background of the card's own colour neither saturation nor chromaticity
    // shows the card's edges, only brightness does. When the colour cues find fewer than three
    // edges, the walks are made again with brightness as the last cue, and that fit is taken
    // only when it finds all four (a brightness step is also a shadow or a pattern's edge).
    if (f.refinement.edgesFitted < 3 && judge.options->brightnessStep > 0.f) {
        QuadFit bright;
        refineTwice(rgb, seed, *judge.options, guide, bright, false, judge.options->brightnessStep);
        if (bright.refinement.edgesFitted == 4)
            f = bright;
    }
    // Found afresh (§2 future work: recovery), an edge in view that its seed's walks did not find
    // is the colour's guess: something of the card's colour joined the component there and the
    // hull's edge lies outside the card. Walked again from deep inside, the card's edge is the
    // first step; kept only when it completes the quad.
    if (!judge.tracking && f.refinement.edgesFitted == 3 && isConvexClockwise(f.raw)) {
        const int k = firstUnfittedEdge(f.refinement);
        const Point2f a = f.refinement.quad[k], b = f.refinement.quad[(k + 1) % 4];
        if (!nearBorder(a, judge.frame) && !nearBorder(b, judge.frame)) {
            QuadFit deep;
            refineTwice(rgb, f.raw, *judge.options, guide, deep, true);
            if (deep.refinement.edgesFitted == 4)
                f = deep;
            else
                unfoundEdge = true;
        }
    }
    if (judge.hidden && judge.predicted && f.refinement.edgesFitted == 4 &&
        hiddenEdgeOutline(judge, f.refinement))
        f.raw = canonicalOrder(f.refinement.quad);
    // An outline's edge is placed like a hidden one but not marked carried: no hand lies over the
    // card's edge there, so the guided fit finding it (fitCard) is not a hand's outline.
    const EdgeRefinement whole = f.refinement;
    const bool outline = judge.predicted && judge.measured && f.refinement.edgesFitted == 4 &&
                         outlineAcrossTheCard(judge, f.refinement) >= 0;
    if (judge.measured && f.refinement.edgesFitted == 3) {
        const int k = firstUnfittedEdge(f.refinement);
        if (placedInDepth(judge, f.refinement)) {
            f.raw = canonicalOrder(f.refinement.quad);
            f.carried = outline ? -1 : k;
            f.inDepth = k;
        } else if (carryHiddenEdge(*judge.measured, judge.frame, f.refinement)) {
            f.raw = canonicalOrder(f.refinement.quad);
            f.carried = outline ? -1 : k;
        } else if (judge.predicted && predictHiddenEdge(*judge.predicted, judge.predictedGuide,
                                                        guide > 0.f, judge.frame, f.refinement)) {
            // Not marked as carried: the carried edge's tests (fitCard) are the similarity's.
            f.raw = canonicalOrder(f.refinement.quad);
        } else if (outline) {
            f.refinement = whole;  // nowhere to place it: the fit as it was
        }
    }
    // Plausibility: the beyond-the-dissertation lost-track test.
    f.area = quadArea(f.raw);
    f.aspect = aspectOf(f.raw);
    f.inlierRatio = f.refinement.normals > 0 ? static_cast<float>(f.refinement.inliers) /
                                                   static_cast<float>(f.refinement.normals)
                                             : 0.f;
    f.fill = std::clamp(static_cast<float>(judge.componentArea) / std::max(f.area, 1.f), 0.f, 1.f);
    f.why = implausibleQuad(f, judge);
    if (!f.why)
        f.why = unlikeTheCard(f, judge);
    // Not walked to even from deep inside, that edge is only the colour's hull: a piece of the
    // card clipped by the light or hidden by a hand, or something of its colour. Nothing of the
    // track vouches for it, so the card is not taken as found from it.
    if (!f.why && unfoundEdge)
        f.why = "an edge in view not found";
    return f;
}

bool betterFit(const QuadFit& a, const QuadFit& b) noexcept
{
    if ((a.why == nullptr) != (b.why == nullptr))
        return a.why == nullptr;
    if (a.refinement.edgesFitted != b.refinement.edgesFitted)
        return a.refinement.edgesFitted > b.refinement.edgesFitted;
    return a.refinement.inliers > b.refinement.inliers;
}

}  // namespace vision
