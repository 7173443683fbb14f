// Allocator for the search's large per-state arrays: every block is cache-line aligned, so a
// 4-ary heap's four children share one line. (Transparent huge pages were tried as well: on
// this VM kind the kernel's zeroing of 2 MiB pages cost more than the TLB misses they saved,
// 410k -> 364k expansions per CPU second on a 63-puzzle.)
#pragma once

#include <cstddef>
#include <limits>
#include <new>

namespace amha {

template <typename T>
struct BigArrayAllocator {
  using value_type = T;
  static constexpr std::size_t kLine = 64;

  BigArrayAllocator() = default;
  template <typename U>
  BigArrayAllocator(const BigArrayAllocator<U>&) noexcept {}  // NOLINT: rebinding converts

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(kLine)));
  }
  void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(kLine)); }
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
