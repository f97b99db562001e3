#pragma once
// A cheap integer hash for deterministic per-pixel noise in the synthetic scenes: the same
// (x, y, z) always gives the same value, so generated frames are reproducible byte for byte.

#include <cstdint>

namespace platform {

inline std::uint32_t noiseHash(std::uint32_t x, std::uint32_t y, std::uint32_t z = 0) noexcept
{
    std::uint32_t h = x * 0x9E3779B1u ^ y * 0x85EBCA77u ^ (z + 0x165667B1u) * 0xC2B2AE3Du;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    h *= 0x297A2D39u;
    h ^= h >> 15;
    return h;
}

}  // namespace platform
