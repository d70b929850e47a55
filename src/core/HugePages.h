#pragma once
// Storage on transparent huge pages for what the renderers touch all over in
// every frame: the large arrays (the terrain's samples as the cast gathers
// them, the pyramid levels, the images) and the per-thread scratch of the
// shear cast. A ray caster's accesses are the worst case for 4 KiB pages: a
// ray that runs along the grid's rows reads a new terrain row, a page of its
// own, at every slice (a 4097-sample row of 8-byte records is 32 KiB); a
// block of image columns writes each image row on a page of its own (a
// 3840-pixel row of depth is 15 KiB); and 16 columns in lockstep paint 32
// stripes of 8 KiB at 4K in one step. So nearly every step misses the TLB,
// and in a virtual machine each miss walks two levels of page tables. On
// Linux with transparent huge pages in `madvise` mode (the default of many
// distributions) memory is backed by 2 MiB pages only where the program asks
// before it first touches it. Elsewhere all of this falls back to plain
// 4 KiB pages: advice, never a requirement.
#include <cstddef>
#include <new>
#include <vector>

namespace overflight {

// Asks the kernel to back the 2 MiB pages that lie wholly inside
// [p, p + bytes) with huge pages when they are first touched. Does nothing
// where the platform has no such advice (and for less than 2 MiB).
void advise_huge_pages(void* p, std::size_t bytes);

// For large arrays in a plain std::vector (so that their type stays the one
// every interface takes): v.assign(n, fill), with storage advised for huge
// pages before it is first touched when v has to grow (its storage is kept
// when it holds n already).
template <typename T>
void assign_on_huge_pages(std::vector<T>& v, std::size_t n, const T& fill = T{}) {
    if (v.capacity() < n) {
        std::vector<T> fresh;
        fresh.reserve(n);
        advise_huge_pages(fresh.data(), n * sizeof(T));
        v = std::move(fresh);
    }
    v.assign(n, fill);
}

// For scratch smaller than a huge page: bytes rounded up to whole 2 MiB
// pages, 2 MiB-aligned, advised (where there is no such advice: to whole
// 64-byte lines); throws std::bad_alloc; free with free_huge_pages.
void* allocate_huge_pages(std::size_t bytes);
void free_huge_pages(void* p) noexcept;

template <typename T>
struct HugePageAllocator {
    using value_type = T;
    HugePageAllocator() = default;
    template <typename U>
    HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) { return static_cast<T*>(allocate_huge_pages(n * sizeof(T))); }
    void deallocate(T* p, std::size_t) noexcept { free_huge_pages(p); }
    friend bool operator==(const HugePageAllocator&, const HugePageAllocator&) { return true; }
};

} // namespace overflight
