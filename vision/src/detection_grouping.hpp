#pragma once
// DetectionGrouping: FaceDetector's grouping of raw hits into faces (METHOD.md §3), as OpenCV's
// cv::groupRectangles and detectMultiScale do it. Working arrays are sized once; no allocation
// per call.

#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <span>
#include <vector>

namespace vision {

class DetectionGrouping {
public:
    /// Working arrays for up to `capacity` rectangles (more are ignored).
    explicit DetectionGrouping(int capacity);

    /// cv::groupRectangles(rects, minNeighbors, eps) into `out` (capacity out.size()); with
    /// minNeighbors <= 0, a copy of the rectangles. Returns the count.
    int group(std::span<const Rect> rects, int minNeighbors, double eps,
              std::span<Rect> out) noexcept;

    /// The faces of cv::CascadeClassifier::detectMultiScale from its raw hits: grouped with
    /// eps 0.2 (minNeighbors <= 0: the hits themselves), then clipped to `image`. Returns the
    /// count in `out`.
    int faces(std::span<const Rect> raw, int minNeighbors, Size image,
              std::span<Rect> out) noexcept;

private:
    void partition(std::span<const Rect> rects, double eps) noexcept;
    int averageClasses(std::span<const Rect> rects) noexcept;
    int keepSupported(int nclasses, int minNeighbors, double eps,
                      std::span<Rect> out) const noexcept;

    std::vector<int> parent_, label_, classCount_;
    std::vector<Rect> classSum_;
};

}  // namespace vision
