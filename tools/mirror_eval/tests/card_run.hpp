#pragma once
// The card tracker on frames rendered in memory by cardgen, scored as mirror-eval card scores
// (card_metrics.hpp): for tests of what the tracker must survive. Nothing is written to disk.

#include "card_metrics.hpp"
#include "scene.hpp"

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace card_test {

/// One frame to run: what it shows and its sensor noise seed.
using FrameSource = std::function<cardgen::FrameSpec(int index)>;

struct TrackerRun {
    mirror_eval::CardMetrics metrics;
    std::vector<mirror_eval::TrackedFrame> tracked;  ///< per frame of `frames`, in order
    std::vector<mirror_eval::TruthRow> truth;
    std::vector<int> frames;  ///< the scene's frame index of each entry
};

/// Renders `frames` (the first one trains: it must show the card filling the view) over
/// `background` and runs the firmware's card tracker (chromaticity, then CardTracker trained on
/// the whole of the first frame) on them in order, like mirror-eval card.
TrackerRun runFrames(const cv::Mat& background, const FrameSource& scene,
                     const std::vector<int>& frames, std::uint64_t noiseSeed = 1);

/// Frame 0, then `first` .. `last` of a cardgen scenario (its own background photograph).
TrackerRun runScenario(const std::string& scenario, std::uint32_t seed, int first, int last,
                       int length = 240);

/// "frame:error" or "frame:lost(problem)" for every scored frame not within 3 px: for messages.
std::string misses(const TrackerRun& run);

}  // namespace card_test
