// The A-MHA* engine's queue for integer keys of any range (the lattice's costs, in millimetres:
// keys of tens of thousands and more): one stack of state ids per key value (id_stacks.h),
// newest first among equal keys, and the keys past kMaxBuckets in a heap. Where the 4-ary heap
// walks ten levels of cache misses per pop, a pop here reads one block and, when its key runs
// out, scans the next few keys; an entry takes 4 bytes instead of the heap's 16.
//
// Why not bucket_queue.h's nested (f, h) buckets: a lattice key's states have h values spread
// over the whole path's cost, and an array per key spanning them would hold megabytes. Ties
// broken newest-first instead of towards the smaller h change little on the lattice (A* on the
// bundled Willow Garage map: 559,253 expansions instead of 559,235), unlike on the tiles.
//
// Keys are f * scale for a scale that makes them integers (f = g + w1 * h + (w1 - 1) * b with
// integer g, h and b, so any w1 that is a multiple of 1 / scale).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "amha_planner/search/detail/realloc_vector.h"
#include "amha_planner/search/types.h"
#include "id_stacks.h"
#include "lazy_queue.h"

namespace amha {
namespace detail {

class KeyBucketQueue {
 public:
  /// Keys at or past this many buckets go to the heap: 16 MB of stack heads at most.
  static constexpr std::size_t kMaxBuckets = std::size_t{1} << 22;

  explicit KeyBucketQueue(double scale = 1.0) : scale_(scale) { clear(); }

  /// Empties the queue for keys of another scale; its memory stays for reuse.
  void reset(double scale) {
    scale_ = scale;
    clear();
  }

  bool empty() const { return size_ == 0 && overflow_.empty(); }

  /// The lowest key's newest entry (every bucket's key is below every heap entry's).
  double topKey() const {
    return size_ > 0 ? static_cast<double>(min_) / scale_ : overflow_.top().f;
  }
  StateId topId() const { return size_ > 0 ? stacks_.top(heads_[min_]) : overflow_.top().id; }

  void push(double f, HeuristicValue h, StateId id) {
    const std::size_t k = bucketOf(f);
    if (k >= kMaxBuckets) {
      overflow_.push(QueueEntry{f, h, id});
      return;
    }
    if (k >= heads_.size()) grow(k);
    stacks_.push(heads_[k], id);
    counted(k);
  }

  /// push() when it allocates nothing (the key's stack has room, the common case); otherwise
  /// false and nothing changes.
  bool tryPush(double f, HeuristicValue h, StateId id) {
    const std::size_t k = bucketOf(f);
    if (k >= kMaxBuckets) return overflow_.tryPush(QueueEntry{f, h, id});
    if (k >= heads_.size() || !stacks_.hasRoom(heads_[k])) return false;
    stacks_.push(heads_[k], id);
    counted(k);
    return true;
  }

  void pop() {
    if (size_ == 0) {
      overflow_.pop();
      return;
    }
    stacks_.pop(heads_[min_]);
    if (--size_ == 0) {
      min_ = kEmptyMin;
    } else {
      while (heads_[min_] == IdStacks::kNone) ++min_;  // some key above holds an entry
    }
  }

  void clear() {
    std::fill(heads_.data(), heads_.data() + heads_.size(), IdStacks::kNone);
    stacks_.clear();
    overflow_.clear();
    size_ = 0;
    min_ = kEmptyMin;
  }

  /// Calls fn(f, id) for every entry (members and stale ones).
  template <typename F>
  void forEach(F&& fn) const {
    for (std::size_t k = 0; k < heads_.size(); ++k) {
      const double f = static_cast<double>(k) / scale_;
      stacks_.forEach(heads_[k], [&](StateId id) { fn(f, id); });
    }
    for (const QueueEntry& e : overflow_) fn(e.f, e.id);
  }

  std::size_t memoryBytes() const {
    return stacks_.memoryBytes() + heads_.capacity() * sizeof(std::uint32_t) +
           overflow_.memoryBytes();
  }
  /// Bytes push(f, ...) may allocate (0 unless the heads, the pool or the heap must grow).
  std::size_t growthBytes(double f) const {
    const std::size_t k = bucketOf(f);
    if (k >= kMaxBuckets) return overflow_.growthBytes();
    std::size_t bytes = 0;
    if (k >= heads_.size()) {
      bytes += newHeadCount(k) * sizeof(std::uint32_t);
    } else if (stacks_.hasRoom(heads_[k])) {
      return 0;
    }
    return bytes + stacks_.newBlockBytes();
  }

 private:
  static constexpr std::size_t kEmptyMin = static_cast<std::size_t>(-1);

  // f * scale is a whole number up to rounding in the product (see bucket_queue.h).
  std::size_t bucketOf(double f) const { return static_cast<std::size_t>(f * scale_ + 0.5); }

  std::size_t newHeadCount(std::size_t k) const {
    return std::min(std::max(k + 1, 2 * heads_.size()), kMaxBuckets);
  }
  void grow(std::size_t k) {
    const std::size_t old = heads_.size();
    heads_.resize(newHeadCount(k));
    std::fill(heads_.data() + old, heads_.data() + heads_.size(), IdStacks::kNone);
  }

  void counted(std::size_t k) {
    ++size_;
    if (k < min_) min_ = k;
  }

  double scale_;
  ReallocVector<std::uint32_t> heads_;  // per key f * scale below kMaxBuckets: its stack
  IdStacks stacks_;
  LazyQueue overflow_;           // the keys from kMaxBuckets on
  std::size_t size_ = 0;         // entries in the buckets
  std::size_t min_ = kEmptyMin;  // lowest non-empty bucket while size_ > 0
};

}  // namespace detail
}  // namespace amha
