// One stop condition for every long computation (the searches, the heuristic grids and tables,
// the goal choice, a planner's setup): a cancel flag and a deadline on a chosen clock, and why
// it stopped. In the spirit of OMPL's PlannerTerminationCondition.
#pragma once

#include <atomic>
#include <ctime>
#include <limits>

namespace amha {

/// The clock a deadline is on.
enum class StopClock {
  kWall,       ///< std::chrono::steady_clock
  kThreadCpu,  ///< the CPU time of the thread that made the condition: fair on a shared machine
};

/// Why a computation stopped.
enum class StopReason { kNone, kCancelled, kDeadline };

class StopCondition {
 public:
  /// Never stops.
  StopCondition() = default;
  /// Stops when *cancel becomes true (null: never) or `seconds` after now on `clock` (infinite
  /// or >= 1e9: never; negative counts as 0). kThreadCpu measures the calling thread, whichever
  /// thread asks later.
  StopCondition(const std::atomic<bool>* cancel, double seconds,
                StopClock clock = StopClock::kWall);

  StopCondition(const StopCondition& o) { *this = o; }
  StopCondition& operator=(const StopCondition& o);

  /// The cancel flag first, then the deadline (reads the clock only if there is a deadline).
  /// Once it has said to stop, it keeps that answer: the first reason is the reason.
  StopReason reason() const;
  /// Why it stopped, as reason() first said (kNone if it has not said to stop): what callers
  /// report afterwards, without asking the flag and the clock again.
  StopReason stoppedBy() const {
    return static_cast<StopReason>(said_.load(std::memory_order_relaxed));
  }
  bool requested() const { return reason() != StopReason::kNone; }
  /// Only the cancel flag (no clock read).
  bool cancelled() const { return cancel_ != nullptr && cancel_->load(std::memory_order_relaxed); }
  /// Seconds on its clock since it was made.
  double elapsed() const { return now() - start_; }
  bool hasDeadline() const { return seconds_ < std::numeric_limits<double>::infinity(); }

 private:
  double now() const;

  const std::atomic<bool>* cancel_ = nullptr;
  StopClock clock_ = StopClock::kWall;
  clockid_t cpu_clock_{};  // the making thread's CPU clock (kThreadCpu)
  double start_ = 0.0;     // now() when made
  double seconds_ = std::numeric_limits<double>::infinity();
  mutable std::atomic<int> said_{static_cast<int>(StopReason::kNone)};  // the first reason
};

}  // namespace amha
