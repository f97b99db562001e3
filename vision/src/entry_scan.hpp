#pragma once
// EntryScan: FaceTracker's scan of the image's edge bands where something moves and no track is,
// first in each frame's window budget (METHOD.md §3, "Detection"). A face coming into view
// enters through an edge; the budgeted scan of the whole search mask reaches it only when its
// turn comes (about two frames with the shipped budget, more for the tilted scans), so it was in
// view unshown for frames. The band along each edge (left, right, top, bottom) with moving
// untracked cells, one of them on the edge itself, is scanned on its own before the rest of the
// mask, upright and turned by +-tiltScanDegrees (as TiltedScan turns the moving regions: a face
// may come in tilted); its windows come out of the same budget. Private to vision/src.
//
// Use: construct with the tracker's options (off without a window budget, where every frame's
// scan is whole anyway); each frame call run() before the upright scan with the share of the
// budget it may take, and give the upright scan what it left; when completed(), hits() holds the
// faces of the bands scanned to the end this frame (image boxes).
#include "face_track.hpp"
#include "vision/face_detector.hpp"
#include "vision/face_tracker.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/image.hpp"
#include "vision/integral_image.hpp"

#include <array>
#include <memory>
#include <span>
#include <vector>

namespace vision {

class EntryScan {
public:
    /// What the scan looks at: the working image, the motion mask (Gray8, 255 = moving) and its
    /// integral image, the live tracks.
    struct Frame {
        ConstImageView gray;
        ConstImageView motionMask;
        const IntegralImage& motionIntegral;
        std::span<const Track> tracks;
    };

    /// Allocates the detector and buffers (nothing when options.detectionWindowBudget is 0).
    EntryScan(const HaarCascade& cascade, const FaceTrackerOptions& options);

    /// Whether the scan runs at all (a window budget, tracking on).
    bool enabled() const noexcept { return detector_ != nullptr; }
    /// This frame's edge-band scanning with at most `budget` windows (> 0). Returns the
    /// windows evaluated. Call it every frame (a band's scan may continue on the next).
    long run(const Frame& frame, long budget) noexcept;
    /// True when a band's scan completed in the last run().
    bool completed() const noexcept { return done_; }
    /// The faces of the bands completed in the last run(), as image boxes.
    std::span<const Rect> hits() const noexcept;
    std::span<const float> hitRolls() const noexcept;
    /// Forgets the scan in progress and the hits.
    void reset() noexcept;

private:
    /// The motion mask of the scanned region is resampled to this square.
    static constexpr int kMaskSide = 64;
    static constexpr int kEdges = 4;  ///< left, right, top, bottom
    static constexpr int kLooks = 3;  ///< upright, +tilt, -tilt

    bool chooseRegion(const Frame& frame, int edge) noexcept;
    bool turnRegion(int look) noexcept;
    long step(const Frame& frame, long budget) noexcept;
    int excludeTracks(std::span<const Track> tracks) noexcept;
    void collectHits() noexcept;

    FaceTrackerOptions options_;
    std::unique_ptr<FaceDetector> detector_;  ///< null when off
    ImageBuffer gray_;                        ///< a turned look's region (top-left part)
    ImageBuffer mask_;  ///< the region's motion mask, resampled to kMaskSide squared
    IntegralImage maskIntegral_;
    bool active_ = false;  ///< a look's scan is in progress over region_
    Rect region_{};        ///< the band's moving part, in the image
    float angle_ = 0.f;    ///< the look's angle
    Size turned_{};        ///< the turned region's size (a turned look's)
    int job_ = 0;          ///< edge * kLooks + look: scanned next (or now, when active_)
    std::array<Rect, kMaxTracks> excluded_{};
    std::vector<Rect> hits_;
    std::vector<float> hitRolls_;
    int count_ = 0;
    bool done_ = false;
};

}  // namespace vision
