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

bool PlanQueue::submit(std::function<void()> job, std::uint64_t* ticket) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_ || jobs_.size() >= max_waiting_ + (running_ ? 0 : 1)) return false;
    if (ticket != nullptr) *ticket = next_ticket_;
    jobs_.emplace_back(next_ticket_++, std::move(job));
  }
  wake_.notify_all();
  return true;
}

bool PlanQueue::removeWaiting(std::uint64_t ticket) {
  std::function<void()> dropped;  // destroyed outside the lock
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = jobs_.begin(); it != jobs_.end(); ++it) {
    if (it->first == ticket) {
      dropped = std::move(it->second);
      jobs_.erase(it);
      return true;
    }
  }
  return false;
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
    std::function<void()> job = std::move(jobs_.front().second);
    jobs_.pop_front();
    running_ = true;
    lock.unlock();
    job();
    lock.lock();
    running_ = false;
  }
}

}  // namespace amha_planner
