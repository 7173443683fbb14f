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

StopReason StopCondition::reason() const {
  if (cancelled()) return StopReason::kCancelled;
  if (hasDeadline() && elapsed() >= seconds_) return StopReason::kDeadline;
  return StopReason::kNone;
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
