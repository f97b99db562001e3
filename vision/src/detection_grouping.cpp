// The grouping of raw hits as OpenCV 4.6 does it (cv::groupRectangles, then the clipping of
// cv::CascadeClassifier::detectMultiScale): rectangles are joined when all four edges lie within
// eps * (mean of the two smaller sides) of each other (SimilarRects), classes are the connected
// components numbered by first appearance (cv::partition), a class is averaged with its float
// mean rounded to nearest even and kept when it has more than minNeighbors members and does not
// lie inside a larger, better-supported class.

#include "detection_grouping.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace vision {
namespace {

constexpr double kDetectGroupEps = 0.2;  // detectMultiScale's grouping eps

}  // namespace

DetectionGrouping::DetectionGrouping(int capacity)
{
    const auto n = static_cast<std::size_t>(capacity);
    parent_.assign(n, 0);
    label_.assign(n, 0);
    classCount_.assign(n, 0);
    classSum_.assign(n, Rect{});
}

int DetectionGrouping::group(std::span<const Rect> rects, int minNeighbors, double eps,
                             std::span<Rect> out) noexcept
{
    const auto n = std::min(rects.size(), parent_.size());
    if (minNeighbors <= 0) {
        const auto m = std::min(n, out.size());
        std::copy_n(rects.begin(), m, out.begin());
        return static_cast<int>(m);
    }
    partition(rects.first(n), eps);
    const int nclasses = averageClasses(rects.first(n));
    return keepSupported(nclasses, minNeighbors, eps, out);
}

int DetectionGrouping::faces(std::span<const Rect> raw, int minNeighbors, Size image,
                             std::span<Rect> out) noexcept
{
    // A window at the last position can reach past the edge by the size rounding.
    const int n = group(raw, minNeighbors, kDetectGroupEps, out);
    int count = 0;
    for (int i = 0; i < n; ++i) {
        const Rect r = out[static_cast<std::size_t>(i)];
        const int x0 = std::max(r.x, 0);
        const int y0 = std::max(r.y, 0);
        const int x1 = std::min(r.x + r.width, image.width);
        const int y1 = std::min(r.y + r.height, image.height);
        if (x1 > x0 && y1 > y0)
            out[static_cast<std::size_t>(count++)] = {x0, y0, x1 - x0, y1 - y0};
    }
    return count;
}

// cv::partition with SimilarRects: union-find over the similarity graph, each root the smallest
// index of its component.
void DetectionGrouping::partition(std::span<const Rect> rects, double eps) noexcept
{
    const int n = static_cast<int>(rects.size());
    auto find = [&](int i) {
        while (parent_[static_cast<std::size_t>(i)] != i) {
            parent_[static_cast<std::size_t>(i)] =
                parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(i)])];
            i = parent_[static_cast<std::size_t>(i)];
        }
        return i;
    };
    for (int i = 0; i < n; ++i)
        parent_[static_cast<std::size_t>(i)] = i;
    for (int i = 0; i < n; ++i) {
        const Rect& a = rects[static_cast<std::size_t>(i)];
        for (int j = i + 1; j < n; ++j) {
            const Rect& b = rects[static_cast<std::size_t>(j)];
            const double delta =
                eps * (std::min(a.width, b.width) + std::min(a.height, b.height)) * 0.5;
            if (std::abs(a.x - b.x) <= delta && std::abs(a.y - b.y) <= delta &&
                std::abs(a.x + a.width - b.x - b.width) <= delta &&
                std::abs(a.y + a.height - b.y - b.height) <= delta) {
                const int ra = find(i);
                const int rb = find(j);
                if (ra != rb)
                    parent_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
            }
        }
    }
    for (int i = 0; i < n; ++i)
        parent_[static_cast<std::size_t>(i)] = find(i);
}

// Classes numbered by first appearance, each the mean of its rectangles; returns their count.
int DetectionGrouping::averageClasses(std::span<const Rect> rects) noexcept
{
    const int n = static_cast<int>(rects.size());
    int nclasses = 0;
    for (int i = 0; i < n; ++i) {
        const int root = parent_[static_cast<std::size_t>(i)];
        if (root == i) {
            label_[static_cast<std::size_t>(i)] = nclasses;
            classSum_[static_cast<std::size_t>(nclasses)] = {};
            classCount_[static_cast<std::size_t>(nclasses)] = 0;
            ++nclasses;
        } else {
            label_[static_cast<std::size_t>(i)] = label_[static_cast<std::size_t>(root)];
        }
        const int c = label_[static_cast<std::size_t>(i)];
        Rect& s = classSum_[static_cast<std::size_t>(c)];
        const Rect& r = rects[static_cast<std::size_t>(i)];
        s.x += r.x;
        s.y += r.y;
        s.width += r.width;
        s.height += r.height;
        ++classCount_[static_cast<std::size_t>(c)];
    }
    for (int c = 0; c < nclasses; ++c) {
        Rect& s = classSum_[static_cast<std::size_t>(c)];
        const float inv = 1.0f / static_cast<float>(classCount_[static_cast<std::size_t>(c)]);
        s = {static_cast<int>(std::lrint(static_cast<float>(s.x) * inv)),
             static_cast<int>(std::lrint(static_cast<float>(s.y) * inv)),
             static_cast<int>(std::lrint(static_cast<float>(s.width) * inv)),
             static_cast<int>(std::lrint(static_cast<float>(s.height) * inv))};
    }
    return nclasses;
}

// The classes with more than minNeighbors members that lie inside no larger, better-supported
// class, into `out`.
int DetectionGrouping::keepSupported(int nclasses, int minNeighbors, double eps,
                                     std::span<Rect> out) const noexcept
{
    int count = 0;
    for (int i = 0; i < nclasses; ++i) {
        const Rect r1 = classSum_[static_cast<std::size_t>(i)];
        const int n1 = classCount_[static_cast<std::size_t>(i)];
        if (n1 <= minNeighbors)
            continue;
        bool inside = false;
        for (int j = 0; j < nclasses && !inside; ++j) {
            const int n2 = classCount_[static_cast<std::size_t>(j)];
            if (j == i || n2 <= minNeighbors)
                continue;
            const Rect r2 = classSum_[static_cast<std::size_t>(j)];
            const int dx = static_cast<int>(std::lrint(r2.width * eps));
            const int dy = static_cast<int>(std::lrint(r2.height * eps));
            inside = r1.x >= r2.x - dx && r1.y >= r2.y - dy &&
                     r1.x + r1.width <= r2.x + r2.width + dx &&
                     r1.y + r1.height <= r2.y + r2.height + dy && (n2 > std::max(3, n1) || n1 < 3);
        }
        if (!inside && count < static_cast<int>(out.size()))
            out[static_cast<std::size_t>(count++)] = r1;
    }
    return count;
}

}  // namespace vision
