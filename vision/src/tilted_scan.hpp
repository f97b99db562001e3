#pragma once
// TiltedScan: FaceTracker's scan for faces that enter tilted beyond the upright cascade's reach
// (about +-15 degrees). The moving regions no track covers are turned by +tiltScanDegrees and
// -tiltScanDegrees (one angle per scan, alternating) and scanned upright there, within a window
// budget; a scan may take several frames. A cold start's scans (the whole image, in its frame)
// also turn by +-15 degrees, between upright and the tilt. Private to vision/src.
//
// Use: construct with the tracker's options (off when tiltScanDegrees is 0); each frame call
// run() after the upright scan; when completed(), hits() and hitRolls() hold the new faces (image
// boxes) and the angle that found each, the first guess of their roll.
#include "face_track.hpp"
#include "vision/face_detector.hpp"
#include "vision/face_tracker.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/image.hpp"
#include "vision/integral_image.hpp"

#include <array>
#include <limits>
#include <memory>
#include <span>
#include <vector>

namespace vision {

class TiltedScan {
public:
    /// What a tilted scan looks at: the working image, the upright scan's mask (Gray8, 255 =
    /// scannable) and its integral image, the live tracks, and whether the upright scan was a
    /// cold start's (the whole image in one frame; the tilted scans then also turn by +-15).
    struct Frame {
        ConstImageView gray;
        ConstImageView scanMask;
        const IntegralImage& scanMaskIntegral;
        std::span<const Track> tracks;
        bool coldStart = false;
    };

    /// Allocates the detector and buffers (nothing when options.tiltScanDegrees is 0).
    TiltedScan(const HaarCascade& cascade, const FaceTrackerOptions& options);

    /// A budget of no limit.
    static constexpr long kUnlimited = std::numeric_limits<long>::max();

    /// This frame's tilted scanning, with at most `budget` windows (kUnlimited: no limit; 0:
    /// none this frame). Returns the windows evaluated. Call it every frame.
    long run(const Frame& frame, long budget) noexcept;
    /// True when a tilted scan completed in the last run().
    bool completed() const noexcept { return done_; }
    /// The faces of the last completed scans, as axis-aligned image boxes, and their angles.
    std::span<const Rect> hits() const noexcept;
    std::span<const float> hitRolls() const noexcept;
    /// Forgets the scan in progress and the last hits.
    void reset() noexcept;

private:
    /// The motion mask of the scanned region is resampled to this square (the detector maps a
    /// mask of any resolution proportionally onto the image).
    static constexpr int kMaskSide = 64;
    /// This scan's rotation (cosine, sine) and the turned region's half sides.
    struct Turn {
        float c, n, hw, hh;
    };
    Turn turn() const noexcept;
    bool chooseRegion(const Frame& frame) noexcept;
    void markImageInRegion() noexcept;
    long step(const Frame& frame, long budget) noexcept;
    int excludeTracks(std::span<const Track> tracks) noexcept;
    void collectHits() noexcept;

    FaceTrackerOptions options_;
    std::unique_ptr<FaceDetector> detector_;  ///< null when off
    ImageBuffer gray_;  ///< the region turned upright at the scan's angle (top-left part)
    ImageBuffer mask_;  ///< the region's scan mask, resampled to kMaskSide squared
    IntegralImage maskIntegral_;
    bool active_ = false;   ///< a tilted scan is in progress over centre_ / size_
    Point2f centre_{};      ///< image point at the region's centre
    Size size_{};           ///< region in the turned image (pixels as the image's)
    float angle_ = 0.f;     ///< this scan's angle
    float nextSign_ = 1.f;  ///< the next scan turns by this sign times magnitude_
    float magnitude_ = 0.f;  ///< the next scan's angle without its sign (run() sets it)
    std::array<Rect, kMaxTracks> excluded_{};
    std::vector<Rect> hits_;       ///< the last completed tilted scan's faces (image boxes)
    std::vector<float> hitRolls_;  ///< the angle of the scan that found each
    int count_ = 0;
    bool done_ = false;   ///< a tilted scan completed this frame
    bool whole_ = false;  ///< this run() is a cold start's: the whole image, its part of it
};

}  // namespace vision
