// The per-key bucket queue against a reference (a sorted list): pops come in key order, newest
// first among equal keys, also when keys are pushed below the current minimum, when they pass
// the buckets into the overflow heap, and after the queue is emptied and refilled; tryPush
// pushes exactly when nothing must be allocated, and the memory it reports covers what it holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

#include "../../src/search/key_bucket_queue.h"
#include "queue_test_util.h"

namespace amha {
namespace detail {
namespace {

TEST(KeyBucketQueue, PopsInKeyOrderNewestFirstWhateverTheH) {
  KeyBucketQueue q(2.0);  // keys in steps of 0.5
  pushSampleEntries(q);
  const std::vector<std::pair<double, StateId>> popped = drainQueue(q);
  const std::vector<std::pair<double, StateId>> expected = {{0.0, 5}, {1.5, 4}, {1.5, 2},
                                                            {3.0, 6}, {3.0, 3}, {3.0, 1}};
  EXPECT_EQ(popped, expected);
}

TEST(KeyBucketQueue, MatchesSortedReferenceUnderRandomPushesAndPops) {
  std::mt19937 rng(11);
  KeyBucketQueue q(1.0);
  const double far = static_cast<double>(KeyBucketQueue::kMaxBuckets);
  // Reference entries (key, push order): the smallest key, then the latest push. Keys in the
  // overflow heap are all distinct here (the heap breaks their ties by h, not by age).
  std::vector<std::pair<double, long>> ref;
  auto before = [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second > b.second;
  };
  long order = 0;
  std::size_t overflowed = 0;
  for (int step = 0; step < 40000; ++step) {
    if (ref.empty() || rng() % 100 < 55) {
      // Keys rise over time but often drop below the current minimum, as in a search (and in
      // an inadmissible queue's); a few pass every bucket.
      double f = std::max(0.0, step * 5.0 + static_cast<double>(rng() % 2000) - 1000.0);
      if (rng() % 50 == 0) {
        f = far + static_cast<double>(order);
        ++overflowed;
      }
      const auto h = static_cast<HeuristicValue>(rng() % 40);
      if (rng() % 2 == 0 || !q.tryPush(f, h, static_cast<StateId>(order))) {
        q.push(f, h, static_cast<StateId>(order));
      }
      ref.emplace_back(f, order++);
    } else {
      auto best = std::min_element(ref.begin(), ref.end(), before);
      ASSERT_EQ(q.topKey(), best->first) << "step " << step;
      ASSERT_EQ(q.topId(), static_cast<StateId>(best->second)) << "step " << step;
      q.pop();
      ref.erase(best);
    }
    ASSERT_EQ(q.empty(), ref.empty());
    if (step % 10000 == 9999) {  // emptied and refilled: the blocks are reused
      std::size_t visited = 0;
      q.forEach([&](double, StateId) { ++visited; });
      EXPECT_EQ(visited, ref.size());
      q.clear();
      ref.clear();
      EXPECT_TRUE(q.empty());
    }
  }
  EXPECT_GT(overflowed, 100u);
}

TEST(KeyBucketQueue, ReportsTheMemoryItsNextPushNeeds) {
  KeyBucketQueue q(1.0);
  EXPECT_GT(q.growthBytes(10.0), 0u);  // nothing allocated yet
  q.push(10.0, 3, 1);
  EXPECT_GE(q.memoryBytes(), 64u + 11 * sizeof(std::uint32_t));
  EXPECT_EQ(q.growthBytes(10.0), 0u);       // room left in the key's block
  EXPECT_GT(q.growthBytes(100000.0), 0u);   // the heads must grow
  EXPECT_FALSE(q.tryPush(100000.0, 3, 2));  // ... so tryPush refuses
  EXPECT_FALSE(q.tryPush(9.0, 3, 2));       // no stack for key 9 yet
  for (StateId id = 2; q.growthBytes(10.0) == 0; ++id) EXPECT_TRUE(q.tryPush(10.0, 7, id));
  std::size_t entries = 0;
  q.forEach([&](double, StateId) { ++entries; });
  EXPECT_EQ(entries, 14u);  // one 64-byte block holds 14 ids
  EXPECT_FALSE(q.tryPush(10.0, 3, 99));
  EXPECT_EQ(q.topId(), 14u);  // newest first
}

}  // namespace
}  // namespace detail
}  // namespace amha
