#pragma once
// The vision core's one choice of SIMD code path. Private to vision/src.
//
// The product runs on aarch64, whose baseline is NEON: the compiler vectorises plain loops for
// it and chromaticity_neon.cpp is always built, so there is nothing to choose. On an x86-64
// development machine there is one path besides the baseline (SSE2): AVX2. A kernel built for it
// is marked MIRROR_AVX2 and called only when simd::hasAvx2(). Two forms:
//  - hand-written intrinsics: a function marked MIRROR_AVX2 (chromaticity_avx2.cpp,
//    optical_flow_avx2.cpp, the pyramid's row filter);
//  - a plain loop the compiler vectorises: its body is a MIRROR_SIMD_BODY function, instantiated
//    for AVX2 by a MIRROR_AVX2 wrapper that inlines it, and the caller picks one by hasAvx2().
// Every path gives the same bits as the scalar reference; the tests compare them.
#if defined(__x86_64__)
#define MIRROR_AVX2 __attribute__((target("avx2")))
#endif
/// A loop body compiled into each path that inlines it (and with that path's instructions).
#define MIRROR_SIMD_BODY __attribute__((always_inline)) inline

namespace vision::simd {

/// True when the AVX2 path runs on this CPU (x86-64 with AVX2); false on every other machine.
bool hasAvx2() noexcept;

}  // namespace vision::simd
