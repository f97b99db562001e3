#pragma once
// FaceDetector: Viola-Jones face detection (METHOD.md §3) with an OpenCV Haar cascade. It gives
// the same boxes as cv::CascadeClassifier::detectMultiScale (OpenCV 4.6) with the same cascade and
// parameters, in integer arithmetic, and allocates nothing per frame.
//
// Modes: full scan (detect), masked scan (detectMasked: windows with too little mask, or whose
// centre lies in an excluded box, are skipped), the same scan spread over frames under a window
// budget (detectMaskedIncremental) and first hit (detectFirst: stops at the first window that
// passes, for verifying a track on a small upright patch).

#include "vision/geometry.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/image.hpp"
#include "vision/integral_image.hpp"

#include <memory>
#include <span>

namespace vision {

struct FaceDetectorOptions {
    Size maxFrameSize{360, 240};  ///< largest image detect() accepts (buffers are sized for it)
    double scaleFactor = 1.1;     ///< > 1
    int minNeighbors = 3;         ///< a group needs more than this many raw hits; 0: no grouping
    Size minSize{0, 0};           ///< smallest face box
    Size maxSize{0, 0};           ///< largest face box; 0 = the image size
    int maxRawHits = 8192;        ///< capacity of the raw hit list (extra hits are dropped)
    int maxFaces = 128;           ///< capacity of the grouped result
};

class FaceDetector {
public:
    /// Converts the cascade to fixed point and allocates every buffer (start-up). Throws
    /// std::runtime_error on a cascade it cannot evaluate (tilted features, non-integer
    /// rectangle weights) or bad options.
    FaceDetector(const HaarCascade& cascade, const FaceDetectorOptions& options);
    ~FaceDetector();
    FaceDetector(FaceDetector&&) noexcept;
    FaceDetector& operator=(FaceDetector&&) noexcept;

    /// Full scan of a Gray8 image no larger than maxFrameSize. Returns the number of faces
    /// (grouped), or -1 on a bad image (lastError()).
    int detect(const ConstImageView& gray) noexcept;

    /// Masked scan: a window is evaluated only when the mean of `mask` (0/255, its integral
    /// image; any resolution, mapped proportionally onto the image) over it is at least
    /// minFraction, and its centre lies in none of `exclude` (image coordinates).
    int detectMasked(const ConstImageView& gray, const IntegralImage& mask, float minFraction,
                     std::span<const Rect> exclude) noexcept;

    /// The masked scan spread over several frames so that no frame stalls on detection: each
    /// call evaluates at most `windowBudget` windows (0: no limit, the whole scan in this call)
    /// of `gray`, continuing the scan (scale, row, window) where the previous call stopped, and
    /// accumulates the raw hits. `gray` is a new frame each call: the current scale is shrunk
    /// from it (and only when one of its windows is evaluated). `mask` null: no masking;
    /// `exclude` applies either way. Returns true when the scan completed in this call: faces()
    /// then holds the grouped result of the whole scan (until then, that of the previous one)
    /// and the next call starts a new scan. False while in progress, and on a bad image or
    /// mask (lastError(); the scan is abandoned).
    /// Guarantee: windowsEvaluated() after a call is <= windowBudget (the scan may stop inside
    /// a row); masked-out and excluded windows are not counted. Work beyond that is bounded by
    /// one row: the row prefilter's first stages for the rest of the row where the call stops,
    /// and shrinking the current scale once per call. A call with a different image
    /// size starts a new scan; detect(), detectMasked() and detectFirst() abandon it.
    bool detectMaskedIncremental(const ConstImageView& gray, const IntegralImage* mask,
                                 float minFraction, std::span<const Rect> exclude,
                                 long windowBudget) noexcept;
    /// Abandons an incremental scan in progress: the next detectMaskedIncremental() starts anew.
    void resetIncremental() noexcept;
    /// True while an incremental scan is in progress (started, not completed).
    bool incrementalScanActive() const noexcept;

    /// Coarse to fine (a cold start's scan of a whole image): every scale as detectMasked()
    /// scans it, but first only every other window of every other row (a coarse grid) through
    /// the cascade's first stages; a window of the full grid is then decided, exactly as
    /// detectMasked() decides it, only when it is, or is next to (one step along a row, a
    /// column or both), a coarse window that passed them. A face gives a cluster of raw hits
    /// whose neighbours pass the first stages, so this finds the faces of the full scan at a
    /// fraction of its windows: its raw hits are those of the full scan near the coarse
    /// windows that passed, in the same order (a window the full scan skips after a
    /// first-stage rejection, as OpenCV's does, is skipped here too), and the same grouping
    /// makes the faces. `mask` null: no masking.
    /// Returns the number of faces, or -1 on a bad image or mask. Abandons an incremental scan.
    int detectCoarseToFine(const ConstImageView& gray, const IntegralImage* mask, float minFraction,
                           std::span<const Rect> exclude) noexcept;

    /// First hit: scans like detect() and returns true at the first window that passes the
    /// cascade, with its box in `hit` (no grouping).
    bool detectFirst(const ConstImageView& gray, Rect& hit) noexcept;

    /// Grouped faces of the last detect()/detectMasked(), clipped to the image like OpenCV's
    /// (with minNeighbors 0: the raw hits, clipped, up to maxFaces).
    std::span<const Rect> faces() const noexcept;
    /// Raw hits (every window that passed) of the last scan (so far, during an incremental
    /// one), in OpenCV's order, not clipped:
    /// the last window of a row can reach a pixel past the image by the size rounding.
    std::span<const Rect> rawHits() const noexcept;
    /// True when the last scan found more raw hits than maxRawHits.
    bool rawHitsOverflowed() const noexcept;
    /// Windows evaluated by the last scan (after masking); for detectMaskedIncremental(), by
    /// the last call.
    long windowsEvaluated() const noexcept;

    /// The cascade's window (width, height): the smallest face box.
    Size windowSize() const noexcept;
    const char* lastError() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vision
