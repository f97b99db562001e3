#pragma once
// The whole card-tracking stage per frame, as the appliance runs it: chromaticity of the camera
// frame, then CardTracker::process. The frames are made in memory at start: a synthetic card
// (platform::CardSceneSource) moving over the benchmark photograph, with its true corners.

#include "vision/card_tracker.hpp"
#include "vision/chromaticity.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <memory>
#include <opencv2/core.hpp>
#include <vector>

namespace bench {

class CardTrackerCase {
public:
    /// `bgr`: the 720x480 BGR photograph; `frames`: length of the sequence (frame 0 trains).
    CardTrackerCase(const cv::Mat& bgr, int frames);

    /// Forgets the track and trains on frame 0 (the card's central region); the next step()
    /// processes frame 1.
    void restart();
    /// Chromaticity and CardTracker::process on the next frame; false once the sequence is done
    /// (call restart()).
    bool step();

    int frames() const { return static_cast<int>(frames_.size()); }
    /// Frames processed since restart().
    int processedFrames() const { return next_ - 1; }
    /// Frames (since restart) the tracker reported Tracking, and their mean corner error (px).
    int trackedFrames() const { return tracked_; }
    double meanCornerErrorPx() const { return tracked_ ? errorSum_ / (4.0 * tracked_) : 0.0; }

private:
    vision::ChromaticityPlanes planes();

    std::vector<vision::ImageBuffer> frames_;
    std::vector<vision::Quad> truth_;
    vision::ChromaticityTable table_;
    vision::ImageBuffer r_, g_, b_;
    std::unique_ptr<vision::CardTracker> tracker_;
    vision::Rect trainRegion_{};
    int next_ = 1;
    int tracked_ = 0;
    double errorSum_ = 0.0;
};

}  // namespace bench
