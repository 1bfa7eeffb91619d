// Fresh memory, mapped in bulk: a fresh page costs a fault and a zeroing (and on a VM that hands freed
// memory back to its host, a host fault). Used where it measurably pays: limited_cells' output
// columns (partition/detail/cell_columns.hpp) and the grid index's arrays, a few percent of CPU time
// (system time) at 1e6 agents; and an allocator that leaves arrays unfilled, on huge pages, for the
// grid diagram's nearest-point maps (a 2048^2 build took 6,500 page faults, a third of its time when
// its memory was fresh). Elsewhere (the exact partition) mapping up front measured within noise and
// was removed (docs/performance.md). -DDVORONOI_NO_PAGE_MAPPING turns
// prefault and advise_huge_pages into no-ops (tools/bench_pages.sh compares the two builds).
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace dvoronoi {
namespace detail {

/// An allocator whose value-less construct() leaves trivial types uninitialised, so resize(n) does
/// not write n zeros: for arrays that their parallel passes fill completely, where a serial fill
/// before them would be a sequential part of the run.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = DefaultInitAllocator<U>;
    };
    using std::allocator<T>::allocator;
    /// Arrays of 4 MB or more start on a 2 MB boundary, so that huge pages (advise_huge_pages) can
    /// cover all of them: malloc's large blocks start 16 bytes into a 4 KB page, which leaves up to
    /// 2 MB at each end in 4 KB pages.
    static constexpr std::size_t kHugeAlign = std::size_t{1} << 21;
    T* allocate(std::size_t n) {
        if (n * sizeof(T) < 2 * kHugeAlign) return std::allocator<T>::allocate(n);
        return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{kHugeAlign}));
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < 2 * kHugeAlign) return std::allocator<T>::deallocate(p, n);
        ::operator delete(p, std::align_val_t{kHugeAlign});
    }
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

/// A vector whose resize() leaves new trivial elements uninitialised (see DefaultInitAllocator).
template <class T>
using UninitVector = std::vector<T, DefaultInitAllocator<T>>;

/// Maps the pages of [p, p + bytes) by one system call (MADV_POPULATE_WRITE, Linux 5.14+) instead
/// of one page fault each; elsewhere, on older kernels or for small buffers it does nothing and the
/// pages fault in as before. Measured when limited_cells touched 700 MB at 1e6 agents: page faults
/// were about a sixth of the run, and mapping the pages up front took about a quarter off that.
inline void prefault(const void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE) && !defined(DVORONOI_NO_PAGE_MAPPING)
    constexpr std::uintptr_t kPage = 4096;
    if (bytes < (std::size_t{1} << 20)) return;
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t lo = (at + kPage - 1) & ~(kPage - 1), hi = (at + bytes) & ~(kPage - 1);
    if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_POPULATE_WRITE);  // a hint: failure is harmless
#else
    (void)p;
    (void)bytes;
#endif
}

/// Asks for huge pages under [p, p + bytes) (its whole 2 MB pages). For arrays accessed in scattered
/// order: with 4 KB pages such an access misses the TLB at nearly every agent once the arrays
/// outgrow it, and under a hypervisor each miss is a two-level page walk. For arrays filled in
/// order, measure: limited_cells' output columns mapped slower on fresh huge pages, the grid
/// diagram's nearest-point maps (filled by several passes) faster.
inline void advise_huge_pages(const void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE) && !defined(DVORONOI_NO_PAGE_MAPPING)
    constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t lo = (at + kHuge - 1) & ~(kHuge - 1), hi = (at + bytes) & ~(kHuge - 1);
    if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);  // a hint, as above
#else
    (void)p;
    (void)bytes;
#endif
}

/// prefault for several buffers at once, each split over up to `team` threads: page faults are
/// handled by the faulting thread, so two threads map pages faster than one.
inline void prefault_together(std::initializer_list<std::pair<const void*, std::size_t>> buffers, int team) {
#pragma omp parallel for num_threads(team) schedule(static, 1) if (team > 1)
    for (int t = 0; t < team; ++t)
        for (const auto& [p, bytes] : buffers) {
            const std::size_t lo = bytes / static_cast<std::size_t>(team) * static_cast<std::size_t>(t);
            const std::size_t hi = t + 1 == team ? bytes : bytes / static_cast<std::size_t>(team) * static_cast<std::size_t>(t + 1);
            prefault(static_cast<const char*>(p) + lo, hi - lo);
        }
}

}  // namespace detail
}  // namespace dvoronoi
