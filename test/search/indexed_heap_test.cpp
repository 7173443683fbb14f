// The indexed heap against std::set under random pushes, key changes, removals and rebuilds.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "amha_planner/search/indexed_heap.h"

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
      // Re-key everything with a new function and rebuild.
      heap.rekey([&](StateId s) { return key[s] = 1000 - key[s]; });
      ref.clear();
      for (StateId s = 0; s < n; ++s) {
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

}  // namespace
}  // namespace amha
