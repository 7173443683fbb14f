// The A-MHA* engine's queue for keys of any size (see open_queue.h): a 4-ary min-heap of
// 16-byte (f, h, id) entries with no position index. Entries are never changed or removed in
// place: a state whose key drops is pushed again, and the engine skips entries that no longer
// describe a member when they reach the top (the engine keeps membership in its per-state
// records). Compared with an indexed binary heap this never writes into other states' records
// while sifting, removes a state from every queue in O(1), and keeps a node's four children in
// one cache line.
#pragma once

#include <cstddef>
#include <cstdint>

#include "amha_planner/search/detail/realloc_vector.h"
#include "amha_planner/search/types.h"

namespace amha {
namespace detail {

/// Key f = g + w1 * h, ties broken towards the smaller h (deeper states), which matters in
/// domains with many equal f-values such as the sliding tiles.
struct QueueEntry {
  double f;
  HeuristicValue h;
  StateId id;
};
static_assert(sizeof(QueueEntry) == 16, "four entries per cache line");

inline bool before(const QueueEntry& a, const QueueEntry& b) {
  return a.f < b.f || (a.f == b.f && a.h < b.h);
}

class LazyQueue {
 public:
  LazyQueue() { clear(); }

  bool empty() const { return store_.size() == kPad; }
  std::size_t size() const { return store_.size() - kPad; }
  const QueueEntry& top() const { return store_[kPad]; }
  // The bucket queues' surface (OpenQueue dispatches to either kind alike).
  double topKey() const { return top().f; }
  StateId topId() const { return top().id; }
  void push(double f, HeuristicValue h, StateId id) { push(QueueEntry{f, h, id}); }
  bool tryPush(double f, HeuristicValue h, StateId id) { return tryPush(QueueEntry{f, h, id}); }
  /// Calls fn(f, id) for every entry (members and stale ones).
  template <typename F>
  void forEach(F&& fn) const {
    for (const QueueEntry& e : *this) fn(e.f, e.id);
  }

  /// Raw entries (members and stale ones), in heap order.
  const QueueEntry* begin() const { return store_.data() + kPad; }
  const QueueEntry* end() const { return store_.data() + store_.size(); }

  void push(const QueueEntry& e) {
    store_.push_back(e);
    siftUp(size() - 1);
  }

  /// push() when the storage has room; otherwise false and nothing changes.
  bool tryPush(const QueueEntry& e) {
    if (store_.size() == store_.capacity()) return false;
    push(e);
    return true;
  }

  void pop() {
    QueueEntry* a = heap();
    const std::size_t n = size() - 1;
    if (n > 0) {
      const QueueEntry last = a[n];
      store_.pop_back();
      siftDown(last, 0, n);
    } else {
      store_.pop_back();
    }
  }

  void clear() {
    store_.resize(kPad);  // the padding puts every group of four siblings on one cache line
  }

  /// Appends without restoring heap order; call heapify() before the next top()/pop().
  void appendUnordered(const QueueEntry& e) { store_.push_back(e); }

  /// Restores heap order in O(n) (Floyd).
  void heapify() {
    const std::size_t n = size();
    if (n < 2) return;
    QueueEntry* a = heap();
    for (std::size_t i = (n - 2) / 4 + 1; i-- > 0;) siftDown(a[i], i, n);
  }

  std::size_t memoryBytes() const { return store_.capacity() * sizeof(QueueEntry); }
  /// Bytes the next push() allocates (0 unless the storage is full and must double).
  std::size_t growthBytes() const {
    return store_.size() < store_.capacity() ? 0 : store_.capacity() * sizeof(QueueEntry);
  }

 private:
  // The root is store_[kPad]; node i's children are 4i+1..4i+4, i.e. store_[4(i+1)..4(i+1)+3],
  // which start on a 64-byte boundary because store_ is aligned to 64 bytes.
  static constexpr std::size_t kPad = 3;

  QueueEntry* heap() { return store_.data() + kPad; }

  void siftUp(std::size_t i) {
    QueueEntry* a = heap();
    const QueueEntry e = a[i];
    while (i > 0) {
      const std::size_t parent = (i - 1) / 4;
      if (!before(e, a[parent])) break;
      a[i] = a[parent];
      i = parent;
    }
    a[i] = e;
  }

  // Places e at hole i of a heap of n entries.
  void siftDown(const QueueEntry e, std::size_t i, std::size_t n) {
    QueueEntry* a = heap();
    for (;;) {
      const std::size_t c = 4 * i + 1;
      if (c >= n) break;
      // The walk down is a chain of dependent cache misses; fetch the next level (the four
      // children's groups, one line each) while this one is compared.
      const std::size_t g = 4 * c + 1;
      for (std::size_t k = 0; k < 4 && g + 4 * k < n; ++k) __builtin_prefetch(a + g + 4 * k);
      std::size_t best = c;
      const std::size_t last = c + 4 < n ? c + 4 : n;
      for (std::size_t k = c + 1; k < last; ++k) {
        if (before(a[k], a[best])) best = k;
      }
      if (!before(a[best], e)) break;
      a[i] = a[best];
      i = best;
    }
    a[i] = e;
  }

  ReallocVector<QueueEntry> store_;
};

}  // namespace detail
}  // namespace amha
