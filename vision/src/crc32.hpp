#pragma once
// CRC-32 (IEEE 802.3, the polynomial zlib, PNG and gzip use; check value 0xCBF43926 for
// "123456789"). Written out here because vision links only the standard library and Eigen; it
// checks a model file once at start-up, so a byte-wise table is fast enough.

#include <cstddef>
#include <cstdint>
#include <span>

namespace vision {

std::uint32_t crc32(std::span<const std::byte> bytes) noexcept;

}  // namespace vision
