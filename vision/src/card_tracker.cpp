#include "vision/card_tracker.hpp"

#include "card_quad_fit.hpp"
#include "card_shape_model.hpp"
#include "vision/card_color_model.hpp"
#include "vision/connected_components.hpp"
#include "vision/convex_hull.hpp"
#include "vision/edge_refinement.hpp"
#include "vision/frame_difference.hpp"
#include "vision/min_bounding_quad.hpp"
#include "vision/one_euro_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace vision {

const char* cardStateName(CardState state) noexcept
{
    switch (state) {
        case CardState::Untrained:
            return "untrained";
        case CardState::Searching:
            return "searching";
        case CardState::Tracking:
            return "tracking";
        case CardState::Lost:
            return "lost";
    }
    return "?";
}

struct CardTracker::State {
    State(Size sz, const CardTrackerOptions& o)
        : size(sz),
          options(o),
          mask(sz.width, sz.height, PixelFormat::Gray8),
          difference(sz),
          labeler(sz),
          points(std::make_unique<Point2f[]>(static_cast<std::size_t>(2 * sz.height + 2))),
          hull(std::make_unique<Point2f[]>(static_cast<std::size_t>(2 * sz.height + 3)))
    {
        for (OneEuroFilter& f : filters)
            f.setParameters(o.smoothingMinCutoffHz, o.smoothingBeta, o.smoothingDerivativeCutoffHz);
    }

    Size size;
    CardTrackerOptions options;
    CardColorModel trained, current;
    ImageBuffer mask;
    FrameDifference difference;
    ComponentLabeler labeler;
    std::unique_ptr<Point2f[]> points;
    std::unique_ptr<Point2f[]> hull;
    CardObservation obs;
    OneEuroFilter filters[8];
    Quad filterOrder{};  // the filters' corners in their own (stable) order
    bool filtering = false;
    CardShapeModel shape;
    CardCameraEstimate camera;  // the focal length and the card's aspect (the card in 3D)
    CardColorModel recent;  // the model of the last tracked frame (adapted to its light)

    void resetTrack() noexcept
    {
        const CardState st = trained.valid ? CardState::Searching : CardState::Untrained;
        obs = CardObservation{};
        obs.state = st;
        obs.mask = mask.view();
        current = trained;
        filtering = false;
        shape.reset();
        camera.reset();
        recent = CardColorModel{};
        difference.forget();
        std::memset(mask.view().data, 0, mask.bytes());
    }

    ColorBounds searchBounds() const noexcept;
    Component selectCard(int largestArea) noexcept;
    bool coarseQuad(Quad& out) noexcept;
    QuadFit fitCard(const ConstImageView& rgb, const Quad* coarse, int componentArea,
                    bool tracking) const noexcept;
    void remember(const QuadFit& fit, unsigned missed) noexcept;
    Quad smooth(const Quad& raw, float scale) noexcept;
    void clearOutside(const Quad& q, float margin) noexcept;
    const CardObservation& fail(bool wasTracking, const char* why) noexcept;
    const char* problem = "";
};

/// The colour a search looks for: the trained one (a drifted model is what loses a track), and,
/// beyond the dissertation, for a while after the card was lost, also the model it was tracked
/// with last: the light it was lost in (a ramp that clips moves the card's chromaticity out of
/// the trained band) is most likely the light it comes back in.
ColorBounds CardTracker::State::searchBounds() const noexcept
{
    constexpr unsigned kRecentColourFrames = 150;  // 5 s at 30 frames per second
    const ColorBounds t = colorBounds(trained, options.threshold);
    if (!recent.valid || obs.framesSinceGood > kRecentColourFrames)
        return t;
    return joinedBounds(t, colorBounds(recent, options.threshold));
}

/// Step 4's component. While tracking, or just after losing the card, where the shape model
/// expects it, with the pieces an occluder cut off it (a piece reaching out of there is something
/// else of the card's colour); a little longer after, the largest one there alone; otherwise the
/// largest one.
Component CardTracker::State::selectCard(int largestArea) noexcept
{
    constexpr unsigned kRecentFrames = 3;
    // A third of a second: about as long as an arm passing in front of the card hides it. Cut in
    // pieces by the arm, the card is smaller than a patch of its colour elsewhere, which the
    // largest component would take for it (and then follow). The place where it is expected grows
    // with the frames lost, so from the fourth its pieces are no longer added: they would gather
    // a patch of its colour beside it. Later the card may be anywhere.
    constexpr unsigned kLostFrames = 10;
    constexpr int kNoPieces = std::numeric_limits<int>::max();
    const unsigned missed = obs.framesSinceGood;
    if (shape.haveLast() && missed <= kLostFrames)
        return labeler.selectNear(shape.expectedBounds(missed),
                                  missed <= kRecentFrames ? std::max(16, largestArea / 20)
                                                          : kNoPieces);
    return labeler.selectLargest();
}

/// Step 4: convex hull of the selected component -> minimum bounding quad.
bool CardTracker::State::coarseQuad(Quad& out) noexcept
{
    int n = 0;
    for (int y = 0; y < size.height; ++y) {
        const int x0 = labeler.rowMin()[y];
        if (x0 < 0)
            continue;
        const int x1 = labeler.rowMax()[y];
        points[n++] = {static_cast<float>(x0), static_cast<float>(y)};
        if (x1 != x0)
            points[n++] = {static_cast<float>(x1), static_cast<float>(y)};
    }
    const int hn = convexHull(points.get(), n, hull.get());
    if (hn < 3 || !minBoundingQuad(hull.get(), std::min(hn, kMaxQuadInputVertices), out, size))
        return false;
    out = canonicalOrder(out);
    return true;
}

namespace {

/// Every edge of `r` either fitted to the image or with both ends in view: none is kept from its
/// seed where it runs out of view (there a stale line, not the card's).
bool inViewOrFitted(const EdgeRefinement& r, Size size) noexcept
{
    for (int i = 0; i < 4; ++i)
        if (!r.fitted[i] && (nearBorder(r.quad[i], size) || nearBorder(r.quad[(i + 1) % 4], size)))
            return false;
    return true;
}

/// Every edge of `r` not fitted to the image lies farther than `margin` from the frame's border:
/// it cuts the card in view (a hand), not where the border cuts it.
bool unfittedWellInside(const EdgeRefinement& r, Size size, float margin) noexcept
{
    auto inside = [&](Point2f p) {
        return p.x >= margin && p.y >= margin &&
               p.x <= static_cast<float>(size.width - 1) - margin &&
               p.y <= static_cast<float>(size.height - 1) - margin;
    };
    for (int i = 0; i < 4; ++i)
        if (!r.fitted[i] && (!inside(r.quad[i]) || !inside(r.quad[(i + 1) % 4])))
            return false;
    return true;
}

}  // namespace

/// Step 5 and the plausibility test, from the colour's coarse quad and, beyond the dissertation,
/// from the quad the shape model predicts when the colour's is implausible or disagrees with it
/// (an occluder cut the card, something of its colour joined it): the better of the two.
QuadFit CardTracker::State::fitCard(const ConstImageView& rgb, const Quad* coarse,
                                    int componentArea, bool tracking) const noexcept
{
    constexpr unsigned kShapeFrames = 3;
    const unsigned missed = obs.framesSinceGood;
    const bool haveShape = shape.haveLast() && missed <= kShapeFrames;
    const Quad predicted = shape.predicted(missed);
    QuadJudge judge;
    judge.frame = size;
    judge.options = &options;
    judge.componentArea = componentArea;
    judge.tracking = tracking;
    judge.missed = missed;
    judge.lastArea = shape.lastArea();
    judge.haveGood = shape.haveGood();
    judge.goodArea = shape.goodArea();
    judge.goodAspect = shape.goodAspect();
    judge.measured = tracking ? shape.lastMeasured() : nullptr;
    judge.predicted = tracking && haveShape ? &predicted : nullptr;
    judge.predictedGuide = shape.edgeGuide(missed);
    judge.hidden = tracking && haveShape ? shape.lastHidden() : nullptr;
    judge.camera = tracking ? &camera : nullptr;
    judge.sinceMeasured = shape.sinceMeasured();
    QuadFit best;
    if (coarse)
        best = fitQuad(rgb, *coarse, judge);
    if (!haveShape)
        return best;
    // An edge the colour's seed did not find may be found from where it is expected.
    if (coarse && !best.why && best.refinement.edgesFitted == 4 &&
        quadDistance(best.raw, predicted) <= shape.tolerance())
        return best;
    const QuadFit alt = fitQuad(rgb, predicted, judge, shape.edgeGuide(missed));
    // The colour's fit carried an edge under a hand with the card; a line the guided pass found
    // for that edge away from where the card carried it is the hand's outline (it lies within
    // the guide of where the edge is expected) farther than the carry can be off, not the card's
    // edge.
    if (coarse && !best.why && best.carried >= 0 && alt.refinement.fitted[best.carried] &&
        alt.refinement.edgesFitted > best.refinement.edgesFitted &&
        quadDistance(alt.raw, best.raw) >
            std::max(shape.tolerance(), carriedEdgeSlack(best.refinement, best.carried))) {
        return best;
    }
    // An edge of the colour's fit without evidence that could not be carried keeps the colour's
    // hull there (cut by a hand over the corner): far from where the card is expected, with no
    // more edges fitted than the guided fit, it is the hull's guess, not the card.
    if (!alt.why && !best.why && best.carried < 0 && best.refinement.edgesFitted < 4 &&
        alt.refinement.edgesFitted >= best.refinement.edgesFitted &&
        inViewOrFitted(alt.refinement, size) &&
        unfittedWellInside(best.refinement, size, shape.edgeGuide(missed)) &&
        quadDistance(best.raw, predicted) > shape.edgeGuide(missed)) {
        return alt;
    }
    return betterFit(alt, best) ? alt : best;
}

void CardTracker::State::remember(const QuadFit& fit, unsigned missed) noexcept
{
    bool whole = true;
    for (const Point2f& p : fit.raw)
        whole = whole && !nearBorder(p, size);
    shape.track(fit.raw, fit.area, fit.aspect, missed, whole, fit.refinement.edgesFitted == 4);
    if (fit.refinement.edgesFitted == 4)
        camera.measure(fit.raw, size);
    // The edge without evidence (under a hand), for the next frame's fit (hiddenEdgeOutline).
    const int k = std::min(firstUnfittedEdge(fit.refinement), 3);
    shape.setHidden(fit.refinement.edgesFitted == 3, fit.refinement.quad[k],
                    fit.refinement.quad[(k + 1) % 4]);
}

// The corners are filtered by a One-Euro filter per coordinate (options: rest cutoff, speed gain,
// frame rate), matched to the filters' own corner order first.
Quad CardTracker::State::smooth(const Quad& raw, float scale) noexcept
{
    const float dt = 1.f / std::max(options.frameRateHz, 1.f);
    int shift = 0;
    if (filtering) {
        float best = 1e30f;
        for (int s = 0; s < 4; ++s) {
            float d = 0.f;
            for (int i = 0; i < 4; ++i) {
                const Point2f a = raw[(i + s) % 4], b = filterOrder[i];
                d += (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
            }
            if (d < best) {
                best = d;
                shift = s;
            }
        }
        // A jump of a quarter of the card's size is a new track, not motion to smooth.
        if (best > 4.f * (0.25f * scale) * (0.25f * scale))
            filtering = false;
    }
    if (!filtering) {
        for (OneEuroFilter& f : filters)
            f.reset();
        shift = 0;
        filtering = true;
    }
    for (int i = 0; i < 4; ++i) {
        const Point2f p = raw[(i + shift) % 4];
        filterOrder[i] = {filters[2 * i].filter(p.x, dt), filters[2 * i + 1].filter(p.y, dt)};
    }
    return canonicalOrder(filterOrder);
}

void CardTracker::State::clearOutside(const Quad& q, float margin) noexcept
{
    // Half-planes of the clockwise quad: outward normal of edge a->b is (ey, -ex).
    float nx[4], ny[4], c[4];
    for (int i = 0; i < 4; ++i) {
        const Point2f a = q[i], b = q[(i + 1) % 4];
        const float ex = b.x - a.x, ey = b.y - a.y;
        const float len = std::max(std::hypot(ex, ey), 1e-6f);
        nx[i] = ey / len;
        ny[i] = -ex / len;
        c[i] = nx[i] * a.x + ny[i] * a.y + margin;
    }
    const ImageView m = mask.view();
    for (int y = 0; y < m.height; ++y) {
        float lo = 0.f, hi = static_cast<float>(m.width - 1);
        for (int i = 0; i < 4; ++i) {
            const float rhs = c[i] - ny[i] * static_cast<float>(y);
            if (nx[i] > 1e-6f)
                hi = std::min(hi, rhs / nx[i]);
            else if (nx[i] < -1e-6f)
                lo = std::max(lo, rhs / nx[i]);
            else if (rhs < 0.f)
                hi = -1.f;
        }
        std::uint8_t* row = m.row(y);
        if (hi < lo) {
            std::memset(row, 0, static_cast<std::size_t>(m.width));
            continue;
        }
        const int x0 = static_cast<int>(std::ceil(lo));
        const int x1 = static_cast<int>(std::floor(hi));
        if (x0 > 0)
            std::memset(row, 0, static_cast<std::size_t>(std::min(x0, m.width)));
        if (x1 + 1 < m.width)
            std::memset(row + std::max(x1 + 1, 0), 0,
                        static_cast<std::size_t>(m.width - std::max(x1 + 1, 0)));
    }
}

const CardObservation& CardTracker::State::fail(bool wasTracking, const char* why) noexcept
{
    problem = why;
    if (wasTracking || obs.state == CardState::Lost) {
        obs.state = CardState::Lost;
        current = trained;  // recover from the trained colour, not the drifted one
    } else {
        obs.state = CardState::Searching;
    }
    obs.hasQuad = shape.haveGood();
    obs.confidence = 0.f;
    ++obs.framesSinceGood;
    return obs;
}

CardTracker::CardTracker(Size size, const CardTrackerOptions& options)
    : s_(std::make_unique<State>(size, options))
{
    s_->resetTrack();
}

CardTracker::~CardTracker() = default;

bool CardTracker::train(const ConstImageView& rgb, const ChromaticityPlanes& chroma,
                        Rect region) noexcept
{
    if (rgb.size() != s_->size || chroma.r.size() != s_->size)
        return false;
    CardColorModel m;
    if (!trainColorModel(chroma, region, s_->options.minSigma, m))
        return false;
    s_->trained = m;
    s_->resetTrack();
    return true;
}

void CardTracker::setModel(const CardColorModel& model) noexcept
{
    s_->trained = model;
    s_->resetTrack();
}

const CardColorModel& CardTracker::trainedModel() const noexcept
{
    return s_->trained;
}
const CardColorModel& CardTracker::currentModel() const noexcept
{
    return s_->current;
}
const CardObservation& CardTracker::observation() const noexcept
{
    return s_->obs;
}
const CardTrackerOptions& CardTracker::options() const noexcept
{
    return s_->options;
}
void CardTracker::reset() noexcept
{
    s_->resetTrack();
}
const char* CardTracker::lastProblem() const noexcept
{
    return s_->problem;
}

// Per frame, the steps of §2: colour test of every pixel against a Gaussian chromaticity model (2),
// object mask updated only where the frame changed (3), largest 8-connected component -> convex
// hull -> Low & Ilie minimum bounding quadrilateral (4), refinement along edge normals on the
// saturation gradient with a RANSAC line fit per edge (5, details in edge_refinement.hpp), mask
// cleared outside the quad (6), model update mu' = a mu_train + (1 - a)(b mu_prev + (1 - b) mu_cur)
// (7). Beyond the dissertation, a frame is accepted only when its quad is plausible, and a lost
// track is searched for with the trained colour and recovered to the last good shape.
const CardObservation& CardTracker::process(const ConstImageView& rgb,
                                            const ChromaticityPlanes& chroma) noexcept
{
    State& s = *s_;
    const CardTrackerOptions& o = s.options;
    CardObservation& obs = s.obs;
    obs.mask = s.mask.view();
    if (!s.trained.valid) {
        obs.state = CardState::Untrained;
        obs.hasQuad = false;
        obs.confidence = 0.f;
        return obs;
    }
    const bool formatOk = rgb.format == PixelFormat::RGB24 || rgb.format == PixelFormat::BGR24 ||
                          rgb.format == PixelFormat::XRGB8888;
    if (!formatOk || rgb.size() != s.size || chroma.r.size() != s.size ||
        chroma.g.size() != s.size || chroma.b.size() != s.size)
        return s.fail(obs.state == CardState::Tracking, "frame size or format mismatch");

    const bool tracking = obs.state == CardState::Tracking;
    const ImageView mask = s.mask.view();
    // Steps 2-3. While searching or lost, the whole frame against the trained colour (a stale mask
    // or a drifted model is what lost the track); while tracking, only the pixels that changed.
    if (tracking) {
        s.difference.updateMask(rgb, chroma, colorBounds(s.current, o.threshold), o.changeThreshold,
                                mask);
    } else {
        colorTest(chroma, s.searchBounds(), {0, 0, s.size.width, s.size.height}, mask);
        s.difference.remember(rgb);
    }

    // Step 4: the card's component, its hull and minimum bounding quad.
    const float frameArea = static_cast<float>(s.size.width) * static_cast<float>(s.size.height);
    s.labeler.label(mask);
    const Component largest = s.labeler.largest();
    const Component comp = s.selectCard(largest.area);
    obs.area = largest.area;
    if (largest.area < o.minAreaFraction * frameArea)
        return s.fail(tracking, "no card-coloured component");
    if (largest.area > o.maxAreaFraction * frameArea) {
        s.recent = CardColorModel{};  // the trained colour alone from now on
        return s.fail(tracking, "colour model ran away");
    }
    Quad coarse;
    const bool haveCoarse = s.coarseQuad(coarse);

    // Step 5, and whether the result is the card.
    const QuadFit fit = s.fitCard(rgb, haveCoarse ? &coarse : nullptr, comp.area, tracking);
    if (fit.why)
        return s.fail(tracking, fit.why);
    s.problem = "";
    const Quad& raw = fit.raw;

    // Step 6: the object mask is the card: nothing outside the quad.
    s.clearOutside(raw, 1.0f);

    // Step 7: model update from the card's own pixels.
    CardColorModel measured;
    float colourFit = 1.f;
    if (measureColorModel(chroma, mask, boundsOf(raw, 0.f), 2, o.minSigma, 32, measured)) {
        colourFit = colorFit(s.trained, measured, o.threshold);
        s.current =
            blendColorModel(s.trained, tracking ? s.current : s.recent, measured, o.alpha, o.beta);
    }
    s.recent = s.current;

    if (!tracking && obs.framesSinceGood > 3)
        s.filtering = false;  // a new track: do not drag the old corners along
    obs.state = CardState::Tracking;
    obs.hasQuad = true;
    obs.rawQuad = raw;
    obs.quad = s.smooth(raw, std::sqrt(std::max(fit.area, 1.f)));
    const unsigned missed = obs.framesSinceGood;
    obs.framesSinceGood = 0;
    obs.confidence = std::clamp(0.4f * std::min(fit.inlierRatio, 1.f) + 0.2f * colourFit +
                                    0.2f * std::min(fit.fill / 0.9f, 1.f) + 0.2f * fit.shape,
                                0.f, 1.f);
    s.remember(fit, missed);
    return obs;
}

}  // namespace vision
