// One worker, FIFO, bounded waiting list (see plan_queue.h).
#include "amha_planner/ros/plan_queue.h"

#include <utility>

namespace amha_planner {

PlanQueue::PlanQueue(std::size_t max_waiting)
    : max_waiting_(max_waiting), worker_([this] { work(); }) {}

PlanQueue::~PlanQueue() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

bool PlanQueue::submit(std::function<void()> job) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_ || jobs_.size() >= max_waiting_ + (running_ ? 0 : 1)) return false;
    jobs_.push_back(std::move(job));
  }
  wake_.notify_all();
  return true;
}

std::size_t PlanQueue::waiting() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return jobs_.size();
}

bool PlanQueue::running() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return running_;
}

void PlanQueue::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
    if (jobs_.empty()) return;  // stopping and drained
    std::function<void()> job = std::move(jobs_.front());
    jobs_.pop_front();
    running_ = true;
    lock.unlock();
    job();
    lock.lock();
    running_ = false;
  }
}

}  // namespace amha_planner
