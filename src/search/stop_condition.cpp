#include "amha_planner/search/stop_condition.h"

#include <pthread.h>

#include <algorithm>
#include <chrono>

namespace amha {

StopCondition::StopCondition(const std::atomic<bool>* cancel, double seconds, StopClock clock)
    : cancel_(cancel), clock_(clock) {
  if (clock_ == StopClock::kThreadCpu) pthread_getcpuclockid(pthread_self(), &cpu_clock_);
  start_ = now();
  if (seconds < 1e9) seconds_ = std::max(0.0, seconds);  // NaN never stops, as before
}

StopCondition& StopCondition::operator=(const StopCondition& o) {
  cancel_ = o.cancel_;
  clock_ = o.clock_;
  cpu_clock_ = o.cpu_clock_;
  start_ = o.start_;
  seconds_ = o.seconds_;
  said_.store(o.said_.load(std::memory_order_relaxed), std::memory_order_relaxed);
  return *this;
}

StopReason StopCondition::reason() const {
  const StopReason said = stoppedBy();
  if (said != StopReason::kNone) return said;
  StopReason now = StopReason::kNone;
  if (cancelled()) {
    now = StopReason::kCancelled;
  } else if (hasDeadline() && elapsed() >= seconds_) {
    now = StopReason::kDeadline;
  } else {
    return StopReason::kNone;
  }
  // Several threads may ask at once (the grids): the first answer stays.
  int none = static_cast<int>(StopReason::kNone);
  said_.compare_exchange_strong(none, static_cast<int>(now), std::memory_order_relaxed);
  return stoppedBy();
}

double StopCondition::now() const {
  if (clock_ == StopClock::kThreadCpu) {
    timespec ts{};
    clock_gettime(cpu_clock_, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace amha
