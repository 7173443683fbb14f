// The A-MHA* engine's queue for domains with small integer keys (the sliding tiles): nested
// buckets, one per key value f and, inside it, one per heuristic value h, so that pops come in
// (f, h) order like the heap's (smaller h first: the deeper state among equal f), newest first
// among equal (f, h). Each (f, h) bucket is a stack of 4-byte state ids (id_stacks.h). Push and pop
// touch a few cache lines, where a heap of millions of entries walks a dozen levels per pop. Like
// LazyQueue, entries are never changed in place; the engine skips stale ones.
//
// Keys are f * scale for a scale that makes them integers (f = g + w1 * h with integer g and h,
// so any w1 that is a multiple of 1 / scale).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "amha_planner/search/types.h"
#include "id_stacks.h"

namespace amha {
namespace detail {

class BucketQueue {
 public:
  /// Keys f become buckets f * scale; every pushed f must make that an integer >= 0.
  explicit BucketQueue(double scale = 1.0) : scale_(scale) { clear(); }

  /// Empties the queue for keys of another scale; its memory stays for reuse.
  void reset(double scale) {
    scale_ = scale;
    clear();
  }

  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  /// The newest entry of the lowest non-empty (f, h) bucket: its key and id.
  double topKey() const { return static_cast<double>(min_) / scale_; }
  StateId topId() const {
    const FBucket& fb = f_[min_];
    return stacks_.top(fb.heads[fb.min_h - fb.base]);
  }

  void push(double f, HeuristicValue h, StateId id) {
    const std::size_t k = bucketOf(f);
    if (k >= f_.size()) f_.resize(std::max(k + 1, 2 * f_.size()));
    FBucket& fb = f_[k];
    const std::size_t before = fb.heads.capacity();
    std::uint32_t& head = fb.slot(h);
    stack_heads_ += fb.heads.capacity() - before;
    stacks_.push(head, id);
    count(k, fb, h);
  }

  /// push() when it allocates nothing (its stack exists and its newest block has room, the
  /// common case); otherwise false and nothing changes. Saves a growthBytes() lookup per push.
  bool tryPush(double f, HeuristicValue h, StateId id) {
    const std::size_t k = bucketOf(f);
    if (!stackHasRoom(k, h)) return false;
    FBucket& fb = f_[k];
    stacks_.push(fb.heads[h - fb.base], id);
    count(k, fb, h);
    return true;
  }

  void pop() {
    FBucket& fb = f_[min_];
    stacks_.pop(fb.heads[fb.min_h - fb.base]);
    --size_;
    if (--fb.count > 0) {
      while (fb.heads[fb.min_h - fb.base] == kNone) ++fb.min_h;  // a stack above is non-empty
    } else if (size_ == 0) {
      min_ = kEmptyMin;
    } else {
      while (f_[min_].count == 0) ++min_;  // some bucket above holds an entry
    }
  }

  void clear() {
    for (FBucket& fb : f_) fb.reset();
    stacks_.clear();
    size_ = 0;
    min_ = kEmptyMin;
  }

  /// Calls fn(f, id) for every entry (members and stale ones).
  template <typename F>
  void forEach(F&& fn) const {
    for (std::size_t k = 0; k < f_.size(); ++k) {
      if (f_[k].count == 0) continue;
      const double f = static_cast<double>(k) / scale_;
      for (std::uint32_t head : f_[k].heads) stacks_.forEach(head, [&](StateId id) { fn(f, id); });
    }
  }

  std::size_t memoryBytes() const {
    return stacks_.memoryBytes() + f_.capacity() * sizeof(FBucket) +
           stack_heads_ * sizeof(std::uint32_t);
  }
  /// Bytes push(f, h, ...) may allocate (0 unless the pool or a bucket array must grow).
  std::size_t growthBytes(double f, HeuristicValue h) const {
    const std::size_t k = bucketOf(f);
    std::size_t bytes = 0;
    if (k >= f_.size()) {
      bytes += std::max(k + 1, 2 * f_.size()) * sizeof(FBucket) + sizeof(std::uint32_t);
    } else if (stackHasRoom(k, h)) {
      return 0;  // the common case: the stack's newest block has room
    } else if (f_[k].spanWith(h) > f_[k].heads.capacity()) {
      bytes += 2 * f_[k].spanWith(h) * sizeof(std::uint32_t);
    }
    // Past this point the push takes a new block.
    return bytes + stacks_.newBlockBytes();
  }

 private:
  static constexpr std::uint32_t kNone = IdStacks::kNone;
  static constexpr std::size_t kEmptyMin = static_cast<std::size_t>(-1);

  // The entries of one key value: a stack per h in [base, base + heads.size()). The array
  // keeps its capacity when the bucket empties, so a warmed-up search allocates nothing.
  struct FBucket {
    std::vector<std::uint32_t> heads;  // per h - base: its newest block, or kNone
    HeuristicValue base = 0;
    HeuristicValue min_h = 0;  // lowest non-empty stack while count > 0
    std::size_t count = 0;     // entries in the bucket

    void reset() {
      std::fill(heads.begin(), heads.end(), kNone);
      count = 0;
    }
    // The number of stacks the array must span to hold h as well.
    std::size_t spanWith(HeuristicValue h) const {
      if (count == 0 || heads.empty()) return 1;
      if (h < base) return heads.size() + (base - h);
      return std::max<std::size_t>(heads.size(), h - base + 1);
    }
    std::uint32_t& slot(HeuristicValue h) {
      if (count == 0) {
        // Empty: every stack is kNone, so the array can be re-based at h for free.
        if (heads.empty()) heads.push_back(kNone);
        base = h;
      } else if (h < base) {
        heads.insert(heads.begin(), base - h, kNone);
        base = h;
      } else if (h - base >= heads.size()) {
        heads.resize(h - base + 1, kNone);
      }
      return heads[h - base];
    }
  };

  // f * scale is a whole number (up to rounding in the product), so adding 0.5 and truncating
  // rounds it; std::llround is a library call.
  std::size_t bucketOf(double f) const { return static_cast<std::size_t>(f * scale_ + 0.5); }

  // True if the stack for key bucket k and h exists and a push there allocates nothing.
  bool stackHasRoom(std::size_t k, HeuristicValue h) const {
    if (k >= f_.size()) return false;
    const FBucket& fb = f_[k];
    if (fb.count == 0 || h < fb.base || h - fb.base >= fb.heads.size()) return false;
    return stacks_.hasRoom(fb.heads[h - fb.base]);
  }

  // Counts an id just pushed on fb's stack for h (fb is key bucket k).
  void count(std::size_t k, FBucket& fb, HeuristicValue h) {
    if (fb.count++ == 0 || h < fb.min_h) fb.min_h = h;
    ++size_;
    if (k < min_) min_ = k;
  }

  double scale_;
  std::vector<FBucket> f_;  // per key f * scale
  IdStacks stacks_;
  std::size_t size_ = 0;
  std::size_t min_ = kEmptyMin;  // lowest non-empty key bucket while size_ > 0
  std::size_t stack_heads_ = 0;  // capacity of all FBucket::heads arrays together
};

}  // namespace detail
}  // namespace amha
