#pragma once
// Scores a card tracker's per-frame output against the ground truth (truth_file.hpp). Pure
// computation: mirror-eval card feeds it the tracker's frames; tests feed it made-up ones.
//
// Which frames count:
//  - frames before `firstScored` are not scored (frame 0 trains the colour model);
//  - a frame is *scored* when the truth has a card with at least 3 corners inside the image: with
//    one corner out, both edges through it are still visible, so the corner is determined by the
//    image; with two or more out a whole edge is unseen and no tracker can know the quad;
//  - *fully visible*: all 4 corners inside the image (recovery is timed from there).
// Corner errors are Euclidean distances between matching corners (both clockwise from the
// top-left), pooled over the 4 corners of every scored frame in which the tracker tracks.
// "Top-left" is the corner with the smallest x + y; when two corners of the truth tie on it (a
// card turned 45 degrees) either may be the first, and the tracker's labelling is matched to the
// one nearer its quad (matchedCornerErrors).

#include "truth_file.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <string>
#include <vector>

namespace mirror_eval {

/// What the tracker said about one frame.
struct TrackedFrame {
    bool tracking = false;  ///< state Tracking with a quad
    vision::Quad quad{};
    const char* problem = "";  ///< the tracker's reason when not tracking (a static string)
};

struct CardEvalSettings {
    vision::Size frameSize;
    int firstScored = 1;            ///< frame 0 trains
    float withinPx = 3.0f;          ///< "all corners within" threshold
    float cornerTiePx = 6.0f;       ///< truth first corners this close in x + y are a tie
    int restSettleFrames = 5;       ///< frames at the start of a static stretch not counted
    int minRestFrames = 5;          ///< frames a static stretch needs (after settling)
    float restTolerancePx = 0.01f;  ///< truth corners moving less than this are at rest
};

struct CardMetrics {
    int frames = 0;          ///< all frames (truth rows)
    int scoredFrames = 0;    ///< see above
    int partialFrames = 0;   ///< truth card with 2+ corners outside the image (not scored)
    int absentFrames = 0;    ///< truth without card (frames >= firstScored)
    int measuredFrames = 0;  ///< scored frames in which the tracker tracks
    double meanErrPx = 0.0;  ///< NaN when nothing was measured
    double p95ErrPx = 0.0;
    double maxErrPx = 0.0;
    int withinFrames = 0;  ///< scored frames with all 4 corners within withinPx
    double withinFraction = 0.0;
    int lostFrames = 0;  ///< scored frames not tracking
    /// Runs of lost frames: a run starts at a scored frame not tracking and ends at the next
    /// tracking frame (unscored frames in between, with the card mostly out, do not end it).
    int lostStretches = 0;
    int falseTrackingFrames = 0;  ///< tracking while the truth has no card
    int recoveries = 0;           ///< stretches of no card / no track that ended in tracking
    int unrecovered = 0;          ///< such stretches still open at the end of the sequence
    int maxRecoverFrames = 0;     ///< frames from the card fully visible again to tracking again
    double meanRecoverFrames = 0.0;
    int restRuns = 0;       ///< static stretches measured
    double jitterPx = 0.0;  ///< mean over static stretches of the RMS corner deviation
    double maxJitterPx = 0.0;
};

/// Distances from each corner of `found` to its truth corner, both clockwise from the corner with
/// the smallest x + y. When another truth corner's x + y is within `tiePx` of that smallest, the
/// truth is also labelled from it and the labelling with the smaller largest error is used.
void matchedCornerErrors(const vision::Quad& found, const vision::Quad& truth, float tiePx,
                         double errors[4]) noexcept;

/// Scores `tracked` (one entry per frame) against `truth` (same length; throws
/// std::invalid_argument otherwise).
CardMetrics computeCardMetrics(const std::vector<TruthRow>& truth,
                               const std::vector<TrackedFrame>& tracked,
                               const CardEvalSettings& settings);

/// The last line of mirror-eval card: "card: mean_err_px=%.2f p95_err_px=%.2f within3px=%.3f
/// lost_frames=%d" and extra fields after those.
std::string cardSummaryLine(const CardMetrics& m);

/// The human-readable lines before it.
std::string cardReport(const CardMetrics& m);

}  // namespace mirror_eval
