#include "alloc_counter.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MIRROR_ALLOC_HOOKS 0
#else
#define MIRROR_ALLOC_HOOKS 1
#endif

namespace {
thread_local bool tCounting = false;
thread_local testing_support::AllocationCounts tCounts;
}  // namespace

namespace testing_support {

AllocationScope::AllocationScope()
{
    tCounts = {};
    tCounting = true;
}
AllocationScope::~AllocationScope()
{
    tCounting = false;
}
AllocationCounts AllocationScope::counts() const
{
    return tCounts;
}
bool allocationCountingAvailable()
{
    return MIRROR_ALLOC_HOOKS != 0;
}

}  // namespace testing_support

#if MIRROR_ALLOC_HOOKS

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
extern const char __executable_start;
extern const char etext;
}

namespace {

void noteCAllocation(const void* caller)
{
    if (!tCounting)
        return;
    const auto* c = static_cast<const char*>(caller);
    if (c >= &__executable_start && c < &etext)
        ++tCounts.ownMalloc;
    else
        ++tCounts.foreignMalloc;
}

void* cxxAllocate(std::size_t size, std::size_t alignment, bool nothrow)
{
    if (tCounting)
        ++tCounts.cxxNew;
    if (size == 0)
        size = 1;
    void* p = alignment > alignof(std::max_align_t) ? __libc_memalign(alignment, size)
                                                    : __libc_malloc(size);
    if (!p && !nothrow)
        throw std::bad_alloc();
    return p;
}

}  // namespace

extern "C" {
void* malloc(std::size_t size)
{
    noteCAllocation(__builtin_return_address(0));
    return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size)
{
    noteCAllocation(__builtin_return_address(0));
    return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size)
{
    noteCAllocation(__builtin_return_address(0));
    return __libc_realloc(p, size);
}
void* memalign(std::size_t alignment, std::size_t size)
{
    noteCAllocation(__builtin_return_address(0));
    return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size)
{
    noteCAllocation(__builtin_return_address(0));
    return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size)
{
    noteCAllocation(__builtin_return_address(0));
    void* p = __libc_memalign(alignment, size);
    if (!p)
        return 12;  // ENOMEM
    *out = p;
    return 0;
}
void free(void* p)
{
    __libc_free(p);
}
}

void* operator new(std::size_t n)
{
    return cxxAllocate(n, 0, false);
}
void* operator new[](std::size_t n)
{
    return cxxAllocate(n, 0, false);
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept
{
    return cxxAllocate(n, 0, true);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept
{
    return cxxAllocate(n, 0, true);
}
void* operator new(std::size_t n, std::align_val_t a)
{
    return cxxAllocate(n, std::size_t(a), false);
}
void* operator new[](std::size_t n, std::align_val_t a)
{
    return cxxAllocate(n, std::size_t(a), false);
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept
{
    return cxxAllocate(n, std::size_t(a), true);
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept
{
    return cxxAllocate(n, std::size_t(a), true);
}
void operator delete(void* p) noexcept
{
    __libc_free(p);
}
void operator delete[](void* p) noexcept
{
    __libc_free(p);
}
void operator delete(void* p, std::size_t) noexcept
{
    __libc_free(p);
}
void operator delete[](void* p, std::size_t) noexcept
{
    __libc_free(p);
}
void operator delete(void* p, std::align_val_t) noexcept
{
    __libc_free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept
{
    __libc_free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept
{
    __libc_free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept
{
    __libc_free(p);
}

#endif  // MIRROR_ALLOC_HOOKS
