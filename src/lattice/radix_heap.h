// Monotone integer priority queue for the Dijkstra searches of the heuristics.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace amha {
namespace lattice {
namespace detail {

// Monotone priority queue for integer keys (Ahuja et al.'s radix heap): pops never go below
// the last popped key, which Dijkstra guarantees.
class RadixHeap {
 public:
  bool empty() const { return size_ == 0; }
  void push(std::uint32_t key, std::uint32_t value) {
    buckets_[bucket(key)].push_back({key, value});
    ++size_;
  }
  std::pair<std::uint32_t, std::uint32_t> pop() {
    if (buckets_[0].empty()) {
      int i = 1;
      while (buckets_[i].empty()) ++i;
      std::uint32_t m = std::numeric_limits<std::uint32_t>::max();
      for (const auto& e : buckets_[i]) m = std::min(m, e.first);
      last_ = m;
      for (const auto& e : buckets_[i]) buckets_[bucket(e.first)].push_back(e);
      buckets_[i].clear();
    }
    const auto e = buckets_[0].back();
    buckets_[0].pop_back();
    --size_;
    return e;
  }
  /// The key of the last pop (0 before the first): the largest, the queue being monotone.
  std::uint32_t lastPopped() const { return last_; }
  /// The value popped `ahead` pops from now if no push comes first (else any value), for
  /// prefetching; `fallback` if unknown.
  std::uint32_t upcoming(std::size_t ahead, std::uint32_t fallback) const {
    const auto& b = buckets_[0];
    return b.size() > ahead ? b[b.size() - 1 - ahead].second : fallback;
  }

 private:
  int bucket(std::uint32_t key) const { return key == last_ ? 0 : 32 - __builtin_clz(key ^ last_); }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> buckets_[33];
  std::uint32_t last_ = 0;
  std::size_t size_ = 0;
};

}  // namespace detail
}  // namespace lattice
}  // namespace amha
