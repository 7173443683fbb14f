// Helpers shared by the queue tests.
#pragma once

#include <utility>
#include <vector>

#include "amha_planner/search/types.h"

namespace amha {
namespace detail {

/// Pushes six entries over three keys in steps of 0.5, with equal keys of different h and of
/// equal h: ids 1..6, keys 3, 1.5, 3, 1.5, 0, 3 and h 2, 1, 1, 1, 0, 2.
template <class Queue>
void pushSampleEntries(Queue& q) {
  q.push(3.0, 2, 1);
  q.push(1.5, 1, 2);
  q.push(3.0, 1, 3);
  q.push(1.5, 1, 4);
  q.push(0.0, 0, 5);
  q.push(3.0, 2, 6);
}

/// Pops a queue (BucketQueue, KeyBucketQueue) empty: its (key, id) pairs in pop order.
template <class Queue>
std::vector<std::pair<double, StateId>> drainQueue(Queue& q) {
  std::vector<std::pair<double, StateId>> popped;
  while (!q.empty()) {
    popped.emplace_back(q.topKey(), q.topId());
    q.pop();
  }
  return popped;
}

}  // namespace detail
}  // namespace amha
