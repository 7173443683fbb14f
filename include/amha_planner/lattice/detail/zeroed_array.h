// A fixed-size array of zeroed, trivially copyable elements from calloc: a large one is fresh
// zero pages that cost no memory until written. A map's grid whose zero means "nothing here"
// (blocked, or not reached) then takes no memory for a page where nothing is: rows being
// contiguous, e.g. the rows of unknown above and below a building, or the cells a search never
// reached. std::vector would write every element.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>

namespace amha {
namespace lattice {

template <typename T>
class ZeroedArray {
  static_assert(std::is_trivially_copyable<T>::value, "zero bytes must be a valid T");

 public:
  ZeroedArray() = default;
  explicit ZeroedArray(std::size_t n) { reset(n); }
  ZeroedArray(const ZeroedArray&) = delete;
  ZeroedArray& operator=(const ZeroedArray&) = delete;
  ZeroedArray(ZeroedArray&& o) noexcept : data_(o.data_), size_(o.size_) {
    o.data_ = nullptr;
    o.size_ = 0;
  }
  ZeroedArray& operator=(ZeroedArray&& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    return *this;
  }
  ~ZeroedArray() { std::free(data_); }

  /// n zero elements (the old ones freed). Throws std::bad_alloc.
  void reset(std::size_t n) {
    std::free(data_);
    data_ = nullptr;
    size_ = 0;
    if (n == 0) return;
    data_ = static_cast<T*>(std::calloc(n, sizeof(T)));
    if (data_ == nullptr) throw std::bad_alloc();
    size_ = n;
  }
  std::size_t size() const { return size_; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace lattice
}  // namespace amha
