#pragma once
// The AAM fit's integer image kernels (§5; dissertation 5.3.4: integer images and dot products).
// Private to vision/src.
//
// Both run over the mean appearance frame's row spans, each row from its first to its last model
// pixel (no mask tests): a pixel between them outside the model (the mouth opening) has a zero
// mask, applied as a bitwise AND. The SIMD paths (NEON on aarch64, AVX2 on x86-64) give exactly the
// scalar path's integers: every sum is exact because no partial sum can overflow (bounds below), so
// the order of the additions does not matter. The tests compare every path with the scalar
// reference.

#include <cstdint>

namespace vision::aam {

/// The error image's bound: |error| <= kErrorLimit (1/16 grey levels: 255 grey levels and some).
inline constexpr int kErrorLimit = 4095;
/// Products summed in one int32 before they go into the int64 total: 64 * 4095 * 4095 < 2^31,
/// and the same for a steepest-descent image (|value| <= 2047).
inline constexpr int kDotChunk = 64;

/// error[i] = clamp(16 * warped[i] - ((gain * mean[i] + bias) >> 12), +-kErrorLimit) & mask[i]:
/// the warped image less the mean appearance under the current gain and bias, in 1/16 grey
/// levels (gain in grey levels * 256 per unit of mean, bias in grey levels * 65536).
void errorImage(const std::int16_t* warped, const std::int16_t* mean, const std::int16_t* mask,
                std::int32_t gain, std::int32_t bias, std::int16_t* error, int n) noexcept;

/// sum a[i] * b[i], exact, for |a[i]|, |b[i]| <= kErrorLimit.
std::int64_t dotProduct(const std::int16_t* a, const std::int16_t* b, int n) noexcept;

// The scalar reference of each (never vectorised), for the tests.
void errorImageScalar(const std::int16_t* warped, const std::int16_t* mean,
                      const std::int16_t* mask, std::int32_t gain, std::int32_t bias,
                      std::int16_t* error, int n) noexcept;
std::int64_t dotProductScalar(const std::int16_t* a, const std::int16_t* b, int n) noexcept;

/// The name of the path errorImage and dotProduct take on this machine ("neon", "avx2", "sse2").
const char* aamKernelPath() noexcept;

#if defined(__aarch64__)
void errorImageNeon(const std::int16_t* warped, const std::int16_t* mean, const std::int16_t* mask,
                    std::int32_t gain, std::int32_t bias, std::int16_t* error, int n) noexcept;
std::int64_t dotProductNeon(const std::int16_t* a, const std::int16_t* b, int n) noexcept;
#endif

}  // namespace vision::aam
