// The AAM fit's integer kernels (§5, dissertation 5.3.4: integer images and dot products): the
// path this machine takes (NEON on aarch64, run under qemu in the arm64 build; AVX2 or SSE2 on
// x86-64) gives exactly the scalar reference's integers, on random data, at the extremes the
// kernels promise to hold (no partial sum overflows), and at every length (SIMD tails).
#include "aam_kernels.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace {

using vision::aam::kErrorLimit;

std::vector<std::int16_t> randomValues(int n, int limit, std::mt19937& random)
{
    std::uniform_int_distribution<int> value(-limit, limit);
    std::vector<std::int16_t> v(static_cast<std::size_t>(n));
    for (auto& x : v)
        x = static_cast<std::int16_t>(value(random));
    return v;
}

TEST(AamKernels, DotProductIsTheScalarReferenceAtEveryLength)
{
    std::printf("aam kernel path: %s\n", vision::aam::aamKernelPath());
    std::mt19937 random(3);
    for (int n : {0, 1, 7, 8, 9, 63, 64, 65, 127, 128, 129, 1000, 8011}) {
        const auto a = randomValues(n, kErrorLimit, random);
        const auto b = randomValues(n, 2047, random);
        EXPECT_EQ(vision::aam::dotProduct(a.data(), b.data(), n),
                  vision::aam::dotProductScalar(a.data(), b.data(), n))
            << n;
    }
}

TEST(AamKernels, DotProductHoldsAtTheExtremes)
{
    const int n = 8011;
    const std::vector<std::int16_t> high(n, kErrorLimit), low(n, -kErrorLimit);
    const std::int64_t expected = std::int64_t{n} * kErrorLimit * kErrorLimit;
    EXPECT_EQ(vision::aam::dotProduct(high.data(), high.data(), n), expected);
    EXPECT_EQ(vision::aam::dotProduct(low.data(), low.data(), n), expected);
    EXPECT_EQ(vision::aam::dotProduct(high.data(), low.data(), n), -expected);
    EXPECT_EQ(vision::aam::dotProductScalar(high.data(), low.data(), n), -expected);
}

TEST(AamKernels, ErrorImageIsTheScalarReference)
{
    std::mt19937 random(5);
    for (int n : {1, 8, 15, 16, 17, 1001, 7999}) {
        std::uniform_int_distribution<int> grey(0, 255), keep(0, 9);
        std::vector<std::int16_t> warped(static_cast<std::size_t>(n)), mask(warped.size());
        for (std::size_t i = 0; i < warped.size(); ++i) {
            warped[i] = static_cast<std::int16_t>(grey(random));
            mask[i] = keep(random) == 0 ? 0 : -1;
        }
        const auto mean = randomValues(n, 2000, random);
        for (const auto& [gain, bias] : {std::pair{45 * 256, 120 * 65536}, std::pair{256, 0},
                                         std::pair{250 * 256, 255 * 65536}}) {
            std::vector<std::int16_t> fast(warped.size()), scalar(warped.size());
            vision::aam::errorImage(warped.data(), mean.data(), mask.data(), gain, bias,
                                    fast.data(), n);
            vision::aam::errorImageScalar(warped.data(), mean.data(), mask.data(), gain, bias,
                                          scalar.data(), n);
            EXPECT_EQ(fast, scalar) << n << " " << gain;
            for (std::size_t i = 0; i < scalar.size(); ++i) {
                ASSERT_LE(std::abs(scalar[i]), kErrorLimit);
                if (mask[i] == 0) {
                    ASSERT_EQ(scalar[i], 0);
                }
            }
        }
    }
}

}  // namespace
