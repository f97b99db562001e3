#pragma once
// FaceSmoother: steadies the faces the overlays are drawn on. The tracker's boxes jitter by a
// pixel or two from frame to frame; a hat drawn straight on them would shiver. Each face's centre,
// size and roll go through a One-Euro filter (the card's smoothing, §2): at rest the cutoff is
// low (no jitter), moving it rises with the speed (no visible lag). Filters are kept per face id
// in fixed slots and forgotten when the face is dropped.
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
                                               std::int64_t timeNs) noexcept;

private:
    struct Slot {
        int faceId = 0;  ///< 0 = free
        bool seen = false;
        vision::OneEuroFilter x{1.0f, 0.02f}, y{1.0f, 0.02f}, size{0.7f, 0.01f}, roll{1.0f, 0.05f};
    };
    Slot* slotFor(int faceId) noexcept;

    std::array<Slot, kMaxFaces> slots_{};
    std::array<vision::TrackedFace, kMaxFaces> out_{};
    std::int64_t lastNs_ = 0;
};

}  // namespace firmware
