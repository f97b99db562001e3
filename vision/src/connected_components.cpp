#include "vision/connected_components.hpp"

#include <algorithm>
#include <cstring>

namespace vision {

ComponentLabeler::ComponentLabeler(Size size)
    : size_(size),
      capacity_(((size.width + 1) / 2) * size.height + 1),
      runs_(std::make_unique<Run[]>(static_cast<std::size_t>(capacity_))),
      parent_(std::make_unique<std::int32_t[]>(static_cast<std::size_t>(capacity_))),
      area_(std::make_unique<std::int32_t[]>(static_cast<std::size_t>(capacity_))),
      box_(std::make_unique<Rect[]>(static_cast<std::size_t>(capacity_))),
      selected_(std::make_unique<std::uint8_t[]>(static_cast<std::size_t>(capacity_))),
      rowStart_(std::make_unique<std::int32_t[]>(static_cast<std::size_t>(size.height) + 1)),
      rowMin_(std::make_unique<std::int16_t[]>(static_cast<std::size_t>(size.height))),
      rowMax_(std::make_unique<std::int16_t[]>(static_cast<std::size_t>(size.height)))
{
}

ComponentLabeler::~ComponentLabeler() = default;

int ComponentLabeler::find(int i) noexcept
{
    while (parent_[i] != i) {
        parent_[i] = parent_[parent_[i]];  // path halving
        i = parent_[i];
    }
    return i;
}

int ComponentLabeler::label(const ConstImageView& mask) noexcept
{
    runCount_ = 0;
    rootCount_ = 0;
    largestRoot_ = -1;
    if (mask.empty() || mask.size() != size_) {
        for (int y = 0; y <= size_.height; ++y)
            rowStart_[y] = 0;
        return 0;
    }
    const int w = size_.width;
    int prevStart = 0, prevEnd = 0;
    for (int y = 0; y < size_.height; ++y) {
        const std::uint8_t* p = mask.row(y);
        rowStart_[y] = runCount_;
        int x = 0;
        while (x < w) {
            // Skip zeros eight at a time: most of a frame is background.
            while (x + 8 <= w) {
                std::uint64_t word;
                std::memcpy(&word, p + x, 8);
                if (word != 0)
                    break;
                x += 8;
            }
            while (x < w && p[x] == 0)
                ++x;
            if (x >= w)
                break;
            const int x0 = x;
            while (x < w && p[x] != 0)
                ++x;
            const int idx = runCount_++;
            runs_[idx] = {static_cast<std::int16_t>(x0), static_cast<std::int16_t>(x - 1),
                          static_cast<std::int16_t>(y)};
            parent_[idx] = idx;
            // 8-connectivity: runs of the row above overlapping [x0 - 1, x].
            for (int j = prevStart; j < prevEnd; ++j) {
                if (runs_[j].x1 < x0 - 1)
                    continue;
                if (runs_[j].x0 > x)
                    break;
                const int a = find(idx), b = find(j);
                if (a != b) {
                    // The older root survives so roots stay the first run of their component.
                    if (a < b)
                        parent_[b] = a;
                    else
                        parent_[a] = b;
                }
            }
        }
        prevStart = rowStart_[y];
        prevEnd = runCount_;
    }
    rowStart_[size_.height] = runCount_;

    // Areas and boxes per root.
    int best = -1;
    for (int i = 0; i < runCount_; ++i) {
        const Run& r = runs_[i];
        const int root = find(i);
        parent_[i] = root;  // full compression: later passes read roots directly
        const int len = r.x1 - r.x0 + 1;
        if (root == i) {
            ++rootCount_;
            area_[i] = len;
            box_[i] = {r.x0, r.y, r.x1 + 1, r.y + 1};  // x0, y0, x1, y1 while accumulating
        } else {
            area_[root] += len;
            Rect& b = box_[root];
            b.x = std::min<int>(b.x, r.x0);
            b.width = std::max<int>(b.width, r.x1 + 1);
            b.height = std::max<int>(b.height, r.y + 1);
        }
    }
    for (int i = 0; i < runCount_; ++i) {
        if (parent_[i] != i)
            continue;
        Rect& b = box_[i];
        b = {b.x, b.y, b.width - b.x, b.height - b.y};
        if (best < 0 || area_[i] > area_[best])
            best = i;
    }
    largestRoot_ = best;
    return rootCount_;
}

Component ComponentLabeler::largest() const noexcept
{
    if (largestRoot_ < 0)
        return {};
    return {area_[largestRoot_], box_[largestRoot_]};
}

void ComponentLabeler::finishSelection(Component& c) noexcept
{
    for (int y = 0; y < size_.height; ++y) {
        rowMin_[y] = -1;
        rowMax_[y] = -1;
    }
    c.area = 0;
    int x0 = size_.width, y0 = size_.height, x1 = -1, y1 = -1;
    for (int i = 0; i < runCount_; ++i) {
        const int root = parent_[i];  // fully compressed by label(): every run points at its root
        if (!selected_[root])
            continue;
        const Run& r = runs_[i];
        const int y = r.y;
        if (rowMin_[y] < 0 || r.x0 < rowMin_[y])
            rowMin_[y] = r.x0;
        if (r.x1 > rowMax_[y])
            rowMax_[y] = r.x1;
        c.area += r.x1 - r.x0 + 1;
        x0 = std::min<int>(x0, r.x0);
        x1 = std::max<int>(x1, r.x1);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
    }
    c.bounds = c.area > 0 ? Rect{x0, y0, x1 - x0 + 1, y1 - y0 + 1} : Rect{};
}

Component ComponentLabeler::selectLargest() noexcept
{
    for (int i = 0; i < runCount_; ++i)
        selected_[i] = static_cast<std::uint8_t>(i == largestRoot_);
    Component c;
    finishSelection(c);
    return c;
}

Component ComponentLabeler::selectNear(Rect near, int minArea) noexcept
{
    auto meets = [&near](const Rect& b) {
        return b.x < near.x + near.width && near.x < b.x + b.width && b.y < near.y + near.height &&
               near.y < b.y + b.height;
    };
    auto inside = [&near](const Rect& b) {
        return b.x >= near.x && b.y >= near.y && b.x + b.width <= near.x + near.width &&
               b.y + b.height <= near.y + near.height;
    };
    int anchor = -1;
    for (int i = 0; i < runCount_; ++i)
        if (parent_[i] == i && meets(box_[i]) && (anchor < 0 || area_[i] > area_[anchor]))
            anchor = i;
    if (anchor < 0)
        anchor = largestRoot_;
    for (int i = 0; i < runCount_; ++i)
        selected_[i] = static_cast<std::uint8_t>(
            parent_[i] == i && (i == anchor || (inside(box_[i]) && area_[i] >= minArea)));
    Component c;
    finishSelection(c);
    return c;
}

}  // namespace vision
