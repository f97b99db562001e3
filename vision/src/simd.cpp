#include "simd.hpp"

namespace vision::simd {

bool hasAvx2() noexcept
{
#if defined(__x86_64__)
    // Asked once: the answer is a property of the machine.
    static const bool has = __builtin_cpu_supports("avx2") != 0;
    return has;
#else
    return false;
#endif
}

}  // namespace vision::simd
