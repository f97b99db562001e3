#include "vision/card_tracker.hpp"

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

namespace {

float edgeLength(const Quad& q, int i) noexcept
{
    const Point2f a = q[i], b = q[(i + 1) % 4];
    return std::hypot(b.x - a.x, b.y - a.y);
}

float quadArea(const Quad& q) noexcept
{
    return static_cast<float>(0.5 * signedArea2(q.data(), 4));
}

/// Clockwise on screen, starting at the corner with the smallest x + y (the top-left one).
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

/// Convex, clockwise and simple: every turn is clockwise (a self-intersecting or concave quad has
/// a turn the other way).
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

/// Within 2 pixels of the frame's border, or outside it.
bool nearBorder(Point2f p, Size size) noexcept
{
    constexpr float kMargin = 2.f;
    return p.x < kMargin || p.y < kMargin || p.x > static_cast<float>(size.width - 1) - kMargin ||
           p.y > static_cast<float>(size.height - 1) - kMargin;
}

Rect boundsOf(const Quad& q, float grow) noexcept
{
    float x0 = q[0].x, x1 = q[0].x, y0 = q[0].y, y1 = q[0].y;
    for (const Point2f& p : q) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
    }
    const float gx = grow * (x1 - x0), gy = grow * (y1 - y0);
    const int ix0 = static_cast<int>(std::floor(x0 - gx)),
              iy0 = static_cast<int>(std::floor(y0 - gy));
    const int ix1 = static_cast<int>(std::ceil(x1 + gx)),
              iy1 = static_cast<int>(std::ceil(y1 + gy));
    return {ix0, iy0, ix1 - ix0 + 1, iy1 - iy0 + 1};
}

}  // namespace

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
    Quad lastGood{};
    float lastGoodArea = 0.f;
    float lastGoodAspect = 1.f;
    float previousArea = 0.f;  // quad area of the previous tracked frame
    Quad previousQuad{};       // raw quad of the previous tracked frame
    bool haveLastGood = false;

    void resetTrack() noexcept
    {
        const CardState st = trained.valid ? CardState::Searching : CardState::Untrained;
        obs = CardObservation{};
        obs.state = st;
        obs.mask = mask.view();
        current = trained;
        filtering = false;
        haveLastGood = false;
        difference.forget();
        std::memset(mask.view().data, 0, mask.bytes());
    }

    Quad smooth(const Quad& raw, float scale) noexcept;
    void clearOutside(const Quad& q, float margin) noexcept;
    const CardObservation& fail(bool wasTracking, const char* why) noexcept;
    const char* problem = "";
};

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
    obs.hasQuad = haveLastGood;
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
    // Steps 2-3. While searching, the whole frame against the trained colour (a stale mask or a
    // drifted model is what lost the track); while tracking, only the pixels that changed.
    if (tracking) {
        s.difference.updateMask(rgb, chroma, colorBounds(s.current, o.threshold), o.changeThreshold,
                                mask);
    } else {
        colorTest(chroma, colorBounds(s.trained, o.threshold), {0, 0, s.size.width, s.size.height},
                  mask);
        s.difference.remember(rgb);
    }

    // Step 4: largest component (while tracking, with the pieces an occluder cut off it).
    const float frameArea = static_cast<float>(s.size.width) * static_cast<float>(s.size.height);
    s.labeler.label(mask);
    const Component largest = s.labeler.largest();
    Component comp;
    if (tracking)
        comp =
            s.labeler.selectNear(boundsOf(s.previousQuad, 0.25f), std::max(16, largest.area / 20));
    else
        comp = s.labeler.selectLargest();
    obs.area = largest.area;
    if (largest.area < o.minAreaFraction * frameArea)
        return s.fail(tracking, "no card-coloured component");
    if (largest.area > o.maxAreaFraction * frameArea)
        return s.fail(tracking, "colour model ran away");

    int n = 0;
    for (int y = 0; y < s.size.height; ++y) {
        const int x0 = s.labeler.rowMin()[y];
        if (x0 < 0)
            continue;
        const int x1 = s.labeler.rowMax()[y];
        s.points[n++] = {static_cast<float>(x0), static_cast<float>(y)};
        if (x1 != x0)
            s.points[n++] = {static_cast<float>(x1), static_cast<float>(y)};
    }
    const int hn = convexHull(s.points.get(), n, s.hull.get());
    Quad coarse;
    if (hn < 3 ||
        !minBoundingQuad(s.hull.get(), std::min(hn, kMaxQuadInputVertices), coarse, s.size))
        return s.fail(tracking, "degenerate component");
    coarse = canonicalOrder(coarse);

    // Step 5: two passes, a wide one from the coarse quad and a narrow one from its result.
    EdgeRefinementOptions eo;
    eo.normalsPerEdge = o.normalsPerEdge;
    eo.saturationGradient = o.saturationGradient;
    eo.chromaticityStep = o.chromaticityStep;
    eo.inlierDistance = o.inlierDistance;
    const float scale = std::sqrt(std::max(quadArea(coarse), 1.f));
    eo.searchInside = eo.searchOutside = std::clamp(o.coarseSearch * scale, 6.f, 48.f);
    EdgeRefinement r1, r2;
    refineQuad(rgb, coarse, eo, r1);
    Quad raw = canonicalOrder(r1.quad);
    eo.searchInside = eo.searchOutside = o.fineSearch;
    eo.normalsPerEdge = o.fineNormalsPerEdge;
    const EdgeRefinement* result = &r1;
    if (isConvexClockwise(raw) && refineQuad(rgb, raw, eo, r2) &&
        r2.edgesFitted >= r1.edgesFitted) {
        raw = canonicalOrder(r2.quad);
        result = &r2;
    }

    // Plausibility: the beyond-the-dissertation lost-track test.
    const float area = quadArea(raw);
    const float aspect = aspectOf(raw);
    const float inlierRatio = result->normals > 0 ? static_cast<float>(result->inliers) /
                                                        static_cast<float>(result->normals)
                                                  : 0.f;
    const char* why = nullptr;
    if (!isConvexClockwise(raw))
        why = "quad not convex";
    else if (area < o.minAreaFraction * frameArea || area > frameArea * 1.5f)
        why = "quad area implausible";
    else if (aspect > o.maxAspect)
        why = "absurd aspect";
    else if (result->edgesFitted < 3 || inlierRatio < o.minInlierRatio)
        why = "too few edge inliers";
    for (int i = 0; i < 2 && !why; ++i) {
        const float a = edgeLength(raw, i), b = edgeLength(raw, i + 2);
        if (std::min(a, b) < 4.f || std::max(a, b) > o.maxOppositeEdgeRatio * std::min(a, b))
            why = "absurd perspective";
    }
    float shape = 1.f;
    if (!why && s.haveLastGood) {
        const float ratio = area / std::max(s.lastGoodArea, 1.f);
        const float aspectRatio = aspect / std::max(s.lastGoodAspect, 1e-3f);
        shape = std::exp(-2.f * (std::fabs(std::log(ratio)) + std::fabs(std::log(aspectRatio))));
        if (!tracking && obs.framesSinceGood <= o.shapeMemoryFrames) {
            if (ratio > o.maxRecoveryAreaChange || ratio < 1.f / o.maxRecoveryAreaChange ||
                aspectRatio > 2.f || aspectRatio < 0.5f)
                why = "shape unlike the last good one";
        }
    }
    if (!why && tracking) {
        const float jump = area / std::max(s.previousArea, 1.f);
        if (jump > o.maxAreaJump || jump < 1.f / o.maxAreaJump)
            why = "area jump";
    }
    // An edge without image evidence lying on the frame border: the card is leaving the view and
    // that edge is unknowable.
    for (int i = 0; i < 4 && !why; ++i)
        if (!result->fitted[i] && nearBorder(raw[i], s.size) &&
            nearBorder(raw[(i + 1) % 4], s.size))
            why = "card leaving the frame";
    const float fill = std::clamp(static_cast<float>(comp.area) / std::max(area, 1.f), 0.f, 1.f);
    if (!why && fill < o.minFill)
        why = "component does not fill the quad";
    if (why)
        return s.fail(tracking, why);
    s.problem = "";

    // Step 6: the object mask is the card: nothing outside the quad.
    s.clearOutside(raw, 1.0f);

    // Step 7: model update from the card's own pixels.
    CardColorModel measured;
    float colourFit = 1.f;
    if (measureColorModel(chroma, mask, boundsOf(raw, 0.f), 2, o.minSigma, 32, measured)) {
        colourFit = colorFit(s.trained, measured, o.threshold);
        s.current =
            blendColorModel(s.trained, tracking ? s.current : s.trained, measured, o.alpha, o.beta);
    }

    if (!tracking && obs.framesSinceGood > 3)
        s.filtering = false;  // a new track: do not drag the old corners along
    obs.state = CardState::Tracking;
    obs.hasQuad = true;
    obs.rawQuad = raw;
    obs.quad = s.smooth(raw, std::sqrt(std::max(area, 1.f)));
    obs.framesSinceGood = 0;
    obs.confidence = std::clamp(0.4f * std::min(inlierRatio, 1.f) + 0.2f * colourFit +
                                    0.2f * std::min(fill / 0.9f, 1.f) + 0.2f * shape,
                                0.f, 1.f);
    s.previousArea = area;
    s.previousQuad = raw;
    // The shape to recover to is one seen whole: not a card half out of the frame.
    bool whole = true;
    for (const Point2f& p : raw)
        whole = whole && !nearBorder(p, s.size);
    if (whole || !s.haveLastGood) {
        s.lastGood = raw;
        s.lastGoodArea = area;
        s.lastGoodAspect = aspect;
        s.haveLastGood = true;
    }
    return obs;
}

}  // namespace vision
