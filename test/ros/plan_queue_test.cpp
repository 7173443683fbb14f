// The server's request policy: one job at a time, FIFO, at most max_waiting waiting, the rest
// refused; queued jobs still run at shutdown (their owners cancel them first). ROS-free: built
// without ROS too, and the suite's name (Concurrent...) puts it in the ThreadSanitizer pass.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include "amha_planner/ros/plan_queue.h"

namespace amha_planner {
namespace {

using namespace std::chrono_literals;

// A job that blocks until released, so the test controls what is running.
struct Gate {
  std::promise<void> open;
  std::shared_future<void> opened = open.get_future().share();
};

TEST(ConcurrentPlanQueue, RunsOneAtATimeInOrderAndRefusesBeyondTheBound) {
  PlanQueue queue(2);
  Gate gate;
  std::mutex m;
  std::vector<int> order;
  std::atomic<int> concurrent{0}, max_concurrent{0};
  auto job = [&](int id) {
    return [&, id] {
      const int now = ++concurrent;
      int seen = max_concurrent.load();
      while (now > seen && !max_concurrent.compare_exchange_weak(seen, now)) {
      }
      gate.opened.wait();
      {
        std::lock_guard<std::mutex> lock(m);
        order.push_back(id);
      }
      --concurrent;
    };
  };
  ASSERT_TRUE(queue.submit(job(1)));
  // Wait until job 1 is running, so that the waiting list is empty.
  for (int i = 0; i < 1000 && !queue.running(); ++i) std::this_thread::sleep_for(1ms);
  ASSERT_TRUE(queue.running());
  EXPECT_TRUE(queue.submit(job(2)));
  EXPECT_TRUE(queue.submit(job(3)));
  EXPECT_EQ(queue.waiting(), 2u);
  EXPECT_FALSE(queue.submit(job(4))) << "a third waiting job must be refused";
  gate.open.set_value();
  for (int i = 0; i < 2000; ++i) {
    {
      std::lock_guard<std::mutex> lock(m);
      if (order.size() == 3) break;
    }
    std::this_thread::sleep_for(1ms);
  }
  std::lock_guard<std::mutex> lock(m);
  EXPECT_EQ(order, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(max_concurrent.load(), 1);
}

TEST(ConcurrentPlanQueue, ZeroWaitingMeansRejectWhileBusy) {
  PlanQueue queue(0);
  Gate gate;
  std::atomic<bool> ran{false};
  ASSERT_TRUE(queue.submit([&] { gate.opened.wait(); }));
  for (int i = 0; i < 1000 && !queue.running(); ++i) std::this_thread::sleep_for(1ms);
  EXPECT_FALSE(queue.submit([&] { ran = true; }));
  gate.open.set_value();
  for (int i = 0; i < 1000 && queue.running(); ++i) std::this_thread::sleep_for(1ms);
  EXPECT_TRUE(queue.submit([&] { ran = true; })) << "accepted again once idle";
  for (int i = 0; i < 1000 && !ran; ++i) std::this_thread::sleep_for(1ms);
  EXPECT_TRUE(ran);
}

// A cancelled request that waits leaves the queue at once and frees its place (issue 22, item
// 9: it stayed until the worker reached it, and a request sent next was refused BUSY).
TEST(ConcurrentPlanQueue, AWaitingJobRemovedLeavesAtOnceAndFreesItsPlace) {
  PlanQueue queue(1);
  Gate gate;
  std::atomic<bool> removed_ran{false}, next_ran{false};
  ASSERT_TRUE(queue.submit([&] { gate.opened.wait(); }));
  for (int i = 0; i < 1000 && !queue.running(); ++i) std::this_thread::sleep_for(1ms);
  std::uint64_t ticket = 0;
  ASSERT_TRUE(queue.submit([&] { removed_ran = true; }, &ticket));
  EXPECT_FALSE(queue.submit([&] { next_ran = true; })) << "the one place is taken";
  EXPECT_TRUE(queue.removeWaiting(ticket));
  EXPECT_FALSE(queue.removeWaiting(ticket)) << "already gone";
  EXPECT_EQ(queue.waiting(), 0u);
  EXPECT_TRUE(queue.submit([&] { next_ran = true; })) << "its place is free again";
  gate.open.set_value();
  for (int i = 0; i < 2000 && !next_ran; ++i) std::this_thread::sleep_for(1ms);
  EXPECT_TRUE(next_ran);
  EXPECT_FALSE(removed_ran) << "a removed job must never run";
}

TEST(ConcurrentPlanQueue, DestructionRunsWaitingJobs) {
  std::atomic<int> ran{0};
  {
    PlanQueue queue(3);
    for (int i = 0; i < 4; ++i)
      ASSERT_TRUE(queue.submit([&] {
        std::this_thread::sleep_for(2ms);
        ++ran;
      }));
  }
  EXPECT_EQ(ran.load(), 4) << "every accepted job gets its answer";
}

// Many threads submitting at once (as the service, action and make_plan callbacks do): every
// submission is either accepted and run exactly once or refused, never two jobs run at once,
// and never more than max_waiting wait.
TEST(ConcurrentPlanQueue, ManySubmittersAtOnce) {
  constexpr int kThreads = 6, kPerThread = 200;
  constexpr std::size_t kMaxWaiting = 2;
  std::atomic<int> accepted{0}, ran{0}, running{0}, overlap{0};
  std::atomic<std::size_t> max_waiting_seen{0};
  {
    PlanQueue queue(kMaxWaiting);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&] {
        for (int i = 0; i < kPerThread; ++i) {
          const bool ok = queue.submit([&] {
            if (++running > 1) ++overlap;
            const std::size_t w = queue.waiting();
            std::size_t seen = max_waiting_seen.load();
            while (w > seen && !max_waiting_seen.compare_exchange_weak(seen, w)) {
            }
            std::this_thread::yield();
            --running;
            ++ran;
          });
          if (ok) ++accepted;
          if (i % 16 == 0) std::this_thread::sleep_for(100us);
        }
      });
    }
    for (auto& t : threads) t.join();
  }  // the destructor runs what is still waiting
  EXPECT_EQ(ran.load(), accepted.load());
  EXPECT_GT(accepted.load(), 0);
  EXPECT_EQ(overlap.load(), 0);
  EXPECT_LE(max_waiting_seen.load(), kMaxWaiting);
}

}  // namespace
}  // namespace amha_planner
