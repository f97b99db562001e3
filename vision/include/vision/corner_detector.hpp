#pragma once
// Shi-Tomasi corners inside a rectangle (METHOD.md §3 "Tracking" and §4), the method of
// cv::goodFeaturesToTrack: 3x3 Sobel gradients in int16, the structure tensor summed over a
// blockSize x blockSize box in int32, its smaller eigenvalue as the score; scores under
// qualityLevel x the best one are dropped, the rest must be 3x3 local maxima; then, strongest
// first, a corner is kept when no kept corner lies within minDistance.

#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <memory>

namespace vision {

struct CornerDetectorOptions {
    int maxCorners = 50;         ///< most corners returned (also the output capacity needed)
    float qualityLevel = 0.01f;  ///< fraction of the best score a corner must reach
    float minDistance = 5.f;     ///< pixels between kept corners (set per face from its size)
    int blockSize = 3;           ///< side of the structure tensor's box (odd, 3..7)
};

/// A corner and its score (the smaller eigenvalue of the structure tensor, in Sobel units).
struct Corner {
    Point2f position{};
    float score = 0.f;
};

/// Finds corners in a rectangle of a Gray8 image. The constructor sizes every buffer for the
/// largest image it will see; detect() never allocates.
class CornerDetector {
public:
    /// Throws std::runtime_error on an empty size or bad options.
    CornerDetector(Size maxImage, const CornerDetectorOptions& options = {});

    const CornerDetectorOptions& options() const noexcept { return options_; }
    void setMinDistance(float pixels) noexcept { options_.minDistance = pixels; }
    void setMaxCorners(int count) noexcept;

    /// Corners inside `area` (clipped to the image; pixels within 2 of the image border are not
    /// scored), strongest first, at most min(maxCorners, capacity) written to `out`. Returns the
    /// count; 0 on a wrong format or an image larger than the constructor's size.
    int detect(ConstImageView gray, Rect area, Corner* out, int capacity) noexcept;

private:
    /// Ring slot `slot` (of 2r + 1): a gradient row's products summed over the block's columns,
    /// the three planes xx, xy, yy one after the other (maxImage width apart).
    std::int32_t* ringRow(int slot) noexcept;
    /// The products dx dx, dx dy, dy dy of one gradient row summed over `side` columns, for
    /// `width` scored pixels, into `out` (a ring slot).
    void sumBlockColumns(const std::int16_t* dx, const std::int16_t* dy, int width, int side,
                         std::int32_t* out) noexcept;
    /// The smaller eigenvalue of the tensor summed over the ring's `side` rows, for `width`
    /// pixels into `out`; returns the row's largest.
    float scoreRow(int side, float* out, int width) noexcept;

    struct Candidate {
        float score;
        std::int32_t index;  ///< y * areaWidth + x within the clipped area
    };

    CornerDetectorOptions options_;
    Size maxImage_{};
    std::unique_ptr<std::int16_t[]> dx_;       ///< Sobel x over the area and a rim
    std::unique_ptr<std::int16_t[]> dy_;       ///< Sobel y over the area and a rim
    std::unique_ptr<float[]> score_;           ///< min eigenvalue per area pixel
    std::unique_ptr<Candidate[]> candidates_;  ///< local maxima above the quality threshold
    std::unique_ptr<std::int32_t[]> ring_;     ///< block column sums of up to 7 gradient rows
    std::unique_ptr<std::int32_t[]> tensor_;   ///< a score row's tensor sums (xx, xy, yy)
};

}  // namespace vision
