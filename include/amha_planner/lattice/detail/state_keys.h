// The lattice search's list of states: each state id's (x, y, heading), as one key
// cell << heading_bits | heading (all ones: the virtual heading of a virtual state), in 4 bytes
// when every key of the map fits (maps below 2^27 cells at 16 headings, 2^25 at 72), else in 8.
// Grown by remapping, not copying (ReallocVector): a vector's doubling would hold the old and
// the new list at once.
#pragma once

#include <cstdint>

#include "amha_planner/search/detail/realloc_vector.h"
#include "amha_planner/search/types.h"

namespace amha {
namespace lattice {

class StateKeys {
 public:
  /// For a map of width x height cells and `headings` headings (at most 0xFFFF);
  /// `virtual_heading` is what at() gives for a state added with it.
  StateKeys(int width, int height, int headings, int virtual_heading)
      : width_(static_cast<std::uint64_t>(width)), virtual_heading_(virtual_heading) {
    while ((std::uint64_t{1} << bits_) <= static_cast<std::uint64_t>(headings)) ++bits_;
    mask_ = (std::uint64_t{1} << bits_) - 1;
    const std::uint64_t cells = width_ * static_cast<std::uint64_t>(height);
    narrow_ = (cells << bits_) <= (std::uint64_t{1} << 32);
  }

  bool narrow() const { return narrow_; }
  std::size_t size() const { return narrow_ ? narrow_keys_.size() : wide_keys_.size(); }
  std::size_t bytes() const {
    return narrow_keys_.capacity() * sizeof(std::uint32_t) +
           wide_keys_.capacity() * sizeof(std::uint64_t);
  }

  /// Appends a state; its id is the number of states before it.
  StateId add(int x, int y, int heading) {
    const std::uint64_t cell =
        static_cast<std::uint64_t>(y) * width_ + static_cast<std::uint64_t>(x);
    const std::uint64_t code =
        heading == virtual_heading_ ? mask_ : static_cast<std::uint64_t>(heading);
    const std::uint64_t key = cell << bits_ | code;
    if (narrow_) {
      narrow_keys_.push_back(static_cast<std::uint32_t>(key));
      return static_cast<StateId>(narrow_keys_.size() - 1);
    }
    wide_keys_.push_back(key);
    return static_cast<StateId>(wide_keys_.size() - 1);
  }

  /// State s's cell and heading. Narrow keys decode in 32 bits (a 64-bit division costs
  /// several times more, and this runs for every expanded state).
  void at(StateId s, int* x, int* y, int* heading) const {
    std::uint32_t code;
    if (narrow_) {
      const std::uint32_t key = narrow_keys_[s];
      const std::uint32_t cell = key >> bits_, width = static_cast<std::uint32_t>(width_);
      code = key & static_cast<std::uint32_t>(mask_);
      *x = static_cast<int>(cell % width);
      *y = static_cast<int>(cell / width);
    } else {
      const std::uint64_t key = wide_keys_[s];
      const std::uint64_t cell = key >> bits_;
      code = static_cast<std::uint32_t>(key & mask_);
      *x = static_cast<int>(cell % width_);
      *y = static_cast<int>(cell / width_);
    }
    *heading = code == mask_ ? virtual_heading_ : static_cast<int>(code);
  }

 private:
  std::uint64_t width_;
  int virtual_heading_;
  int bits_ = 0;  // enough for every heading and one code more (all ones)
  std::uint64_t mask_ = 0;
  bool narrow_ = true;
  amha::detail::ReallocVector<std::uint32_t> narrow_keys_;
  amha::detail::ReallocVector<std::uint64_t> wide_keys_;
};

}  // namespace lattice
}  // namespace amha
