#pragma once
// ComponentLabeler: the largest 8-connected component of a Gray8 mask (step 4 of METHOD.md §2).
//
// Scanline labelling on runs: each row is cut into runs of non-zero pixels, a run is joined
// (union-find over run indices) with every run of the row above that touches it diagonally or
// directly, then areas are summed per root. A solid card is a few runs per row, so the cost is
// one pass over the mask plus work proportional to the number of runs. All buffers are sized for
// the worst case (every other pixel set) at construction.

#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <memory>

namespace vision {

/// One component: its pixel count, bounding box and per-row horizontal extent (rowMin/rowMax of
/// ComponentLabeler, -1 where the row has none of its pixels).
struct Component {
    int area = 0;
    Rect bounds{};
};

class ComponentLabeler {
public:
    explicit ComponentLabeler(Size size);
    ~ComponentLabeler();

    /// Labels `mask` (non-zero = set). Returns the number of components (0 when the mask is empty
    /// or of the wrong size).
    int label(const ConstImageView& mask) noexcept;

    /// After label(): the largest component (area 0 when there is none).
    Component largest() const noexcept;
    /// After label(): the object where it was, with the pieces an occluder cut off it. The anchor
    /// is the largest component whose bounding box intersects `near` (the largest of all when none
    /// does); added to it is every other component of at least `minArea` pixels whose bounding box
    /// lies inside `near` (a piece poking out of where the object can be is something else).
    /// Returns the selection's total area.
    Component selectNear(Rect near, int minArea) noexcept;
    /// After label(): selects only the largest component.
    Component selectLargest() noexcept;

    /// After a select...(): per row, the leftmost and rightmost x of a selected pixel (-1: none).
    const std::int16_t* rowMin() const noexcept { return rowMin_.get(); }
    const std::int16_t* rowMax() const noexcept { return rowMax_.get(); }
    int height() const noexcept { return size_.height; }

private:
    struct Run {
        std::int16_t x0, x1, y;
    };
    int find(int i) noexcept;
    void finishSelection(Component& c) noexcept;

    Size size_;
    int capacity_ = 0;
    int runCount_ = 0;
    int rootCount_ = 0;
    std::unique_ptr<Run[]> runs_;
    std::unique_ptr<std::int32_t[]> parent_;
    std::unique_ptr<std::int32_t[]> area_;      // per run index, valid at roots
    std::unique_ptr<Rect[]> box_;               // per run index, valid at roots
    std::unique_ptr<std::uint8_t[]> selected_;  // per run index, valid at roots
    std::unique_ptr<std::int32_t[]> rowStart_;  // first run of each row, plus one end entry
    std::unique_ptr<std::int16_t[]> rowMin_;
    std::unique_ptr<std::int16_t[]> rowMax_;
    int largestRoot_ = -1;
};

}  // namespace vision
