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

#include <link.h>

#include <cstring>

namespace {
thread_local bool tCounting = false;
thread_local testing_support::AllocationCounts tCounts;

/// Code ranges whose operator new calls count as ours: the executable and libstdc++.
struct CodeRange {
    std::uintptr_t begin = 0;
    std::uintptr_t end = 0;
};
CodeRange gOurCode[8];
int gOurCodeCount = 0;

int noteRanges(dl_phdr_info* info, std::size_t, void*)
{
    const char* name = info->dlpi_name;
    const bool executable = name == nullptr || name[0] == '\0';
    if (!executable && std::strstr(name, "libstdc++") == nullptr)
        return 0;
    for (int i = 0; i < info->dlpi_phnum && gOurCodeCount < 8; ++i) {
        const ElfW(Phdr)& ph = info->dlpi_phdr[i];
        if (ph.p_type == PT_LOAD && (ph.p_flags & PF_X)) {
            const std::uintptr_t begin = info->dlpi_addr + ph.p_vaddr;
            gOurCode[gOurCodeCount++] = {begin, begin + ph.p_memsz};
        }
    }
    return 0;
}

[[maybe_unused]] bool isOurCode(const void* address)
{
    const auto a = reinterpret_cast<std::uintptr_t>(address);
    for (int i = 0; i < gOurCodeCount; ++i)
        if (a >= gOurCode[i].begin && a < gOurCode[i].end)
            return true;
    return false;
}
}  // namespace

namespace testing_support {

AllocationScope::AllocationScope()
{
    if (gOurCodeCount == 0)
        dl_iterate_phdr(noteRanges, nullptr);  // no allocation
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

void* cxxAllocate(std::size_t size, std::size_t alignment, bool nothrow, const void* caller)
{
    if (tCounting) {
        if (isOurCode(caller))
            ++tCounts.cxxNew;
        else
            ++tCounts.foreignNew;
    }
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
    return cxxAllocate(n, 0, false, __builtin_return_address(0));
}
void* operator new[](std::size_t n)
{
    return cxxAllocate(n, 0, false, __builtin_return_address(0));
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept
{
    return cxxAllocate(n, 0, true, __builtin_return_address(0));
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept
{
    return cxxAllocate(n, 0, true, __builtin_return_address(0));
}
void* operator new(std::size_t n, std::align_val_t a)
{
    return cxxAllocate(n, std::size_t(a), false, __builtin_return_address(0));
}
void* operator new[](std::size_t n, std::align_val_t a)
{
    return cxxAllocate(n, std::size_t(a), false, __builtin_return_address(0));
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept
{
    return cxxAllocate(n, std::size_t(a), true, __builtin_return_address(0));
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept
{
    return cxxAllocate(n, std::size_t(a), true, __builtin_return_address(0));
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
