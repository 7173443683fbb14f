// Indexed binary min-heap over dense state ids: O(log n) insert / decrease / increase / remove,
// O(1) membership, and bulk removal and rebuild (O(n) heapify) for ANA*'s prune at each new
// incumbent.
// ANA* uses it: its keys change with every new incumbent. (A-MHA*'s queues are lazy_queue.h.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "amha_planner/search/types.h"

namespace amha {

template <typename Key, typename Less = std::less<Key>>
class IndexedHeap {
 public:
  struct Entry {
    Key key;
    StateId id;
  };

  explicit IndexedHeap(Less less = Less()) : less_(std::move(less)) {}

  static constexpr std::uint32_t kAbsent = 0xFFFFFFFFu;

  /// Makes ids [0, n) addressable in the heap's own position array. Call as the state space
  /// grows (amortised, not per push).
  void reserveIds(std::size_t n) {
    if (pos_.size() < n) pos_.resize(n, kAbsent);
  }

  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  bool contains(StateId id) const { return id < pos_.size() && pos_[id] != kAbsent; }
  const Entry& top() const { return heap_.front(); }
  const std::vector<Entry>& entries() const { return heap_; }

  /// Inserts `id` or changes its key (up or down).
  void push(StateId id, const Key& key) {
    std::uint32_t p = pos(id);
    if (p == kAbsent) {
      p = static_cast<std::uint32_t>(heap_.size());
      heap_.push_back(Entry{key, id});
      pos(id) = p;
      siftUp(p);
      return;
    }
    const bool decreased = less_(key, heap_[p].key);
    heap_[p].key = key;
    if (decreased) {
      siftUp(p);
    } else {
      siftDown(p);
    }
  }

  void remove(StateId id) {
    const std::uint32_t p = pos(id);
    if (p == kAbsent) return;
    pos(id) = kAbsent;
    const std::uint32_t last = static_cast<std::uint32_t>(heap_.size() - 1);
    if (p != last) {
      heap_[p] = heap_[last];
      pos(heap_[p].id) = p;
      heap_.pop_back();
      siftDown(p);
      siftUp(p);
    } else {
      heap_.pop_back();
    }
  }

  StateId pop() {
    const StateId id = heap_.front().id;
    remove(id);
    return id;
  }

  void clear() {
    for (const Entry& e : heap_) pos(e.id) = kAbsent;
    heap_.clear();
  }

  /// Removes, in one pass, every entry for which drop(entry) is true. The others stay, but
  /// out of order and with stale positions: call rebuild() before any other operation.
  template <typename Drop>
  void removeIf(Drop&& drop) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < heap_.size(); ++i) {
      if (drop(heap_[i])) {
        pos(heap_[i].id) = kAbsent;
      } else {
        heap_[kept++] = heap_[i];
      }
    }
    heap_.resize(kept);
  }

  /// Restores heap order (Floyd's heapify) after removals or key changes made in bulk.
  void rebuild() {
    rebuild([](std::size_t) { return false; });
  }
  /// The same, asking stop(k) every 2^16 entries whether to give up (a heap of tens of
  /// millions takes long): false if it did. The heap then holds its entries out of order and
  /// may only be cleared.
  template <typename Stop>
  bool rebuild(Stop&& stop) {
    const std::size_t n = heap_.size();
    for (std::size_t i = 0; i < n; ++i) {
      if ((i & 0xFFFFu) == 0 && i > 0 && stop(i)) return false;
      pos(heap_[i].id) = static_cast<std::uint32_t>(i);
    }
    for (std::size_t i = n / 2; i-- > 0;) {
      if ((i & 0xFFFFu) == 0 && i > 0 && stop(i)) return false;
      siftDown(static_cast<std::uint32_t>(i));
    }
    return true;
  }

  std::size_t memoryBytes() const {
    return heap_.capacity() * sizeof(Entry) + pos_.capacity() * sizeof(std::uint32_t);
  }

 private:
  void siftUp(std::uint32_t p) {
    Entry e = heap_[p];
    while (p > 0) {
      const std::uint32_t parent = (p - 1) / 2;
      if (!less_(e.key, heap_[parent].key)) break;
      heap_[p] = heap_[parent];
      pos(heap_[p].id) = p;
      p = parent;
    }
    heap_[p] = e;
    pos(e.id) = p;
  }

  void siftDown(std::uint32_t p) {
    const std::uint32_t n = static_cast<std::uint32_t>(heap_.size());
    Entry e = heap_[p];
    for (;;) {
      std::uint32_t c = 2 * p + 1;
      if (c >= n) break;
      if (c + 1 < n && less_(heap_[c + 1].key, heap_[c].key)) ++c;
      if (!less_(heap_[c].key, e.key)) break;
      heap_[p] = heap_[c];
      pos(heap_[p].id) = p;
      p = c;
    }
    heap_[p] = e;
    pos(e.id) = p;
  }

  std::uint32_t& pos(StateId id) { return pos_[id]; }

  std::vector<Entry> heap_;
  std::vector<std::uint32_t> pos_;  // heap position of each id, kAbsent if not in the heap
  Less less_;
};

}  // namespace amha
