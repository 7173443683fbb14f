// Runs planning jobs one at a time, first come first served, on one worker thread, with a
// bounded number waiting. The server's policy for concurrent requests lives here: a request
// that arrives while one plans waits its turn if fewer than `max_waiting` are already waiting,
// and is refused (BUSY) otherwise. One at a time because a search uses a whole core and the
// lattice's memory; queued requests keep their full time budget for when they run.
// ROS-free so that it can be unit-tested.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace amha_planner {

class PlanQueue {
 public:
  explicit PlanQueue(std::size_t max_waiting);
  /// Runs the jobs still waiting (callers set their cancel flags first), then joins.
  ~PlanQueue();
  PlanQueue(const PlanQueue&) = delete;
  PlanQueue& operator=(const PlanQueue&) = delete;

  /// Queues `job`; false (and `job` is dropped) when max_waiting jobs are already waiting or
  /// the queue is shutting down. Jobs must not throw. `ticket`, if given, receives a number
  /// that removeWaiting() takes.
  bool submit(std::function<void()> job, std::uint64_t* ticket = nullptr);
  /// Drops the job of `ticket` if it is still waiting (a cancelled request: its place goes to
  /// the next one at once); false if it has started or is gone.
  bool removeWaiting(std::uint64_t ticket);

  std::size_t waiting() const;
  bool running() const;

 private:
  void work();

  const std::size_t max_waiting_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::pair<std::uint64_t, std::function<void()>>> jobs_;  // (ticket, job)
  std::uint64_t next_ticket_ = 0;
  bool running_ = false;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace amha_planner
