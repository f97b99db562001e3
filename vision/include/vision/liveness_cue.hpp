#pragma once
// LivenessCue: a living face standing still told from a photograph on the wall by what only the
// living one does (METHOD.md §3, "Detection": static regions are not faces; dissertation 5.1.3).
// A person never holds perfectly still: within half a second their head sways by a fraction of a
// pixel, and every part of the face sways with it. A print's corners stay within the noise of
// the optical flow, or drift slowly as the light changes, and a passer-by drags only the corners
// on its side.
//
// From each flow step of a face (its corner pairs and the motion fit) the cue keeps the median
// flow of all its corners, of those left of, right of, above and below its centre, and the noise
// of that median (the corners' scatter about the fit). The face swayed when, over the last k of
// its steps (k <= SwayHistory::kSteps), the summed median flow is
//  - large enough: at least kMinSway + k * kSwayPerStep pixels (the light's slow drift of a
//    print's corners never reaches it), plus the length of the view's summed motion taken off
//    the flow (an error of the view's motion moves a print's corrected corners as one),
//  - above the noise: kMinSwayOverNoise times the noise of that sum, and
//  - shared: each half's summed median moved along it by kMinHalfShare of it at least.
// The thresholds and what they were measured on are beside the code (liveness_cue.cpp); measure
// again with `mirror-eval liveness`. Nothing allocates; a SwayHistory is a fixed-size value.
#include "vision/geometry.hpp"
#include "vision/motion_model.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace vision {

/// The last flow steps of one face, as LivenessCue measures them.
class SwayHistory {
public:
    static constexpr int kSteps = 12;  ///< half a second at 25 frames per second

    struct Step {
        Point2f common{};                 ///< median flow of the face's corners
        std::array<Point2f, 4> halves{};  ///< of those left, right, above, below its centre
        float variance = 0.f;             ///< of the median flow, per axis
        Point2f view{};  ///< the view's motion at the face, which the flow was corrected by
    };

    void clear() noexcept { count_ = 0; }
    void push(const Step& step) noexcept;
    int size() const noexcept { return count_; }
    /// The k-th latest step (0: the latest), k < size().
    const Step& latest(int k) const noexcept;

private:
    std::array<Step, kSteps> steps_{};
    int next_ = 0;
    int count_ = 0;
};

class LivenessCue {
public:
    static constexpr int kMaxPairs = 64;  ///< corner pairs per step measured at most

    /// One flow step of a face: the pairs `from` -> `to` the motion fit saw, `inliers` its marks
    /// (1: inlier), `model` the fit, whose centre is the face's centre before the step, `view`
    /// the view's motion at the face that was taken off the flow (BackgroundMotion; zero when
    /// none). Adds the step to `history` when at least 3 inliers make it.
    void addFlowStep(SwayHistory& history, std::span<const Point2f> from,
                     std::span<const Point2f> to, std::span<const std::uint8_t> inliers,
                     const MotionModel& model, Point2f view = {}) noexcept;
    /// Whether the face's corners swayed together within its history (the header comment).
    static bool swayed(const SwayHistory& history) noexcept;
    /// Whether its latest step moved the median of its corners by kMinSway at least, further
    /// than a print's move in one step: a box full of foreground is motion only with it (the
    /// light changing fills a print's box too).
    static bool stirred(const SwayHistory& history) noexcept;

private:
    /// Median flow of the inliers on one side of the centre (`half` 0..3: left, right, above,
    /// below; -1: all). False when fewer than `least` corners are on that side.
    bool medianFlow(std::span<const Point2f> from, std::span<const Point2f> to,
                    std::span<const std::uint8_t> inliers, Point2f centre, int half, int least,
                    Point2f& flow) noexcept;

    std::array<float, kMaxPairs> dx_{};
    std::array<float, kMaxPairs> dy_{};
};

}  // namespace vision
