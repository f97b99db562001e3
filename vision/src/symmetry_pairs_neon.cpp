// NEON pair sums of the roll by image symmetry (aarch64): four pairs (x .. x + 3) a step, their
// partners (a2 - x - 3 .. a2 - x) loaded as one vector and reversed. The lanes are
// symmetry_pairs.hpp's four partial sums and a row's last pairs go to its fifth, so the result
// has the scalar reference's bits.
#if defined(__aarch64__)

#include "symmetry_pairs.hpp"

#include <arm_neon.h>

namespace vision::symmetry_detail {

namespace {

/// v[3], v[2], v[1], v[0].
inline float32x4_t reversed(float32x4_t v) noexcept
{
    const float32x4_t halves = vrev64q_f32(v);  // v1 v0 v3 v2
    return vextq_f32(halves, halves, 2);        // v3 v2 v1 v0
}

}  // namespace

float pairAsymmetryWholeAxisNeon(const PairPlanes& p, int xFirst, int xEnd, int a2) noexcept
{
    PairSums s;
    float32x4_t cost = vdupq_n_f32(0.f);
    float32x4_t norm = vdupq_n_f32(0.f);
    const int full = xFirst + (xEnd - xFirst) / 4 * 4;
    for (int y = p.y0; y < p.y1; ++y) {
        const float* a = p.a + static_cast<std::ptrdiff_t>(y) * p.n;
        const float* b = p.b + static_cast<std::ptrdiff_t>(y) * p.n;
        int x = xFirst;
        for (; x < full; x += 4) {
            const float32x4_t ax = vld1q_f32(a + x);
            const float32x4_t bx = vld1q_f32(b + x);
            const float32x4_t am = reversed(vld1q_f32(a + (a2 - x - 3)));
            const float32x4_t bm = reversed(vld1q_f32(b + (a2 - x - 3)));
            cost = vaddq_f32(cost, vaddq_f32(vabsq_f32(vaddq_f32(ax, am)),
                                             vabsq_f32(vsubq_f32(bx, bm))));
            norm = vaddq_f32(
                norm, vaddq_f32(vaddq_f32(vaddq_f32(vabsq_f32(ax), vabsq_f32(am)), vabsq_f32(bx)),
                                vabsq_f32(bm)));
        }
        for (; x < xEnd; ++x) {
            const float am = a[a2 - x];
            const float bm = b[a2 - x];
            s.tailCost += std::fabs(a[x] + am) + std::fabs(b[x] - bm);
            s.tailNorm += std::fabs(a[x]) + std::fabs(am) + std::fabs(b[x]) + std::fabs(bm);
        }
    }
    vst1q_f32(s.cost, cost);
    vst1q_f32(s.norm, norm);
    return s.ratio();
}

}  // namespace vision::symmetry_detail

#endif
