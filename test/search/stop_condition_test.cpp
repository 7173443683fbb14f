// StopCondition: the cancel flag wins, the deadline is honoured on its clock, and a condition
// without either never stops.
#include "amha_planner/search/stop_condition.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

namespace amha {
namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

TEST(StopCondition, WithoutFlagOrDeadlineNeverStops) {
  EXPECT_EQ(StopCondition().reason(), StopReason::kNone);
  EXPECT_FALSE(StopCondition(nullptr, kNever).requested());
  EXPECT_FALSE(StopCondition(nullptr, 2e9).hasDeadline());
  EXPECT_FALSE(StopCondition(nullptr, std::nan("")).hasDeadline());
}

TEST(StopCondition, TheCancelFlagIsReadWhenAsked) {
  std::atomic<bool> cancel{false};
  const StopCondition stop(&cancel, 0.0);  // a zero budget is used up at once
  EXPECT_FALSE(stop.cancelled());
  cancel = true;
  EXPECT_TRUE(stop.cancelled());
  EXPECT_EQ(stop.reason(), StopReason::kCancelled);  // the flag first
}

TEST(StopCondition, ItsFirstReasonStays) {
  std::atomic<bool> cancel{false};
  const StopCondition stop(&cancel, 0.0);
  EXPECT_EQ(stop.stoppedBy(), StopReason::kNone);  // not asked yet
  EXPECT_EQ(stop.reason(), StopReason::kDeadline);
  cancel = true;  // later: the deadline stays the reason
  EXPECT_EQ(stop.reason(), StopReason::kDeadline);
  EXPECT_EQ(stop.stoppedBy(), StopReason::kDeadline);
  const StopCondition copy = stop;
  EXPECT_EQ(copy.stoppedBy(), StopReason::kDeadline);

  std::atomic<bool> cancel2{false};
  const StopCondition never(&cancel2, kNever);
  EXPECT_FALSE(never.requested());
  EXPECT_EQ(never.stoppedBy(), StopReason::kNone);
  cancel2 = true;
  EXPECT_EQ(never.reason(), StopReason::kCancelled);
  EXPECT_EQ(never.stoppedBy(), StopReason::kCancelled);
}

TEST(StopCondition, AWallDeadlinePassesWhileTheThreadSleeps) {
  const StopCondition stop(nullptr, 0.02);
  EXPECT_EQ(stop.reason(), StopReason::kNone);
  std::this_thread::sleep_for(std::chrono::milliseconds(40));
  EXPECT_EQ(stop.reason(), StopReason::kDeadline);
  EXPECT_GE(stop.elapsed(), 0.02);
}

TEST(StopCondition, ACpuDeadlineCountsOnlyTheMakingThreadsWork) {
  const StopCondition stop(nullptr, 0.02, StopClock::kThreadCpu);
  std::this_thread::sleep_for(std::chrono::milliseconds(40));  // sleeping uses no CPU
  EXPECT_EQ(stop.reason(), StopReason::kNone);
  // Another thread asking still reads the making thread's clock.
  StopReason seen = StopReason::kDeadline;
  std::thread([&] {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(40);
    while (std::chrono::steady_clock::now() < until) {
    }
    seen = stop.reason();
  }).join();
  EXPECT_EQ(seen, StopReason::kNone);
  volatile double x = 0.0;
  while (stop.reason() == StopReason::kNone) x = x + 1.0;  // busy: the deadline comes
  EXPECT_GE(stop.elapsed(), 0.02);
}

}  // namespace
}  // namespace amha
