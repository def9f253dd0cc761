// Storage for a hierarchy's large per-node and per-item arrays (internal).
//
// Why: a hierarchy is built once into fresh memory, so its build pays a page fault per 4 KiB it writes. On an
// ordinary machine that is ~0.25 µs a page, a few per cent of a build; on the paravirtualised VMs this project
// is benchmarked on it is 12–16 µs a page, as much as the build's arithmetic (a 100k-triangle mesh writes
// ~13 MB of nodes and volumes: ~3,200 faults, ~45 ms against ~45 ms of computing). Arrays of at least
// kBigArrayBytes are therefore placed on 2 MiB boundaries and the kernel is advised to back them with
// transparent huge pages (Linux madvise(MADV_HUGEPAGE); one fault per 2 MiB). It is advice only: where the
// kernel does not follow it (THP off, other systems) the arrays are ordinary memory. Smaller arrays use the
// ordinary allocator, so meshes below ~10k triangles are unchanged. The price is the rounding up to whole
// huge pages: under 2 MiB per array (at most doubling an array of just over 1 MiB, ~10 % of a 100k-triangle
// mesh's hierarchy).
#pragma once

#include <cstddef>
#include <cstdlib>
#include <limits>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace unidist::mesh {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
inline constexpr std::size_t kBigArrayBytes = std::size_t{1} << 20;

template <class T>
struct BigArrayAllocator {
  using value_type = T;

  BigArrayAllocator() = default;
  template <class U>
  BigArrayAllocator(const BigArrayAllocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor): allocator rebind

  static bool big(std::size_t n) { return n >= kBigArrayBytes / sizeof(T); }
  /// The bytes a buffer of n elements takes: whole huge pages when big.
  static std::size_t bufferBytes(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    return big(n) ? (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes : bytes;
  }

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T) - kHugePageBytes) throw std::bad_array_new_length();
    if (!big(n)) return static_cast<T*>(::operator new(n * sizeof(T)));
    const std::size_t bytes = bufferBytes(n);
    void* p = std::aligned_alloc(kHugePageBytes, bytes);
    if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    (void)::madvise(p, bytes, MADV_HUGEPAGE);  // advice: on failure the pages are ordinary ones
#endif
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t n) noexcept {
    if (big(n))
      std::free(p);
    else
      ::operator delete(p);
  }

  template <class U>
  bool operator==(const BigArrayAllocator<U>&) const noexcept {
    return true;
  }
  template <class U>
  bool operator!=(const BigArrayAllocator<U>&) const noexcept {
    return false;
  }
};

/// A vector whose large buffers follow BigArrayAllocator.
template <class T>
using BigVector = std::vector<T, BigArrayAllocator<T>>;

/// The memory a BigVector's buffer takes, huge-page rounding included.
template <class T>
std::size_t footprintBytes(const BigVector<T>& v) {
  return BigArrayAllocator<T>::bufferBytes(v.capacity());
}

}  // namespace unidist::mesh
