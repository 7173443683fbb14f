// One OPEN queue of the A-MHA* engine: a bucket queue when the domain's keys are small integers
// (after scaling) and a 4-ary heap otherwise. The engine picks the kind whenever the queue is
// empty (at the start of every ImprovePath iteration, since w1 changes the keys' scale).
#pragma once

#include <cmath>
#include <cstddef>

#include "bucket_queue.h"
#include "lazy_queue.h"

namespace amha {
namespace detail {

class OpenQueue {
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

  /// Empties the queue and makes it a bucket queue with this scale, or a heap if scale is 0.
  /// Both kinds keep their memory, so the iterations of an anytime search reuse it.
  void reset(double bucket_scale) {
    heap_.clear();
    buckets_.reset(bucket_scale > 0 ? bucket_scale : 1.0);
    use_buckets_ = bucket_scale > 0;
  }
  void clear() { use_buckets_ ? buckets_.clear() : heap_.clear(); }

  bool usesBuckets() const { return use_buckets_; }
  bool empty() const { return use_buckets_ ? buckets_.empty() : heap_.empty(); }
  double topKey() const { return use_buckets_ ? buckets_.topKey() : heap_.top().f; }
  StateId topId() const { return use_buckets_ ? buckets_.topId() : heap_.top().id; }

  void push(const QueueEntry& e) { use_buckets_ ? buckets_.push(e.f, e.h, e.id) : heap_.push(e); }
  /// push(e) if that allocates nothing, else false (see growthBytes).
  bool tryPush(const QueueEntry& e) {
    return use_buckets_ ? buckets_.tryPush(e.f, e.h, e.id) : heap_.tryPush(e);
  }
  void pop() { use_buckets_ ? buckets_.pop() : heap_.pop(); }

  /// Adds without ordering; call restoreOrder() before the next top or pop.
  void appendUnordered(const QueueEntry& e) {
    use_buckets_ ? buckets_.push(e.f, e.h, e.id) : heap_.appendUnordered(e);
  }
  void restoreOrder() {
    if (!use_buckets_) heap_.heapify();
  }

  /// Calls fn(f, id) for every entry (members and stale ones).
  template <typename F>
  void forEach(F&& fn) const {
    if (use_buckets_) {
      buckets_.forEach(fn);
    } else {
      for (const QueueEntry& e : heap_) fn(e.f, e.id);
    }
  }

  std::size_t memoryBytes() const { return heap_.memoryBytes() + buckets_.memoryBytes(); }
  /// Bytes push(e) may allocate.
  std::size_t growthBytes(const QueueEntry& e) const {
    return use_buckets_ ? buckets_.growthBytes(e.f, e.h) : heap_.growthBytes();
  }

 private:
  bool use_buckets_ = false;
  LazyQueue heap_;
  BucketQueue buckets_;
};

}  // namespace detail
}  // namespace amha
