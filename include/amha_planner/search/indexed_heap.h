// Indexed binary min-heap over dense state ids: O(log n) insert / decrease / increase / remove,
// O(1) membership, and a bulk rebuild (O(n) heapify) for re-keying between anytime iterations.
// Each id's position in the heap is kept either in the heap's own array or, to save cache
// misses, inside the caller's per-state records (bindPositions: a base pointer and a stride).
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
    if (own_pos_.size() < n) own_pos_.resize(n, kAbsent);
    base_ = own_pos_.data();
    stride_ = 1;
    ids_ = own_pos_.size();
  }

  /// Keeps positions in caller-owned memory instead: id's slot is base[id * stride], which must
  /// be kAbsent for ids not in the heap. Call again whenever that memory moves or grows.
  void bindPositions(std::uint32_t* base, std::size_t stride, std::size_t ids) {
    base_ = base;
    stride_ = stride;
    ids_ = ids;
  }
  std::size_t idCapacity() const { return ids_; }

  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  bool contains(StateId id) const { return id < ids_ && pos(id) != kAbsent; }
  const Entry& top() const { return heap_.front(); }
  const Key& keyOf(StateId id) const { return heap_[pos(id)].key; }
  const std::vector<Entry>& entries() const { return heap_; }
  Less& less() { return less_; }

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

  /// Appends without restoring heap order; call rebuild() before the next top()/pop().
  void appendUnordered(StateId id, const Key& key) {
    pos(id) = static_cast<std::uint32_t>(heap_.size());
    heap_.push_back(Entry{key, id});
  }

  /// Sets every key to key_of(id) and restores heap order in O(n).
  template <typename KeyOf>
  void rekey(KeyOf&& key_of) {
    for (Entry& e : heap_) e.key = key_of(e.id);
    rebuild();
  }

  /// Restores heap order (Floyd's heapify) after appendUnordered() or external key changes.
  void rebuild() {
    const std::size_t n = heap_.size();
    for (std::size_t i = 0; i < n; ++i) pos(heap_[i].id) = static_cast<std::uint32_t>(i);
    for (std::size_t i = n / 2; i-- > 0;) siftDown(static_cast<std::uint32_t>(i));
  }

  std::size_t memoryBytes() const {
    return heap_.capacity() * sizeof(Entry) + own_pos_.capacity() * sizeof(std::uint32_t);
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

  std::uint32_t& pos(StateId id) { return base_[static_cast<std::size_t>(id) * stride_]; }
  std::uint32_t pos(StateId id) const { return base_[static_cast<std::size_t>(id) * stride_]; }

  std::vector<Entry> heap_;
  std::vector<std::uint32_t> own_pos_;
  std::uint32_t* base_ = nullptr;
  std::size_t stride_ = 1;
  std::size_t ids_ = 0;
  Less less_;
};

}  // namespace amha
