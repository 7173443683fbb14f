// Allocator for the search's large per-state arrays. Every block is cache-line aligned (so a
// 4-ary heap's four children share one line); blocks of 2 MiB or more are 2 MiB aligned and
// advised as transparent huge pages: random access over hundreds of MB then misses the TLB
// far less often, and growing an array costs one page fault per 2 MiB instead of per 4 KiB.
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <limits>
#include <new>

namespace amha {

template <typename T>
struct BigArrayAllocator {
  using value_type = T;
  static constexpr std::size_t kLine = 64;
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;

  BigArrayAllocator() = default;
  template <typename U>
  BigArrayAllocator(const BigArrayAllocator<U>&) noexcept {}  // NOLINT: rebinding converts

  static std::size_t alignmentFor(std::size_t n) {
    return n * sizeof(T) >= kHugePage ? kHugePage : kLine;
  }

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    const std::size_t align = alignmentFor(n);
    void* p = ::operator new(bytes, std::align_val_t(align));
    // Only advice: if the kernel has huge pages off, this fails harmlessly.
    if (align == kHugePage) ::madvise(p, bytes / kHugePage * kHugePage, MADV_HUGEPAGE);
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    ::operator delete(p, std::align_val_t(alignmentFor(n)));
  }
};

template <typename T, typename U>
bool operator==(const BigArrayAllocator<T>&, const BigArrayAllocator<U>&) {
  return true;
}
template <typename T, typename U>
bool operator!=(const BigArrayAllocator<T>&, const BigArrayAllocator<U>&) {
  return false;
}

}  // namespace amha
