#include "vision/background_motion.hpp"

#include <algorithm>
#include <cmath>

namespace vision {

namespace {

/// New corners are sought when fewer than this many are left.
constexpr int kReplenishBelow = 40;
/// Corners are at least this far apart (working pixels): spread over the view, so that its turn
/// is measured and no single object holds most of them.
constexpr float kSpacing = 12.f;
/// A search of the whole image for new corners costs a fifth of the face stage, and a view whose
/// background never yields kReplenishBelow corners (a face filling it, FGNet's; a plain wall)
/// would ask for one every frame in vain: after a search the next waits this many frames, unless
/// the last one had found enough corners for the fit (kMinInliers) and fewer are left (a cut, or
/// something passing in front of them).
constexpr int kSearchEvery = 8;

/// Whether `p` is on a face or on the body of its person: the face's box grown to twice its side
/// and everything below it (shoulders sway with the head, hair and collars move slowly with it:
/// kept, their corners pass the fit's test and bias the view's motion by a few hundredths of a
/// pixel a frame, as much as a calm head sways, facegen seed 1's `one` without shake).
bool onPerson(Point2f p, std::span<const Rect> faces) noexcept
{
    for (const Rect& f : faces) {
        const float w = static_cast<float>(f.width);
        const float cx = static_cast<float>(f.x) + 0.5f * w;
        const float cy = static_cast<float>(f.y) + 0.5f * static_cast<float>(f.height);
        if (p.x >= cx - w && p.x <= cx + w && p.y >= cy - w)
            return true;
    }
    return false;
}

}  // namespace

BackgroundMotion::BackgroundMotion(Size imageSize, const OpticalFlowOptions& flow)
    : size_(imageSize),
      corners_(imageSize, CornerDetectorOptions{kMaxCorners, 0.01f, kSpacing, 3}),
      flow_(flow)
{
    model_.kind = MotionKind::Similarity;
}

void BackgroundMotion::reset() noexcept
{
    count_ = 0;
    known_ = false;
    sinceSearch_ = 0;
    searchFilled_ = false;
}

void BackgroundMotion::update(const ImagePyramid* previous, const ImagePyramid& current,
                              const ConstImageView& gray, std::span<const Rect> faces) noexcept
{
    known_ = false;
    // Corners on a face found since they were (a passer-by, or a face the first frame showed)
    // are not the background's.
    int k = 0;
    for (int i = 0; i < count_; ++i)
        if (!onPerson(points_[static_cast<std::size_t>(i)], faces))
            points_[static_cast<std::size_t>(k++)] = points_[static_cast<std::size_t>(i)];
    count_ = previous != nullptr ? k : 0;
    if (count_ > 0)
        follow(*previous, current);
    ++sinceSearch_;
    const bool due = previous == nullptr || sinceSearch_ >= kSearchEvery ||
                     (searchFilled_ && count_ < kMinInliers);
    if (count_ < kReplenishBelow && due) {
        replenish(gray, faces);
        sinceSearch_ = 0;
        searchFilled_ = count_ >= kMinInliers;
    }
}

void BackgroundMotion::follow(const ImagePyramid& previous, const ImagePyramid& current) noexcept
{
    flow_.track(previous, current, points_.data(), next_.data(), status_.data(), count_);
    int m = 0;
    for (int i = 0; i < count_; ++i) {
        if (status_[static_cast<std::size_t>(i)] != FlowStatus::Tracked)
            continue;
        from_[static_cast<std::size_t>(m)] = points_[static_cast<std::size_t>(i)];
        to_[static_cast<std::size_t>(m)] = next_[static_cast<std::size_t>(i)];
        ++m;
    }
    // About the image centre: the view turns about the camera's axis, near it.
    const Point2f centre{0.5f * static_cast<float>(size_.width),
                         0.5f * static_cast<float>(size_.height)};
    MotionFitOptions fit;
    fit.kind = MotionKind::Similarity;
    // Tighter than a face's fit: the background is rigid, and the sway to be told from it is a
    // fraction of a pixel.
    fit.inlierDistance = 0.5f;
    const int in =
        m >= 3 ? fitMotionRobust(from_.data(), to_.data(), m, centre, fit, model_, inliers_.data())
               : 0;
    known_ = in >= kMinInliers;
    // The inliers go on (people and things that move on their own drop out).
    int k = 0;
    for (int i = 0; i < m; ++i)
        if (in > 0 && inliers_[static_cast<std::size_t>(i)])
            points_[static_cast<std::size_t>(k++)] = to_[static_cast<std::size_t>(i)];
    count_ = k;
}

void BackgroundMotion::replenish(const ConstImageView& gray, std::span<const Rect> faces) noexcept
{
    const int n =
        corners_.detect(gray, {0, 0, size_.width, size_.height}, found_.data(), kMaxCorners);
    const float minSq = kSpacing * kSpacing;
    for (int i = 0; i < n && count_ < kMaxCorners; ++i) {
        const Point2f p = found_[static_cast<std::size_t>(i)].position;
        if (onPerson(p, faces))
            continue;
        bool near = false;
        for (int k = 0; k < count_ && !near; ++k) {
            const float dx = points_[static_cast<std::size_t>(k)].x - p.x;
            const float dy = points_[static_cast<std::size_t>(k)].y - p.y;
            near = dx * dx + dy * dy < minSq;
        }
        if (!near)
            points_[static_cast<std::size_t>(count_++)] = p;
    }
}

float BackgroundMotion::largestDisplacement() const noexcept
{
    float most = 0.f;
    const auto w = static_cast<float>(size_.width), h = static_cast<float>(size_.height);
    for (const Point2f p : {Point2f{0.f, 0.f}, Point2f{w, 0.f}, Point2f{0.f, h}, Point2f{w, h}}) {
        const Point2f d = displacement(p);
        most = std::max(most, std::hypot(d.x, d.y));
    }
    return most;
}

Point2f BackgroundMotion::displacement(Point2f p) const noexcept
{
    if (!known_)
        return {};
    const Point2f q = model_.apply(p);
    return {q.x - p.x, q.y - p.y};
}

}  // namespace vision
