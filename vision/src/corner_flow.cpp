#include "corner_flow.hpp"

#include "vision/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vision {

namespace {

/// Fraction of a track's corners that must survive a flow step for the face to count as held
/// by them (the longer grace of FaceTrackerOptions::occludedGraceFrames).
constexpr float kHeldFraction = 0.8f;
/// A track missed by the cascade is held by its corners only while its box is within this factor
/// of the size it was last seen at (facegen seed 13's `two`: a box the crossing faces' corners
/// grew from 125 to 280 px was held, off any face, for 30 frames, and hid the face under it from
/// the scan).
constexpr float kHeldGrowth = 1.25f;

/// Whether `p` lies in the face's box turned by its roll. Corners are found in the inner part
/// of the box (find()), and the face's own motion never carries them out of it: one outside is
/// on the background, left behind as the face moved on. Kept, it lets the fit explain the
/// face's move by a growth about a still side (a fitted scale of 1.04 a frame on facegen seed
/// 23's `enter-leave`, the box half as large again as the face between re-anchorings).
bool onFace(const TrackedFace& f, Point2f p) noexcept
{
    const float r = f.rollDegrees / kDegreesPerRadian;
    const float c = std::cos(r), s = std::sin(r);
    const float dx = p.x - f.centre.x, dy = p.y - f.centre.y;
    const float half = 0.5f * f.size;
    return std::fabs(c * dx + s * dy) <= half && std::fabs(-s * dx + c * dy) <= half;
}

}  // namespace

CornerFlow::CornerFlow(const FaceTrackerOptions& o)
    : options_(o),
      corners_(o.imageSize, CornerDetectorOptions{kMaxPoints, 0.01f, 5.f, 3}),
      flow_(o.flow),
      pyramids_{ImagePyramid(o.imageSize, o.flow.maxLevel + 1),
                ImagePyramid(o.imageSize, o.flow.maxLevel + 1)},
      grays_{ImageBuffer(o.imageSize.width, o.imageSize.height, PixelFormat::Gray8),
             ImageBuffer(o.imageSize.width, o.imageSize.height, PixelFormat::Gray8)},
      background_(o.imageSize, o.flow)
{
}

void CornerFlow::newFrame(const ConstImageView& gray) noexcept
{
    const Size s = options_.imageSize;
    current_ = 1 - current_;
    for (int y = 0; y < s.height; ++y)
        std::memcpy(grays_[current_].view().row(y), gray.row(y), static_cast<std::size_t>(s.width));
    pyramids_[current_].build(grays_[current_].view());
    hasPrevious_ = hasCurrent_;
    hasCurrent_ = true;
}

void CornerFlow::reset() noexcept
{
    hasCurrent_ = false;
    hasPrevious_ = false;
    background_.reset();
}

void CornerFlow::followBackground(std::span<const Track> tracks) noexcept
{
    std::size_t n = 0;
    for (const Track& t : tracks)
        if (n < faces_.size())
            faces_[n++] = t.face.box();
    background_.update(hasPrevious_ ? &pyramids_[1 - current_] : nullptr, pyramids_[current_],
                       image(), {faces_.data(), n});
}

void CornerFlow::find(Track& t, bool replenish) noexcept
{
    // Shi-Tomasi corners in the face box, spaced in proportion to the face size.
    const float minDistance = std::max(2.f, t.face.size * options_.cornerMinDistanceFraction);
    corners_.setMinDistance(minDistance);
    corners_.setMaxCorners(options_.maxCornersPerFace);
    // The inner part of the box: the box corners are often background or hair, which do not
    // move with the face.
    const float inner = t.face.size * 0.7f;
    const Rect area{static_cast<int>(t.face.centre.x - inner * 0.5f),
                    static_cast<int>(t.face.centre.y - inner * 0.5f), static_cast<int>(inner),
                    static_cast<int>(inner)};
    const int n = corners_.detect(image(), area, found_.data(), kMaxPoints);
    if (!replenish)
        t.pointCount = 0;
    const float minSq = minDistance * minDistance;
    for (int i = 0; i < n && t.pointCount < options_.maxCornersPerFace; ++i) {
        const Point2f p = found_[static_cast<std::size_t>(i)].position;
        bool nearExisting = false;
        for (int k = 0; k < t.pointCount && !nearExisting; ++k) {
            const float dx = t.points[static_cast<std::size_t>(k)].x - p.x;
            const float dy = t.points[static_cast<std::size_t>(k)].y - p.y;
            nearExisting = dx * dx + dy * dy < minSq;
        }
        if (!nearExisting)
            t.points[static_cast<std::size_t>(t.pointCount++)] = p;
    }
}

void CornerFlow::follow(Track& t, StaticFaceRule& rule) noexcept
{
    const int n = t.pointCount;
    if (n == 0)
        return;
    flow_.track(pyramids_[1 - current_], pyramids_[current_], t.points.data(), next_.data(),
                status_.data(), n);
    int m = 0;
    for (int i = 0; i < n; ++i) {
        if (status_[static_cast<std::size_t>(i)] != FlowStatus::Tracked)
            continue;
        from_[static_cast<std::size_t>(m)] = t.points[static_cast<std::size_t>(i)];
        to_[static_cast<std::size_t>(m)] = next_[static_cast<std::size_t>(i)];
        ++m;
    }
    const int minimum = options_.mode == FaceTrackingMode::Affine ? 4 : 3;
    MotionModel model;
    const int in = m >= minimum ? fitMotionRobust(from_.data(), to_.data(), m, t.face.centre,
                                                  options_.fit, model, inliers_.data())
                                : 0;
    const float survived = n > 0 ? static_cast<float>(in) / static_cast<float>(n) : 0.f;
    t.heldByCorners =
        in >= std::max(minimum, options_.minCornersPerFace / 2) && survived >= kHeldFraction;
    if (in < minimum) {
        // Nothing reliable moved: keep the box where it was, start the corners afresh.
        t.pointCount = 0;
        t.face.confidence *= 0.5f;
        return;
    }
    tellRule(t, rule, model, m, survived);
    t.face.centre = model.apply(t.face.centre);
    move(t, model, m);
    // A covered face keeps its size: corners that have scaled the box far from the size it was
    // last seen at follow something else (two faces crossing pull a box's corners apart, and its
    // fit calls that growth), and the cascade's misses then mean the face is not there.
    if (t.seenSize > 0.f &&
        (t.face.size > kHeldGrowth * t.seenSize || t.face.size * kHeldGrowth < t.seenSize))
        t.heldByCorners = false;
    t.face.confidence = std::min(1.f, survived);
}

void CornerFlow::tellRule(Track& t, StaticFaceRule& rule, const MotionModel& model, int pairs,
                          float survived) noexcept
{
    // The rule judges the face's own motion: its corners' flow less the view's (a shaking camera
    // moves a print on the wall as far as a calm head sways, but with the background).
    MotionModel own = model;
    for (int i = 0; i < pairs; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const Point2f d = background_.displacement(from_[k]);
        ownTo_[k] = {to_[k].x - d.x, to_[k].y - d.y};
    }
    if (background_.known())
        fitMotionLeastSquares(from_.data(), ownTo_.data(), pairs, inliers_.data(), t.face.centre,
                              model.kind, own);
    const Point2f view = background_.displacement(t.face.centre);
    const Point2f moved = own.apply(t.face.centre);
    const float shift = std::hypot(moved.x - t.face.centre.x, moved.y - t.face.centre.y);
    const auto n = static_cast<std::size_t>(pairs);
    rule.addFlowStep(t.motion, {{from_.data(), n},
                                {ownTo_.data(), n},
                                {inliers_.data(), n},
                                own,
                                t.face.age,
                                survived,
                                shift,
                                std::hypot(view.x, view.y),
                                view});
}

void CornerFlow::move(Track& t, const MotionModel& model, int pairs) noexcept
{
    if (options_.mode != FaceTrackingMode::Translation) {
        // Scale and roll of the similarity part (METHOD.md §3: th = atan2(a2, a1)).
        // A face does not change size by more than a few percent between frames; larger fitted
        // scales come from corners on the background or hair.
        const float s = std::clamp(model.scale(), 0.95f, 1.05f);
        t.face.size *= s;
        t.face.rollDegrees += toDegrees(model.roll());
        t.face.rollDegrees = std::clamp(t.face.rollDegrees, -60.f, 60.f);
    }
    // The corners that fit and are still on the face go on to the next frame.
    int k = 0;
    for (int i = 0; i < pairs; ++i)
        if (inliers_[static_cast<std::size_t>(i)] &&
            onFace(t.face, to_[static_cast<std::size_t>(i)]))
            t.points[static_cast<std::size_t>(k++)] = to_[static_cast<std::size_t>(i)];
    t.pointCount = k;
}

}  // namespace vision
