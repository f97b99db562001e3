#include "card_shape_model.hpp"

#include <algorithm>
#include <cmath>

namespace vision {

namespace {

/// The cyclic shift s pairing a[(i + s) % 4] with b[i] at the least summed squared distance.
int bestShift(const Quad& a, const Quad& b) noexcept
{
    int shift = 0;
    float best = 1e30f;
    for (int s = 0; s < 4; ++s) {
        float d = 0.f;
        for (int i = 0; i < 4; ++i) {
            const float dx = a[(i + s) % 4].x - b[i].x, dy = a[(i + s) % 4].y - b[i].y;
            d += dx * dx + dy * dy;
        }
        if (d < best) {
            best = d;
            shift = s;
        }
    }
    return shift;
}

}  // namespace

float quadDistance(const Quad& a, const Quad& b) noexcept
{
    const int s = bestShift(a, b);
    float worst = 0.f;
    for (int i = 0; i < 4; ++i)
        worst = std::max(worst, std::hypot(a[(i + s) % 4].x - b[i].x, a[(i + s) % 4].y - b[i].y));
    return worst;
}

void CardShapeModel::track(const Quad& raw, float area, float aspect, unsigned missed, bool whole,
                           bool measured) noexcept
{
    velocity_ = {};
    speed_ = 0.f;
    if (haveLast_ && measured && lastMeasured_) {
        // Per frame over the frames since the last track; a jump of a quarter of the card's size
        // is a new track, not motion.
        const int s = bestShift(raw, last_);
        const float frames = static_cast<float>(missed + 1);
        Quad v;
        float fastest = 0.f;
        for (int i = 0; i < 4; ++i) {
            const int j = (i + s) % 4;
            v[j] = {(raw[j].x - last_[i].x) / frames, (raw[j].y - last_[i].y) / frames};
            fastest = std::max(fastest, std::hypot(v[j].x, v[j].y));
        }
        if (fastest < 0.25f * std::sqrt(std::max(area, 1.f))) {
            velocity_ = v;
            speed_ = fastest;
        }
    }
    last_ = raw;
    lastArea_ = area;
    lastMeasured_ = measured;
    haveLast_ = true;
    // The shape to recover to is one seen whole: not a card half out of the frame.
    if (whole || !haveGood_) {
        goodArea_ = area;
        goodAspect_ = aspect;
        haveGood_ = true;
    }
}

Quad CardShapeModel::predicted(unsigned missed) const noexcept
{
    const float k = static_cast<float>(missed + 1);
    Quad q;
    for (int i = 0; i < 4; ++i)
        q[i] = {last_[i].x + k * velocity_[i].x, last_[i].y + k * velocity_[i].y};
    return q;
}

Rect CardShapeModel::expectedBounds(unsigned missed) const noexcept
{
    const Quad q = predicted(missed);
    float x0 = q[0].x, x1 = q[0].x, y0 = q[0].y, y1 = q[0].y;
    for (const Point2f& p : q) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
    }
    // A constant-velocity guess is off by about the last motion (the card speeds up, slows
    // down, turns), more the more frames it spans.
    const float margin =
        8.f + 0.06f * std::sqrt(std::max(lastArea_, 1.f)) + static_cast<float>(missed + 1) * speed_;
    const int ix0 = static_cast<int>(std::floor(x0 - margin));
    const int iy0 = static_cast<int>(std::floor(y0 - margin));
    const int ix1 = static_cast<int>(std::ceil(x1 + margin));
    const int iy1 = static_cast<int>(std::ceil(y1 + margin));
    return {ix0, iy0, ix1 - ix0 + 1, iy1 - iy0 + 1};
}

float CardShapeModel::tolerance() const noexcept
{
    return std::max(4.f, 0.04f * std::sqrt(std::max(lastArea_, 1.f)));
}

float CardShapeModel::edgeGuide(unsigned missed) const noexcept
{
    const float k = static_cast<float>(missed + 1);
    return k * (6.f + 0.05f * std::sqrt(std::max(lastArea_, 1.f)) + 0.5f * speed_);
}

}  // namespace vision
