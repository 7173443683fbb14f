// Dial's bucket queue for the Dijkstra searches of the heuristics (integer keys, bounded steps).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace amha {
namespace lattice {
namespace detail {

// Dial's bucket queue: exact for integer keys when every step is below the bucket count, and
// O(1) per operation, which beats a heap when the steps are small (most maps).
class DialQueue {
 public:
  /// Every key pushed must lie in [k, k + max_step], k the last key popped, or `first` before
  /// the first pop (an A*'s first key is its heuristic).
  explicit DialQueue(std::uint32_t max_step, std::uint32_t first = 0) : cur_(first) {
    std::uint32_t n = 1;
    while (n <= max_step) n <<= 1;
    buckets_.resize(n);
    mask_ = n - 1;
  }
  bool empty() const { return size_ == 0; }
  void push(std::uint32_t key, std::uint32_t value) {
    buckets_[key & mask_].push_back(value);
    ++size_;
  }
  std::pair<std::uint32_t, std::uint32_t> pop() {
    while (buckets_[cur_ & mask_].empty()) ++cur_;
    std::vector<std::uint32_t>& b = buckets_[cur_ & mask_];
    const std::uint32_t v = b.back();
    b.pop_back();
    --size_;
    return {cur_, v};
  }
  std::uint32_t upcoming(std::size_t ahead, std::uint32_t fallback) const {
    const std::vector<std::uint32_t>& b = buckets_[cur_ & mask_];
    return b.size() > ahead ? b[b.size() - 1 - ahead] : fallback;
  }
  /// The key of the last pop (`first` before the first): the largest, the queue being monotone.
  std::uint32_t lastPopped() const { return cur_; }

 private:
  std::vector<std::vector<std::uint32_t>> buckets_;
  std::uint32_t mask_ = 0, cur_ = 0;
  std::size_t size_ = 0;
};

}  // namespace detail
}  // namespace lattice
}  // namespace amha
