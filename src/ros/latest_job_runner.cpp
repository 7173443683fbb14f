// One worker, at most one waiting job, newest wins (see latest_job_runner.h).
#include "amha_planner/ros/latest_job_runner.h"

#include <utility>

namespace amha_planner {

LatestJobRunner::LatestJobRunner() : worker_([this] { work(); }) {}

LatestJobRunner::~LatestJobRunner() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    waiting_ = nullptr;
  }
  wake_.notify_all();
  worker_.join();
}

bool LatestJobRunner::post(std::function<void()> job) {
  bool replaced = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) return false;
    replaced = static_cast<bool>(waiting_);
    if (replaced) ++replaced_;
    waiting_ = std::move(job);
  }
  wake_.notify_all();
  return replaced;
}

void LatestJobRunner::waitIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return !running_ && !waiting_; });
}

std::uint64_t LatestJobRunner::ran() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ran_;
}

std::uint64_t LatestJobRunner::replaced() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return replaced_;
}

void LatestJobRunner::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stopping_ || waiting_; });
    if (stopping_) break;
    std::function<void()> job = std::move(waiting_);
    waiting_ = nullptr;
    running_ = true;
    lock.unlock();
    job();
    lock.lock();
    running_ = false;
    ++ran_;
    idle_.notify_all();
  }
  running_ = false;
  idle_.notify_all();
}

}  // namespace amha_planner
