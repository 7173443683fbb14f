// A growable array of trivially copyable elements for the search's big per-state arrays (the
// records, the queues' storage). New elements are left uninitialised, as with new T[n].
//
// Why not std::vector: growing a vector allocates a new block, copies everything into it and
// frees the old one. For a search holding tens of millions of states that is a pause of seconds
// that no clock check can interrupt, a transient peak of old + new memory, and a first touch of
// every page of the new block (writing the new elements), where page faults are expensive
// (on this VM kind a fifth of a big 63-puzzle run went to the kernel's page clearing). This
// grows with realloc and leaves new elements unwritten. glibc moves a large (mmap-ed) block
// with mremap, which remaps pages instead of copying them; a heap block grows in place when
// it is at the top of the heap, and is copied otherwise. (`amha tiles` keeps all blocks on
// the heap so that runs reuse each other's pages: there, a growth can still copy.)
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>

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
  ~ReallocVector() { std::free(raw_); }

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
  }

 private:
  // data_ is raw_ rounded up to a cache line: a 4-ary heap's four children, or one 64-byte
  // queue block, then sit in one line.
  static constexpr std::size_t kAlign = 64;

  void reallocate(std::size_t n) {
    if (n > (static_cast<std::size_t>(-1) / 2 - kAlign) / sizeof(T)) {
      throw std::bad_array_new_length();
    }
    const std::size_t old_offset = static_cast<std::size_t>(reinterpret_cast<char*>(data_) -
                                                            static_cast<char*>(raw_));
    void* raw = std::realloc(raw_, n * sizeof(T) + kAlign);
    if (raw == nullptr) throw std::bad_alloc();
    const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(raw);
    const std::size_t offset = static_cast<std::size_t>((kAlign - at % kAlign) % kAlign);
    // realloc keeps the bytes at the old offset; a block that moved may need a new one (a
    // large block keeps its offset, so this copy is confined to small blocks).
    if (raw_ != nullptr && offset != old_offset) {
      std::memmove(static_cast<char*>(raw) + offset, static_cast<char*>(raw) + old_offset,
                   size_ * sizeof(T));
    }
    raw_ = raw;
    data_ = reinterpret_cast<T*>(static_cast<char*>(raw) + offset);
    capacity_ = n;
  }

  void* raw_ = nullptr;
  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

}  // namespace detail
}  // namespace amha
