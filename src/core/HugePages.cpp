#include "core/HugePages.h"

#include <cstdint>
#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace overflight {

namespace {
constexpr std::size_t kHuge = std::size_t(2) << 20;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
constexpr bool kAdvice = true;
#else
constexpr bool kAdvice = false; // nothing to align for: cache lines only
#endif
} // namespace

void advise_huge_pages([[maybe_unused]] void* p, [[maybe_unused]] std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(p) + kHuge - 1) & ~std::uintptr_t(kHuge - 1);
    const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~std::uintptr_t(kHuge - 1);
    // Advice only: where the kernel declines (THP off), 4 KiB pages serve as before.
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

void* allocate_huge_pages(std::size_t bytes) {
    const std::size_t align = kAdvice ? kHuge : 64;
    const std::size_t whole = (bytes + align - 1) / align * align;
    void* p = whole ? std::aligned_alloc(align, whole) : nullptr;
    if (!p && whole) throw std::bad_alloc();
    advise_huge_pages(p, whole);
    return p;
}

void free_huge_pages(void* p) noexcept { std::free(p); }

} // namespace overflight
