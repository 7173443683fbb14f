// A growable array of trivially copyable elements for the search's big per-state arrays (the
// records, the queues' storage). New elements are left uninitialised, as with new T[n].
//
// Why not std::vector: growing a vector allocates a new block, copies everything into it and
// frees the old one. For a search holding tens of millions of states that is a pause of seconds
// that no clock check can interrupt, a transient peak of old + new memory, and a first touch of
// every page of the new block (writing the new elements), where page faults are expensive
// (on this VM kind a fifth of a big 63-puzzle run went to the kernel's page clearing). This
// leaves new elements unwritten, grows small blocks with realloc, and keeps a block of
// kLargeBlockBytes or more in its own mapping, grown with mremap, which remaps pages instead of
// copying them (large_blocks.h). realloc would do that only for blocks malloc had mapped,
// which a process may turn off (mallopt M_MMAP_MAX), and a heap block that cannot grow in
// place is copied: a 10 s run of `amha tiles` once took 14 s that way.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>

#include "amha_planner/search/detail/large_blocks.h"

namespace amha {
namespace detail {

template <typename T>
class ReallocVector {
  static_assert(std::is_trivially_copyable<T>::value, "elements are moved as bytes");

 public:
  ReallocVector() = default;
  ReallocVector(const ReallocVector& o) { *this = o; }
  ReallocVector& operator=(const ReallocVector& o) {
    if (this != &o) {
      size_ = 0;
      resize(o.size_);
      if (o.size_ > 0) std::memcpy(data_, o.data_, o.size_ * sizeof(T));
    }
    return *this;
  }
  ReallocVector(ReallocVector&& o) noexcept { swap(o); }
  ReallocVector& operator=(ReallocVector&& o) noexcept {
    swap(o);
    return *this;
  }
  ~ReallocVector() {
    if (mapped_ > 0) {
      releaseLargeBlock(raw_, mapped_);
    } else {
      std::free(raw_);
    }
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::size_t capacity() const { return capacity_; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }

  void push_back(const T& v) {
    if (size_ == capacity_) reallocate(std::max<std::size_t>(2 * capacity_, 64));
    data_[size_++] = v;
  }
  void pop_back() { --size_; }
  /// Keeps the memory for reuse.
  void clear() { size_ = 0; }
  /// Makes the capacity at least n: exactly n if it must grow (so that a memory cap can be
  /// respected), never shrinking.
  void reserve(std::size_t n) {
    if (n > capacity_) reallocate(n);
  }
  /// New elements [size(), n) are uninitialised.
  void resize(std::size_t n) {
    if (n > capacity_) reallocate(std::max(n, 2 * capacity_));
    size_ = n;
  }

  void swap(ReallocVector& o) noexcept {
    std::swap(raw_, o.raw_);
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
    std::swap(mapped_, o.mapped_);
  }

 private:
  // data_ is raw_ rounded up to a cache line: a 4-ary heap's four children, or one 64-byte
  // queue block, then sit in one line.
  static constexpr std::size_t kAlign = 64;

  void reallocate(std::size_t n) {
    if (n > (static_cast<std::size_t>(-1) / 2 - kAlign) / sizeof(T)) {
      throw std::bad_array_new_length();
    }
    const std::size_t bytes = n * sizeof(T);
    if (mapped_ > 0) {  // a mapping: page-aligned, grows without a copy
      raw_ = growLargeBlock(raw_, bytes, &mapped_);
      data_ = static_cast<T*>(raw_);
    } else if (bytes >= kLargeBlockBytes) {  // from a small block (below 4 MiB) to a mapping
      std::size_t mapped = 0;
      void* block = mapLargeBlock(bytes, &mapped);
      if (size_ > 0) std::memcpy(block, data_, size_ * sizeof(T));
      std::free(raw_);
      raw_ = block;
      data_ = static_cast<T*>(block);
      mapped_ = mapped;
    } else {
      reallocateSmall(bytes);
    }
    capacity_ = n;
  }

  void reallocateSmall(std::size_t bytes) {
    const std::size_t old_offset =
        static_cast<std::size_t>(reinterpret_cast<char*>(data_) - static_cast<char*>(raw_));
    void* raw = std::realloc(raw_, bytes + kAlign);
    if (raw == nullptr) throw std::bad_alloc();
    const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(raw);
    const std::size_t offset = static_cast<std::size_t>((kAlign - at % kAlign) % kAlign);
    // realloc keeps the bytes at the old offset; a block that moved may need a new one.
    if (raw_ != nullptr && offset != old_offset) {
      std::memmove(static_cast<char*>(raw) + offset, static_cast<char*>(raw) + old_offset,
                   size_ * sizeof(T));
    }
    raw_ = raw;
    data_ = reinterpret_cast<T*>(static_cast<char*>(raw) + offset);
  }

  void* raw_ = nullptr;
  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
  std::size_t mapped_ = 0;  // size of raw_'s mapping; 0: raw_ is a malloc block
};

}  // namespace detail
}  // namespace amha
