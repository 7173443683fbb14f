// The bucket queue against a reference (a sorted list): pops come in (key, h) order, newest
// first among equal ones, also when keys or h values are pushed below the current minimum or
// the queue is emptied and refilled; the memory it reports covers what it holds; tryPush
// pushes exactly when nothing must be allocated.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

#include "../../src/search/bucket_queue.h"
#include "../../src/search/open_queue.h"
#include "queue_test_util.h"

namespace amha {
namespace detail {
namespace {

TEST(BucketQueue, PopsInKeyThenHOrderNewestFirst) {
  BucketQueue q(2.0);  // keys in steps of 0.5
  pushSampleEntries(q);
  ASSERT_EQ(q.size(), 6u);
  const std::vector<std::pair<double, StateId>> popped = drainQueue(q);
  const std::vector<std::pair<double, StateId>> expected = {{0.0, 5}, {1.5, 4}, {1.5, 2},
                                                            {3.0, 3}, {3.0, 6}, {3.0, 1}};
  EXPECT_EQ(popped, expected);
}

TEST(BucketQueue, MatchesSortedReferenceUnderRandomPushesAndPops) {
  std::mt19937 rng(7);
  BucketQueue q(4.0);
  // Reference entries (key, h, push order); the queue must pop the smallest key, then the
  // smallest h, then the latest push.
  std::vector<std::tuple<double, HeuristicValue, long>> ref;
  auto before = [](const auto& a, const auto& b) {
    if (std::get<0>(a) != std::get<0>(b)) return std::get<0>(a) < std::get<0>(b);
    if (std::get<1>(a) != std::get<1>(b)) return std::get<1>(a) < std::get<1>(b);
    return std::get<2>(a) > std::get<2>(b);
  };
  long order = 0;
  for (int step = 0; step < 40000; ++step) {
    if (ref.empty() || rng() % 100 < 55) {
      // Keys rise over time but often drop below the current minimum, as in a search; h
      // values spread within a key so that stacks are added below and above existing ones.
      const double base = step / 10;
      const double f = std::max(0.0, base + static_cast<double>(rng() % 400) / 4.0 - 50.0);
      const auto h = static_cast<HeuristicValue>(rng() % 40);
      // tryPush (used by the engine first) must order its entries exactly like push.
      if (rng() % 2 == 0 || !q.tryPush(f, h, static_cast<StateId>(order))) {
        q.push(f, h, static_cast<StateId>(order));
      }
      ref.emplace_back(f, h, order++);
    } else {
      auto best = std::min_element(ref.begin(), ref.end(), before);
      ASSERT_EQ(q.topKey(), std::get<0>(*best)) << "step " << step;
      ASSERT_EQ(q.topId(), static_cast<StateId>(std::get<2>(*best))) << "step " << step;
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
  EXPECT_GT(q.growthBytes(10.0, 3), 0u);  // nothing allocated yet
  q.push(10.0, 3, 1);
  EXPECT_GE(q.memoryBytes(), 64u + 11 * sizeof(std::uint32_t));
  EXPECT_EQ(q.growthBytes(10.0, 3), 0u);    // room left in the stack's block
  EXPECT_GT(q.growthBytes(1000.0, 3), 0u);  // the key array must grow
  EXPECT_GT(q.growthBytes(10.0, 500), 0u);  // the key's stack array must grow
  // tryPush pushes exactly when nothing must be allocated.
  EXPECT_FALSE(q.tryPush(1000.0, 3, 2));
  EXPECT_FALSE(q.tryPush(10.0, 500, 2));
  EXPECT_FALSE(q.tryPush(10.0, 4, 2));  // no stack for h = 4 yet
  EXPECT_EQ(q.size(), 1u);
  for (StateId id = 2; q.growthBytes(10.0, 3) == 0; ++id) EXPECT_TRUE(q.tryPush(10.0, 3, id));
  EXPECT_EQ(q.size(), 14u);  // one 64-byte block holds 14 ids
  EXPECT_FALSE(q.tryPush(10.0, 3, 99));
  EXPECT_EQ(q.topId(), 14u);  // newest first
}

TEST(OpenQueue, PicksBucketsOnlyForKeysThatScaleToIntegers) {
  EXPECT_EQ(OpenQueue::bucketScaleFor(5.0), 1.0);
  EXPECT_EQ(OpenQueue::bucketScaleFor(4.5), 2.0);
  EXPECT_EQ(OpenQueue::bucketScaleFor(1.25), 4.0);
  EXPECT_EQ(OpenQueue::bucketScaleFor(2.3), 0.0);  // no power of two up to 64 makes it whole
  OpenQueue q;
  q.reset(OpenQueue::Kind::kBuckets, 2.0);
  EXPECT_EQ(q.kind(), OpenQueue::Kind::kBuckets);
  q.push(QueueEntry{2.5, 7, 3});
  q.push(QueueEntry{1.0, 9, 4});
  q.push(QueueEntry{1.0, 8, 5});
  EXPECT_EQ(q.topKey(), 1.0);
  EXPECT_EQ(q.topId(), 5u);  // equal keys: the smaller h, as in the heap
  q.reset(OpenQueue::Kind::kHeap);
  EXPECT_EQ(q.kind(), OpenQueue::Kind::kHeap);
  EXPECT_TRUE(q.empty());
  q.push(QueueEntry{2.3, 1, 5});
  q.push(QueueEntry{2.3, 0, 6});
  EXPECT_EQ(q.topId(), 6u);
  q.reset(OpenQueue::Kind::kKeyBuckets, 2.0);
  EXPECT_TRUE(q.empty());
  q.push(QueueEntry{2.5, 7, 3});
  q.push(QueueEntry{1.0, 8, 5});
  q.push(QueueEntry{1.0, 9, 4});
  EXPECT_EQ(q.topKey(), 1.0);
  EXPECT_EQ(q.topId(), 4u);  // equal keys: the newest, whatever its h
  std::size_t entries = 0;
  q.forEach([&](double, StateId) { ++entries; });
  EXPECT_EQ(entries, 3u);
}

}  // namespace
}  // namespace detail
}  // namespace amha
