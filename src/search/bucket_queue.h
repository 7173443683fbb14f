// The A-MHA* engine's queue for domains with small integer keys (the sliding tiles): one
// bucket per key value, each a LIFO stack of state ids in 64-byte blocks from a shared pool.
// Push and pop are O(1) (plus the walk to the next non-empty bucket) and touch one or two cache
// lines, where a heap of millions of entries walks a dozen levels per pop. An entry is a 4-byte
// id: its key is its bucket's. Like LazyQueue, entries are never changed in place; the engine
// skips stale ones.
//
// Keys are f * scale for a scale that makes them integers (f = g + w1 * h with integer g and h,
// so any w1 that is a multiple of 1 / scale). Ties in f go to the newest entry: in a domain
// with unit costs that is usually the deepest state, as the heap's smaller-h rule prefers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "big_array_allocator.h"
#include "amha_planner/search/types.h"

namespace amha {
namespace detail {

class BucketQueue {
 public:
  /// Keys f become buckets f * scale; every pushed f must make that an integer >= 0.
  explicit BucketQueue(double scale = 1.0) : scale_(scale) { clear(); }

  double scale() const { return scale_; }
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  /// The newest entry of the lowest non-empty bucket: its key and id.
  double topKey() const { return static_cast<double>(min_) / scale_; }
  StateId topId() const {
    const Block& b = blocks_[heads_[min_]];
    return b.ids[b.count - 1];
  }

  void push(double f, StateId id) {
    const std::size_t k = bucketOf(f);
    if (k >= heads_.size()) heads_.resize(std::max(k + 1, 2 * heads_.size()), kNone);
    std::uint32_t h = heads_[k];
    if (h == kNone || blocks_[h].count == kIds) {
      const std::uint32_t nb = newBlock();
      blocks_[nb].next = h;
      heads_[k] = h = nb;
    }
    Block& b = blocks_[h];
    b.ids[b.count++] = id;
    ++size_;
    if (k < min_) min_ = k;
  }

  void pop() {
    const std::uint32_t h = heads_[min_];
    Block& b = blocks_[h];
    if (--b.count == 0) {
      heads_[min_] = b.next;
      b.next = free_;
      free_ = h;
    }
    if (--size_ == 0) {
      min_ = kEmptyMin;
      return;
    }
    while (heads_[min_] == kNone) ++min_;  // some bucket above holds an entry
  }

  void clear() {
    heads_.assign(heads_.size(), kNone);
    blocks_.clear();
    free_ = kNone;
    size_ = 0;
    min_ = kEmptyMin;
  }

  /// Calls fn(f, id) for every entry (members and stale ones).
  template <typename F>
  void forEach(F&& fn) const {
    for (std::size_t k = 0; k < heads_.size(); ++k) {
      for (std::uint32_t h = heads_[k]; h != kNone; h = blocks_[h].next) {
        const Block& b = blocks_[h];
        for (std::uint32_t j = 0; j < b.count; ++j) fn(static_cast<double>(k) / scale_, b.ids[j]);
      }
    }
  }

  std::size_t memoryBytes() const {
    return blocks_.capacity() * sizeof(Block) + heads_.capacity() * sizeof(std::uint32_t);
  }
  /// Bytes push(f, ...) may allocate (0 unless the pool or the bucket array must grow).
  std::size_t growthBytes(double f) const {
    std::size_t bytes = 0;
    const std::size_t k = bucketOf(f);
    if (k >= heads_.size()) bytes += std::max(k + 1, 2 * heads_.size()) * sizeof(std::uint32_t);
    const bool needs_block = k >= heads_.size() || heads_[k] == kNone ||
                             blocks_[heads_[k]].count == kIds;
    if (needs_block && free_ == kNone && blocks_.size() == blocks_.capacity()) {
      bytes += std::max<std::size_t>(blocks_.capacity(), 1) * sizeof(Block);
    }
    return bytes;
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  static constexpr std::size_t kEmptyMin = static_cast<std::size_t>(-1);
  static constexpr std::uint32_t kIds = 14;
  struct Block {
    std::uint32_t next;   // the block below it in its bucket, or kNone
    std::uint32_t count;  // ids in use; the newest is ids[count - 1]
    std::uint32_t ids[kIds];
  };
  static_assert(sizeof(Block) == 64, "one block per cache line");

  std::size_t bucketOf(double f) const { return static_cast<std::size_t>(std::llround(f * scale_)); }

  std::uint32_t newBlock() {
    std::uint32_t b = free_;
    if (b != kNone) {
      free_ = blocks_[b].next;
    } else {
      b = static_cast<std::uint32_t>(blocks_.size());
      blocks_.emplace_back();
    }
    blocks_[b].count = 0;
    return b;
  }

  double scale_;
  std::vector<std::uint32_t> heads_;  // per key: its newest block, or kNone
  std::vector<Block, BigArrayAllocator<Block>> blocks_;
  std::uint32_t free_ = kNone;        // free blocks, linked through next
  std::size_t size_ = 0;
  std::size_t min_ = kEmptyMin;       // lowest non-empty bucket while size_ > 0
};

}  // namespace detail
}  // namespace amha
