// The map builder's policy: jobs run one at a time on one thread; a job posted while another
// waits replaces it unrun, so only the newest waiting job ever runs; at destruction the waiting
// job is dropped and the running one finishes. ROS-free, and named Concurrent... so that the
// ThreadSanitizer pass runs it.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include "amha_planner/ros/latest_job_runner.h"

namespace amha_planner {
namespace {

// A job that signals it started, then blocks until released.
struct Gate {
  std::promise<void> started, open;
  std::shared_future<void> opened = open.get_future().share();
};

TEST(ConcurrentLatestJobRunner, RunsEachJobWhenNoneIsWaiting) {
  LatestJobRunner runner;
  std::vector<int> ran;
  for (int i = 0; i < 3; ++i) {
    EXPECT_FALSE(runner.post([&ran, i] { ran.push_back(i); }));
    runner.waitIdle();
  }
  EXPECT_EQ(ran, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(runner.ran(), 3u);
  EXPECT_EQ(runner.replaced(), 0u);
}

TEST(ConcurrentLatestJobRunner, ANewJobReplacesTheWaitingOneAndOnlyTheNewestRuns) {
  LatestJobRunner runner;
  Gate gate;
  std::mutex m;
  std::vector<int> ran;
  auto record = [&](int id) {
    std::lock_guard<std::mutex> lock(m);
    ran.push_back(id);
  };
  EXPECT_FALSE(runner.post([&] {
    gate.started.set_value();
    gate.opened.wait();
    record(0);
  }));
  gate.started.get_future().wait();  // job 0 runs; the next ones wait behind it
  EXPECT_FALSE(runner.post([&] { record(1); }));
  EXPECT_TRUE(runner.post([&] { record(2); })) << "job 2 should replace the waiting job 1";
  EXPECT_TRUE(runner.post([&] { record(3); })) << "job 3 should replace the waiting job 2";
  gate.open.set_value();
  runner.waitIdle();
  EXPECT_EQ(ran, (std::vector<int>{0, 3}));
  EXPECT_EQ(runner.ran(), 2u);
  EXPECT_EQ(runner.replaced(), 2u);
}

TEST(ConcurrentLatestJobRunner, NeverRunsTwoJobsAtOnceAndAlwaysRunsTheLastPosted) {
  LatestJobRunner runner;
  std::atomic<int> concurrent{0}, max_concurrent{0}, last{-1};
  auto job = [&](int id) {
    return [&, id] {
      const int now = ++concurrent;
      int seen = max_concurrent.load();
      while (now > seen && !max_concurrent.compare_exchange_weak(seen, now)) {
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      last = id;
      --concurrent;
    };
  };
  std::vector<std::thread> posters;
  for (int t = 0; t < 2; ++t) {
    posters.emplace_back([&, t] {
      for (int i = 0; i < 200; ++i) runner.post(job(t * 1000 + i));
    });
  }
  for (auto& p : posters) p.join();
  runner.post(job(-7));
  runner.waitIdle();
  EXPECT_EQ(max_concurrent.load(), 1);
  EXPECT_EQ(last.load(), -7) << "the last job posted must run, and run last";
  EXPECT_EQ(runner.ran() + runner.replaced(), 401u) << "every job either ran or was replaced";
  EXPECT_GT(runner.replaced(), 0u) << "posting 400 jobs of 0.2 ms each never replaced one";
}

TEST(ConcurrentLatestJobRunner, DestructionDropsTheWaitingJobAndFinishesTheRunningOne) {
  Gate gate;
  std::atomic<bool> first_done{false}, second_ran{false};
  auto runner = std::make_unique<LatestJobRunner>();
  runner->post([&] {
    gate.started.set_value();
    gate.opened.wait();
    first_done = true;
  });
  gate.started.get_future().wait();
  runner->post([&] { second_ran = true; });
  std::thread destroyer([&] { runner.reset(); });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(first_done.load());
  gate.open.set_value();
  destroyer.join();
  EXPECT_TRUE(first_done.load()) << "the running job must finish before the runner is gone";
  EXPECT_FALSE(second_ran.load()) << "the waiting job must be dropped at destruction";
}

}  // namespace
}  // namespace amha_planner
