// The indexed heap against std::set under random pushes, key changes, removals, and bulk
// removals with rebuilds; a rebuild that is told to stop gives up and leaves a clearable heap.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "amha_planner/search/detail/indexed_heap.h"

namespace amha {
namespace {

TEST(IndexedHeap, MatchesReferenceUnderRandomOperations) {
  std::mt19937 rng(7);
  IndexedHeap<double> heap;
  const StateId n = 500;
  heap.reserveIds(n);
  std::set<std::pair<double, StateId>> ref;
  std::vector<double> key(n, -1);
  for (int step = 0; step < 20000; ++step) {
    const StateId id = rng() % n;
    const int op = rng() % 10;
    if (op < 6) {
      const double k = static_cast<double>(rng() % 1000);
      if (key[id] >= 0) ref.erase({key[id], id});
      key[id] = k;
      ref.insert({k, id});
      heap.push(id, k);
    } else if (op < 8) {
      if (key[id] >= 0) ref.erase({key[id], id});
      key[id] = -1;
      heap.remove(id);
    } else if (op == 8 && !ref.empty()) {
      const double top = heap.top().key;
      ASSERT_EQ(top, ref.begin()->first);
      const StateId popped = heap.pop();
      ASSERT_EQ(key[popped], top);
      ref.erase({key[popped], popped});
      key[popped] = -1;
    } else {
      // Drop every key above a threshold in one pass and rebuild.
      const double cut = static_cast<double>(rng() % 1000);
      heap.removeIf([&](const IndexedHeap<double>::Entry& e) { return e.key > cut; });
      heap.rebuild();
      ref.clear();
      for (StateId s = 0; s < n; ++s) {
        if (key[s] > cut) key[s] = -1;
        if (key[s] >= 0) ref.insert({key[s], s});
      }
    }
    ASSERT_EQ(heap.size(), ref.size());
    for (StateId s = 0; s < 5; ++s) {
      ASSERT_EQ(heap.contains(s), key[s] >= 0);
    }
    if (!ref.empty()) {
      ASSERT_EQ(heap.top().key, ref.begin()->first);
    }
  }
}

TEST(IndexedHeap, RebuildStopsWhenToldAndTheHeapCanThenBeCleared) {
  IndexedHeap<double> heap;
  const StateId n = 300000;  // several 2^16-entry stretches
  heap.reserveIds(n);
  for (StateId s = 0; s < n; ++s) heap.push(s, static_cast<double>((s * 7919u) % n));
  heap.removeIf([](const IndexedHeap<double>::Entry& e) { return e.id % 3 == 0; });
  std::size_t asked = 0;
  EXPECT_FALSE(heap.rebuild([&](std::size_t) { return ++asked == 2; }));
  EXPECT_EQ(asked, 2u);
  heap.clear();
  EXPECT_TRUE(heap.empty());
  for (StateId s = 0; s < n; ++s) ASSERT_FALSE(heap.contains(s)) << s;

  for (StateId s = 0; s < n; ++s) heap.push(s, static_cast<double>((s * 7919u) % n));
  heap.removeIf([](const IndexedHeap<double>::Entry& e) { return e.id % 3 == 0; });
  EXPECT_TRUE(heap.rebuild([](std::size_t) { return false; }));
  EXPECT_EQ(heap.size(), n - (n + 2) / 3);
  double last = -1;
  while (!heap.empty()) {
    const double k = heap.top().key;
    ASSERT_GE(k, last);
    last = k;
    ASSERT_NE(heap.pop() % 3, 0u);
  }
}

}  // namespace
}  // namespace amha
