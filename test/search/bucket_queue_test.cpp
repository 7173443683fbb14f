// The bucket queue against a reference (a sorted list): pops come in key order, newest first
// among equal keys, also when keys are pushed below the current minimum or the queue is
// emptied and refilled; the memory it reports covers what it holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "../../src/search/bucket_queue.h"
#include "../../src/search/open_queue.h"

namespace amha {
namespace detail {
namespace {

TEST(BucketQueue, PopsInKeyOrderNewestFirst) {
  BucketQueue q(2.0);  // keys in steps of 0.5
  q.push(3.0, 1);
  q.push(1.5, 2);
  q.push(3.0, 3);
  q.push(1.5, 4);
  q.push(0.0, 5);
  ASSERT_EQ(q.size(), 5u);
  std::vector<std::pair<double, StateId>> popped;
  while (!q.empty()) {
    popped.emplace_back(q.topKey(), q.topId());
    q.pop();
  }
  const std::vector<std::pair<double, StateId>> expected = {
      {0.0, 5}, {1.5, 4}, {1.5, 2}, {3.0, 3}, {3.0, 1}};
  EXPECT_EQ(popped, expected);
}

TEST(BucketQueue, MatchesSortedReferenceUnderRandomPushesAndPops) {
  std::mt19937 rng(7);
  BucketQueue q(4.0);
  // Reference: (key, push order); the queue must pop the smallest key, latest push first.
  std::vector<std::pair<double, long>> ref;
  long order = 0;
  for (int step = 0; step < 40000; ++step) {
    if (ref.empty() || rng() % 100 < 55) {
      // Keys rise over time but often drop below the current minimum, as in a search.
      const double base = step / 10;
      const double f = std::max(0.0, base + static_cast<double>(rng() % 400) / 4.0 - 50.0);
      const auto id = static_cast<StateId>(order);
      q.push(f, id);
      ref.emplace_back(f, order++);
    } else {
      auto best = std::min_element(ref.begin(), ref.end(), [](const auto& a, const auto& b) {
        return a.first < b.first || (a.first == b.first && a.second > b.second);
      });
      ASSERT_EQ(q.topKey(), best->first) << "step " << step;
      ASSERT_EQ(q.topId(), static_cast<StateId>(best->second)) << "step " << step;
      q.pop();
      ref.erase(best);
    }
    ASSERT_EQ(q.size(), ref.size());
    if (step % 10000 == 9999) {  // emptied and refilled: the block pool is reused
      std::size_t visited = 0;
      q.forEach([&](double, StateId) { ++visited; });
      EXPECT_EQ(visited, ref.size());
      q.clear();
      ref.clear();
      EXPECT_TRUE(q.empty());
    }
  }
}

TEST(BucketQueue, ReportsTheMemoryItsNextPushNeeds) {
  BucketQueue q(1.0);
  EXPECT_GT(q.growthBytes(10.0), 0u);  // nothing allocated yet
  q.push(10.0, 1);
  EXPECT_GE(q.memoryBytes(), 64u + 11 * sizeof(std::uint32_t));
  EXPECT_EQ(q.growthBytes(10.0), 0u);   // room left in the bucket's block
  EXPECT_GT(q.growthBytes(1000.0), 0u);  // the bucket array must grow
}

TEST(OpenQueue, PicksBucketsOnlyForKeysThatScaleToIntegers) {
  EXPECT_EQ(OpenQueue::bucketScaleFor(5.0), 1.0);
  EXPECT_EQ(OpenQueue::bucketScaleFor(4.5), 2.0);
  EXPECT_EQ(OpenQueue::bucketScaleFor(1.25), 4.0);
  EXPECT_EQ(OpenQueue::bucketScaleFor(2.3), 0.0);  // no power of two up to 64 makes it whole
  OpenQueue q;
  q.reset(2.0);
  EXPECT_TRUE(q.usesBuckets());
  q.push(QueueEntry{2.5, 7, 3});
  q.push(QueueEntry{1.0, 9, 4});
  EXPECT_EQ(q.topKey(), 1.0);
  EXPECT_EQ(q.topId(), 4u);
  q.reset(0.0);
  EXPECT_FALSE(q.usesBuckets());
  EXPECT_TRUE(q.empty());
  q.push(QueueEntry{2.3, 1, 5});
  q.push(QueueEntry{2.3, 0, 6});  // equal keys: the heap prefers the smaller h
  EXPECT_EQ(q.topId(), 6u);
}

}  // namespace
}  // namespace detail
}  // namespace amha
