#pragma once
// The parallelism of the core layers (core, raycast, lod, sim) in one place.
// Natively it is oneTBB's, call for call (the same ranges, grain sizes and
// default partitioner): this header only renames it. Built for WebAssembly
// (Emscripten: a page has one thread unless its server sends cross-origin
// isolation headers) or with OVERFLIGHT_SERIAL defined, the same calls run
// serially, in index order, on the calling thread, and TBB is not needed.
// The algorithms never ask which: the only #if is here.
//
//   for_each_index(first, last, body)        body(i) for every i in [first, last)
//   for_each_range(first, last, grain, body) body(begin, end) over subranges
//                                            covering [first, last), split while
//                                            longer than grain (tbb::blocked_range)
//   invoke(f, g)                             f() and g(), possibly at once; returns after both
//   isolate(f)                               f(), this thread taking no other task meanwhile
//                                            (for a caller holding a lock while f waits)
//   ThreadLocal<T>                           local(): one T per calling thread
//                                            (default-constructed on first use)
//   CacheAlignedAllocator<T>                 blocks on their own cache lines (no false
//                                            sharing between threads)
//   fetch_add, fetch_or, load, store         relaxed atomic access to a plain shared integer
//
// Bodies must be correct in any order and on any thread, as TBB requires.
#if defined(__EMSCRIPTEN__) || defined(OVERFLIGHT_SERIAL)
#include <memory>
#else
#include <tbb/blocked_range.h>
#include <tbb/cache_aligned_allocator.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>
#endif

namespace overflight::parallel {

#if defined(__EMSCRIPTEN__) || defined(OVERFLIGHT_SERIAL)

template <typename Index, typename Body>
void for_each_index(Index first, Index last, const Body& body) {
    for (Index i = first; i < last; ++i) body(i);
}

template <typename Index, typename Body>
void for_each_range(Index first, Index last, Index /*grain*/, const Body& body) {
    if (first < last) body(first, last);
}

template <typename F, typename G>
void invoke(const F& f, const G& g) {
    f();
    g();
}

template <typename F>
void isolate(const F& f) {
    f();
}

template <typename T>
class ThreadLocal {
public:
    T& local() { return value_; }

private:
    T value_{};
};

template <typename T>
using CacheAlignedAllocator = std::allocator<T>;

#else

template <typename Index, typename Body>
void for_each_index(Index first, Index last, const Body& body) {
    tbb::parallel_for(first, last, body);
}

template <typename Index, typename Body>
void for_each_range(Index first, Index last, Index grain, const Body& body) {
    tbb::parallel_for(tbb::blocked_range<Index>(first, last, grain),
                      [&](const tbb::blocked_range<Index>& r) { body(r.begin(), r.end()); });
}

template <typename F, typename G>
void invoke(const F& f, const G& g) {
    tbb::parallel_invoke(f, g);
}

template <typename F>
void isolate(const F& f) {
    tbb::this_task_arena::isolate(f);
}

template <typename T>
using ThreadLocal = tbb::enumerable_thread_specific<T>;

template <typename T>
using CacheAlignedAllocator = tbb::cache_aligned_allocator<T>;

#endif

// Relaxed atomic access to a plain integer or bool that bodies running at
// once share (what std::atomic_ref does; the WebAssembly toolchain's library
// lacks it). Ordering between bodies comes from the call that runs them.
template <typename T>
T fetch_add(T& x, T v) {
    return __atomic_fetch_add(&x, v, __ATOMIC_RELAXED);
}

template <typename T>
T fetch_or(T& x, T v) {
    return __atomic_fetch_or(&x, v, __ATOMIC_RELAXED);
}

template <typename T>
T load(const T& x) {
    return __atomic_load_n(&x, __ATOMIC_RELAXED);
}

template <typename T>
void store(T& x, T v) {
    __atomic_store_n(&x, v, __ATOMIC_RELAXED);
}

} // namespace overflight::parallel
