// The AAM fit's integer kernels: the scalar reference, the plain loops the compiler vectorises
// (AVX2 on x86-64 when the CPU has it), and the choice of path (aam_kernels.hpp).
#include "aam_kernels.hpp"

#include "simd.hpp"

#include <algorithm>

namespace vision::aam {

namespace {

MIRROR_SIMD_BODY void errorBody(const std::int16_t* warped, const std::int16_t* mean,
                                const std::int16_t* mask, std::int32_t gain, std::int32_t bias,
                                std::int16_t* error, int n) noexcept
{
    for (int i = 0; i < n; ++i) {
        const std::int32_t model = (gain * mean[i] + bias) >> 12;
        const std::int32_t e = std::clamp(16 * warped[i] - model, -kErrorLimit, kErrorLimit);
        error[i] = static_cast<std::int16_t>(e & mask[i]);
    }
}

MIRROR_SIMD_BODY std::int64_t dotBody(const std::int16_t* a, const std::int16_t* b, int n) noexcept
{
    std::int64_t total = 0;
    for (int start = 0; start < n; start += kDotChunk) {
        const int end = std::min(n, start + kDotChunk);
        std::int32_t chunk = 0;
        for (int i = start; i < end; ++i)
            chunk += a[i] * b[i];
        total += chunk;
    }
    return total;
}

#if defined(MIRROR_AVX2)
MIRROR_AVX2 void errorImageAvx2(const std::int16_t* warped, const std::int16_t* mean,
                                const std::int16_t* mask, std::int32_t gain, std::int32_t bias,
                                std::int16_t* error, int n) noexcept
{
    errorBody(warped, mean, mask, gain, bias, error, n);
}
MIRROR_AVX2 std::int64_t dotProductAvx2(const std::int16_t* a, const std::int16_t* b,
                                        int n) noexcept
{
    return dotBody(a, b, n);
}
#endif

}  // namespace

__attribute__((optimize("no-tree-vectorize"))) void errorImageScalar(
    const std::int16_t* warped, const std::int16_t* mean, const std::int16_t* mask,
    std::int32_t gain, std::int32_t bias, std::int16_t* error, int n) noexcept
{
    for (int i = 0; i < n; ++i) {
        const std::int32_t model = (gain * mean[i] + bias) >> 12;
        const std::int32_t e = std::clamp(16 * warped[i] - model, -kErrorLimit, kErrorLimit);
        error[i] = static_cast<std::int16_t>(e & mask[i]);
    }
}

__attribute__((optimize("no-tree-vectorize"))) std::int64_t dotProductScalar(const std::int16_t* a,
                                                                             const std::int16_t* b,
                                                                             int n) noexcept
{
    std::int64_t total = 0;
    for (int i = 0; i < n; ++i)
        total += std::int64_t{a[i]} * b[i];
    return total;
}

void errorImage(const std::int16_t* warped, const std::int16_t* mean, const std::int16_t* mask,
                std::int32_t gain, std::int32_t bias, std::int16_t* error, int n) noexcept
{
#if defined(__aarch64__)
    errorImageNeon(warped, mean, mask, gain, bias, error, n);
#else
#if defined(MIRROR_AVX2)
    if (simd::hasAvx2()) {
        errorImageAvx2(warped, mean, mask, gain, bias, error, n);
        return;
    }
#endif
    errorBody(warped, mean, mask, gain, bias, error, n);
#endif
}

std::int64_t dotProduct(const std::int16_t* a, const std::int16_t* b, int n) noexcept
{
#if defined(__aarch64__)
    return dotProductNeon(a, b, n);
#else
#if defined(MIRROR_AVX2)
    if (simd::hasAvx2())
        return dotProductAvx2(a, b, n);
#endif
    return dotBody(a, b, n);
#endif
}

const char* aamKernelPath() noexcept
{
#if defined(__aarch64__)
    return "neon";
#else
    return simd::hasAvx2() ? "avx2" : "sse2";
#endif
}

}  // namespace vision::aam
