// scansurf: an allocator for the big working arrays of a CPU stage (smoothing): arrays of
// 32 MiB and more are 2 MiB aligned and asked to be backed by transparent huge pages
// (madvise(MADV_HUGEPAGE), Linux; a hint, ignored where the kernel does not give them), so the
// first touch of every 2 MiB is one page fault instead of 512: first touches of fresh memory,
// not the work on it, dominate such arrays' cost with 4 KiB pages.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace scansurf {

template <typename T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;
  // Smaller arrays: operator new. From 32 MiB glibc maps every allocation on its own, so the
  // hint never reaches the heap that smaller allocations share, and freeing returns it all
  // (with 8 MiB, the phantom's peak RSS grew from 188 to 212 MiB).
  static constexpr std::size_t kLeast = 16 * kHugePage;

  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kLeast) return static_cast<T*>(::operator new(bytes));
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);  // a hint: its failure changes nothing
#endif
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kLeast)
      ::operator delete(p);
    else
      std::free(p);
  }
  friend bool operator==(const HugePageAllocator&, const HugePageAllocator&) { return true; }
};

template <typename T>
using HugeVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace scansurf
