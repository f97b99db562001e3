#pragma once
// FaceSearch: fig. 89's "create face search mask" and "face detection on masked area" (METHOD.md
// §3, "Detection"): the upright Viola-Jones scan where there is motion or a face was seen
// recently, and no track is, within a per-frame window budget (a scan may take several frames).
// Until the first scan after construction or reset() completes (or the mask first marks
// something) it scans the whole image in one frame. Private to vision/src.
//
// Use: scan() once a frame; when completed(), hits() holds the new detections. mask() and
// maskIntegral() are this frame's search mask, for the tilted scans; remember() a dropped
// face's place so it is searched again.
#include "face_track.hpp"
#include "vision/face_detector.hpp"
#include "vision/face_tracker.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/image.hpp"
#include "vision/integral_image.hpp"

#include <array>
#include <span>
#include <vector>

namespace vision {

class FaceSearch {
public:
    /// What the scan looks at: the working image, the motion mask and its integral image (null:
    /// no mask, everything is scanned), the live tracks (their boxes are not scanned), the
    /// frame's index.
    struct Frame {
        ConstImageView gray;
        ConstImageView mask;
        const IntegralImage* motion;
        std::span<const Track> tracks;
        int frameIndex;
        long spent = 0;  ///< windows of this frame's budget already spent (EntryScan's)
    };

    /// Allocates the detector, the mask and the hit list.
    FaceSearch(const HaarCascade& cascade, const FaceTrackerOptions& options);

    /// This frame's part of the scan. Returns the windows evaluated.
    long scan(const Frame& frame) noexcept;
    /// True when a scan completed in the last scan().
    bool completed() const noexcept { return done_; }
    /// The faces of the last completed scan.
    std::span<const Rect> hits() const noexcept;
    /// True when the last scan() was a cold start's (the whole image, whatever the budget).
    bool wasCold() const noexcept { return cold_; }
    /// Windows the last scan() left of the frame's budget (a large number when it has none).
    long windowsLeft() const noexcept;
    /// Windows the last completed masked pass took over all its frames (0: none completed since
    /// construction or reset(), or no budget); what a pass of the whole mask costs now.
    long lastPassWindows() const noexcept { return lastPass_; }
    /// This frame's search mask (Gray8, 255 = scan here) and its integral image.
    ConstImageView mask() const noexcept { return mask_.view(); }
    const IntegralImage& maskIntegral() const noexcept { return maskIntegral_; }

    /// A shown face was dropped at `box`: its place is searched for recentFaceFrames frames.
    void remember(Rect box, int frameIndex) noexcept;
    /// Forgets the scan in progress, the hits and the remembered places; the next scan is cold.
    /// `wholeImage`: cold even where the mask marks motion (after a scene cut, where everything
    /// moves and every face in the new picture is new), in one frame.
    void reset(bool wholeImage = false) noexcept;

private:
    struct RecentArea {
        Rect box;
        int expires = 0;  ///< frame index after which the area is forgotten
    };

    void prepareMask(const Frame& frame) noexcept;
    int detect(const Frame& frame, std::span<const Rect> exclude) noexcept;

    FaceTrackerOptions options_;
    FaceDetector detector_;
    ImageBuffer mask_;
    IntegralImage maskIntegral_;
    /// Until the first scan after construction or reset() completes, or the motion mask first
    /// marks something, the whole image is scanned: nothing is known yet of what moves (a motion
    /// model that has seen one frame marks nothing), so every face is found and the static rule
    /// tells still from moving. A scan spread over frames by the window budget goes on masked
    /// once there is motion (a whole-image scan would keep a moving face waiting).
    bool coldStart_ = true;
    bool wholeImage_ = false;  ///< reset(true): the next scan is cold whatever moves
    bool cold_ = false;        ///< the last scan() was cold
    long budget_ = 0;          ///< the last scan()'s budget (0: none)
    long pass_ = 0;            ///< windows of the pass in progress so far
    long lastPass_ = 0;        ///< windows of the last completed masked pass (0: none yet)
    std::array<RecentArea, 16> recent_{};
    std::array<Rect, kMaxTracks> excluded_{};
    std::vector<Rect> hits_;  ///< the last completed scan's faces
    int count_ = 0;
    bool done_ = false;
};

}  // namespace vision
