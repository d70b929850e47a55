#pragma once
// An allocator for large arrays read at scattered places (the imagery's
// texels, ImageryTexels): blocks of 2 MiB and more are aligned to 2 MiB and
// marked for transparent huge pages (Linux madvise(MADV_HUGEPAGE), where the
// system leaves huge pages to the program's choice), so that one TLB entry
// covers 512 of the 4 KiB pages a gather of texels spread over a level would
// otherwise miss on. Elsewhere, and for smaller blocks, plain operator new.
// Allocation failure throws std::bad_alloc, as std::allocator does.
#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace overflight {

template <class T>
struct HugePageAllocator {
    using value_type = T;
    static constexpr std::size_t kHugePage = std::size_t(2) << 20;

    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
        const std::size_t bytes = n * sizeof(T);
#if defined(__linux__)
        if (bytes >= kHugePage) {
            const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
            void* p = std::aligned_alloc(kHugePage, rounded);
            if (!p) throw std::bad_alloc();
            // Advice only: without huge pages the memory works as any other.
            madvise(p, rounded, MADV_HUGEPAGE);
            return static_cast<T*>(p);
        }
#endif
        return static_cast<T*>(::operator new(bytes));
    }
    void deallocate(T* p, std::size_t n) noexcept {
#if defined(__linux__)
        if (n * sizeof(T) >= kHugePage) {
            std::free(p);
            return;
        }
#endif
        ::operator delete(p);
    }

    template <class U>
    bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
};

} // namespace overflight
