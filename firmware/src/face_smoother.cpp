#include "firmware/face_smoother.hpp"

#include "vision/face_slots.hpp"

#include <algorithm>

namespace firmware {

FaceSmoother::Slot* FaceSmoother::slotFor(int faceId) noexcept
{
    return vision::slotForFace(slots_, faceId);
}

std::span<const vision::TrackedFace> FaceSmoother::apply(
    std::span<const vision::TrackedFace> faces, std::int64_t timeNs,
    std::span<const vision::FaceFit> fits) noexcept
{
    // Seconds since the last frame; the first frame and clock jumps get a nominal 30 fps step.
    float dt = lastNs_ != 0 ? static_cast<float>(timeNs - lastNs_) * 1e-9f : 1.f / 30.f;
    if (!(dt > 0.f && dt < 1.f))
        dt = 1.f / 30.f;
    lastNs_ = timeNs;
    for (Slot& s : slots_)
        s.seen = false;
    const std::size_t n = std::min(faces.size(), out_.size());
    for (std::size_t i = 0; i < n; ++i) {
        vision::TrackedFace f = faces[i];
        Slot* s = slotFor(f.id);
        if (s != nullptr) {
            s->seen = true;
            f.centre.x = s->x.filter(f.centre.x, dt);
            f.centre.y = s->y.filter(f.centre.y, dt);
            f.size = s->size.filter(f.size, dt);
            f.rollDegrees = s->roll.filter(f.rollDegrees, dt);
        }
        out_[i] = f;
        vision::FaceFit& fit = fitsOut_[i];
        const vision::FaceFit* measured = vision::fitFor(fits, f.id);
        if (measured != nullptr) {
            fit = *measured;
        } else {
            fit = vision::FaceFit{};
            fit.faceId = f.id;
        }
        if (s == nullptr)
            continue;
        if (!fit.ok()) {
            s->resetFit();
            continue;
        }
        fit.yawDegrees = s->yaw.filter(fit.yawDegrees, dt);
        fit.pitchDegrees = s->pitch.filter(fit.pitchDegrees, dt);
        fit.rollDegrees = s->fitRoll.filter(fit.rollDegrees, dt);
        fit.eyeMidpoint.x = s->eyeX.filter(fit.eyeMidpoint.x, dt);
        fit.eyeMidpoint.y = s->eyeY.filter(fit.eyeMidpoint.y, dt);
        fit.faceSize = s->fitSize.filter(fit.faceSize, dt);
    }
    count_ = n;
    for (Slot& s : slots_)
        if (!s.seen)
            s.faceId = 0;  // dropped: its filters start afresh if the id ever came back
    return {out_.data(), n};
}

}  // namespace firmware
