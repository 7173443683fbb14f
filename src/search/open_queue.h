// One OPEN queue of the A-MHA* engine: a bucket queue when the keys are integers after scaling
// (nested per key and h when they are small, as the tiles'; one stack per key when they are
// large, as the lattice's) and a 4-ary heap otherwise. The engine picks the kind whenever the
// queue is empty (at the start of every ImprovePath iteration, since w1 changes the keys' scale).
#pragma once

#include <cmath>
#include <cstddef>

#include "bucket_queue.h"
#include "key_bucket_queue.h"
#include "lazy_queue.h"

namespace amha {
namespace detail {

class OpenQueue {
 public:
  enum class Kind {
    kHeap,        // any keys
    kBuckets,     // small integer keys, ties to the smaller h (BucketQueue)
    kKeyBuckets,  // integer keys of any size, ties newest first (KeyBucketQueue)
  };

 private:
  // Calls fn on the queue of the current kind (self: *this, const or not). Defined before its
  // callers, as its return type is deduced.
  template <class Self, typename F>
  static decltype(auto) visit(Self& self, F&& fn) {
    switch (self.kind_) {
      case Kind::kBuckets:
        return fn(self.buckets_);
      case Kind::kKeyBuckets:
        return fn(self.key_buckets_);
      default:
        return fn(self.heap_);
    }
  }

 public:
  /// The smallest scale in 1, 2, 4, ..., 64 that makes every key g + w1 * h an integer for
  /// integer g and h, or 0 if there is none (then only a heap can hold the keys).
  static double bucketScaleFor(double w1) {
    for (double s = 1; s <= 64; s *= 2) {
      const double k = w1 * s;
      if (k == std::floor(k) && k < 1e6) return s;
    }
    return 0;
  }

  /// Empties the queue and makes it of this kind; a bucket kind takes keys f * bucket_scale
  /// (bucketScaleFor). Every kind keeps its memory, so the iterations of an anytime search
  /// reuse it.
  void reset(Kind kind, double bucket_scale = 1.0) {
    heap_.clear();
    buckets_.reset(kind == Kind::kBuckets ? bucket_scale : 1.0);
    key_buckets_.reset(kind == Kind::kKeyBuckets ? bucket_scale : 1.0);
    kind_ = kind;
  }
  void clear() {
    visit(*this, [](auto& q) { q.clear(); });
  }

  Kind kind() const { return kind_; }
  bool empty() const {
    return visit(*this, [](const auto& q) { return q.empty(); });
  }
  double topKey() const {
    return visit(*this, [](const auto& q) { return q.topKey(); });
  }
  StateId topId() const {
    return visit(*this, [](const auto& q) { return q.topId(); });
  }

  void push(const QueueEntry& e) {
    visit(*this, [&](auto& q) { q.push(e.f, e.h, e.id); });
  }
  /// push(e) if that allocates nothing, else false (see growthBytes).
  bool tryPush(const QueueEntry& e) {
    return visit(*this, [&](auto& q) { return q.tryPush(e.f, e.h, e.id); });
  }
  void pop() {
    visit(*this, [](auto& q) { q.pop(); });
  }

  /// Adds without ordering; call restoreOrder() before the next top or pop.
  void appendUnordered(const QueueEntry& e) {
    kind_ == Kind::kHeap ? heap_.appendUnordered(e) : push(e);
  }
  void restoreOrder() {
    if (kind_ == Kind::kHeap) heap_.heapify();
  }

  /// Calls fn(f, id) for every entry (members and stale ones).
  template <typename F>
  void forEach(F&& fn) const {
    visit(*this, [&](const auto& q) { q.forEach(fn); });
  }

  std::size_t memoryBytes() const {
    return heap_.memoryBytes() + buckets_.memoryBytes() + key_buckets_.memoryBytes();
  }
  /// Bytes push(e) may allocate.
  std::size_t growthBytes(const QueueEntry& e) const {
    switch (kind_) {
      case Kind::kBuckets:
        return buckets_.growthBytes(e.f, e.h);
      case Kind::kKeyBuckets:
        return key_buckets_.growthBytes(e.f);
      default:
        return heap_.growthBytes();
    }
  }

 private:
  Kind kind_ = Kind::kHeap;
  LazyQueue heap_;
  BucketQueue buckets_;
  KeyBucketQueue key_buckets_;
};

}  // namespace detail
}  // namespace amha
