#pragma once
// Counts heap allocations made on the calling thread while a scope is active, so a test can prove
// the frame loop allocates nothing per frame.
//
// Counted: every call of the global C++ allocation functions (operator new in all its forms), and
// every malloc/calloc/realloc/aligned allocation. A C allocation is "ours" when its caller's code
// lies in the test executable (all project libraries are linked statically into it) and "foreign"
// when the caller is a shared library such as the Mesa GL driver, which allocates internally on
// every draw call. Not available under AddressSanitizer (it owns malloc); see available().

namespace testing_support {

struct AllocationCounts {
    /// operator new / new[] calls from our executable or from libstdc++ (which our code calls
    /// for strings, vectors, functions...)
    long cxxNew = 0;
    /// operator new calls from other shared libraries: the GL driver's shader compiler (LLVM)
    /// compiles a pipeline variant the first time a state combination is drawn.
    long foreignNew = 0;
    long ownMalloc = 0;      ///< C allocations whose caller is in the executable (our code)
    long foreignMalloc = 0;  ///< C allocations from shared libraries (GL driver, libc internals)
};

class AllocationScope {
public:
    AllocationScope();   ///< starts counting on this thread, from zero
    ~AllocationScope();  ///< stops counting
    AllocationScope(const AllocationScope&) = delete;
    AllocationScope& operator=(const AllocationScope&) = delete;
    AllocationCounts counts() const;
};

/// False where the counting hooks are not compiled in (sanitizer builds).
bool allocationCountingAvailable();

}  // namespace testing_support
