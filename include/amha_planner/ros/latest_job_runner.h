// Runs jobs one at a time on a thread of its own, keeping only the newest waiting job: a job
// posted while another waits replaces it, unrun. The server rebuilds its planner this way: a
// costmap can send updates faster than a large map's planner is built, and only the newest map
// needs one, so a burst of updates costs one or two builds instead of one each, and the planner
// never falls behind the map. ROS-free so that it can be unit-tested.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

namespace amha_planner {

class LatestJobRunner {
 public:
  LatestJobRunner();
  /// Drops the waiting job, lets the running one finish, then joins.
  ~LatestJobRunner();
  LatestJobRunner(const LatestJobRunner&) = delete;
  LatestJobRunner& operator=(const LatestJobRunner&) = delete;

  /// Queues `job` behind the running one; true if it replaced a waiting job (dropped unrun).
  /// Jobs must not throw.
  bool post(std::function<void()> job);
  /// Blocks until no job is running or waiting.
  void waitIdle();
  /// Jobs run so far, and jobs replaced before they ran.
  std::uint64_t ran() const;
  std::uint64_t replaced() const;

 private:
  void work();

  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::function<void()> waiting_;
  bool running_ = false;
  bool stopping_ = false;
  std::uint64_t ran_ = 0, replaced_ = 0;
  std::thread worker_;  ///< last: started after the members it uses
};

}  // namespace amha_planner
