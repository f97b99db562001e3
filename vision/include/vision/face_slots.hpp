#pragma once
// Per-face state kept in a fixed array of slots, found by the face's track id: no allocation per
// frame. A slot type has an `int faceId` member, 0 when the slot is free.

#include <array>
#include <cstddef>

namespace vision {

/// The slot holding `faceId`, else the first free one, reset to a fresh Slot{} holding it;
/// nullptr when every slot is taken.
template <typename Slot, std::size_t N>
Slot* slotForFace(std::array<Slot, N>& slots, int faceId) noexcept
{
    Slot* free = nullptr;
    for (Slot& s : slots) {
        if (s.faceId == faceId)
            return &s;
        if (s.faceId == 0 && free == nullptr)
            free = &s;
    }
    if (free != nullptr) {
        *free = Slot{};
        free->faceId = faceId;
    }
    return free;
}

}  // namespace vision
