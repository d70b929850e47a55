#pragma once
// Storage for the large arrays that the renderers read or write all over in
// every frame (the terrain's samples as the cast gathers them, the pyramid
// levels, the images): backed by transparent huge pages where the kernel
// offers them, so that the TLB covers them. A ray caster's accesses are the
// worst case for 4 KiB pages: a ray that runs along the grid's rows reads a
// new terrain row, a page of its own, at every slice (a 4097-sample row of
// 8-byte records is 32 KiB), and a block of image columns writes each image
// row on a page of its own (a 3840-pixel row of depth is 15 KiB), so nearly
// every step misses the TLB, and in a virtual machine each miss walks two
// levels of page tables. On Linux with transparent huge pages in `madvise`
// mode (the default of many distributions) memory is backed by 2 MiB pages
// only where the program asks before it first touches it.
#include <cstddef>
#include <vector>

namespace overflight {

// Asks the kernel to back the 2 MiB pages that lie wholly inside
// [p, p + bytes) with huge pages when they are first touched. Does nothing
// where the platform has no such advice (and for less than 2 MiB).
void advise_huge_pages(void* p, std::size_t bytes);

// v.assign(n, fill), with storage advised for huge pages before it is first
// touched when v has to grow (its storage is kept when it holds n already).
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

} // namespace overflight
