#pragma once
// FaceSmoother: steadies the faces the overlays are drawn on. The tracker's boxes jitter by a
// pixel or two from frame to frame; a hat drawn straight on them would shiver. Each face's centre,
// size and roll go through a One-Euro filter (the card's smoothing, §2): at rest the cutoff is
// low (no jitter), moving it rises with the speed (no visible lag). With the AAM (§5.3), a face
// whose fit holds also has its fitted yaw, pitch, roll, eye midpoint and size smoothed the same
// way (those filters start afresh after a frame the fit failed in: the face then has the 2D pose).
// Filters are kept per face id in fixed slots and forgotten when the face is dropped.
#include "vision/face_fit.hpp"
#include "vision/face_tracker.hpp"
#include "vision/one_euro_filter.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace firmware {

class FaceSmoother {
public:
    static constexpr int kMaxFaces = 16;

    /// Smooths `faces` (frame coordinates) taken at `timeNs`; the result (same order, points
    /// untouched) is valid until the next call. Never allocates.
    std::span<const vision::TrackedFace> apply(std::span<const vision::TrackedFace> faces,
                                               std::int64_t timeNs,
                                               std::span<const vision::FaceFit> fits = {}) noexcept;
    /// The fits of the faces of the last apply(), smoothed, in the same order (matched by face
    /// id; a face without a fit gets one that is not ok). Valid until the next call.
    std::span<const vision::FaceFit> fits() const noexcept { return {fitsOut_.data(), count_}; }

private:
    struct Slot {
        int faceId = 0;  ///< 0 = free
        bool seen = false;
        vision::OneEuroFilter x{1.0f, 0.02f}, y{1.0f, 0.02f}, size{0.7f, 0.01f}, roll{1.0f, 0.05f};
        // The fit's pose (§5.3): its angles as the roll's, its eyes and size as the box's.
        vision::OneEuroFilter yaw{1.0f, 0.05f}, pitch{1.0f, 0.05f}, fitRoll{1.0f, 0.05f};
        vision::OneEuroFilter eyeX{1.0f, 0.02f}, eyeY{1.0f, 0.02f}, fitSize{0.7f, 0.01f};
        void resetFit() noexcept
        {
            for (vision::OneEuroFilter* f : {&yaw, &pitch, &fitRoll, &eyeX, &eyeY, &fitSize})
                f->reset();
        }
    };
    Slot* slotFor(int faceId) noexcept;

    std::array<Slot, kMaxFaces> slots_{};
    std::array<vision::TrackedFace, kMaxFaces> out_{};
    std::array<vision::FaceFit, kMaxFaces> fitsOut_{};
    std::size_t count_ = 0;
    std::int64_t lastNs_ = 0;
};

}  // namespace firmware
