// The interfaces' requests as the one PlannerRequest, and its checks against the parameters,
// without a ROS master.
#include <gtest/gtest.h>

#include <cstddef>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "amha_planner/ros/request_conversion.h"

namespace amha_planner {
namespace {

template <class Message>
Message filledIn() {
  Message m;
  m.start.header.frame_id = "odom";
  m.start.pose.position.x = 1.5;
  m.goal.header.frame_id = "map";
  m.goal.pose.position.y = -2.5;
  m.time_budget = 3.0;
  m.algorithm = "ara";
  m.w1 = 4.0;
  m.w2 = 2.0;
  m.goal_tolerance = 0.3;
  m.ignore_goal_heading = true;
  m.start_tolerance = 0.2;
  return m;
}

/// Every field of a request, by name (printed when a comparison fails).
auto fields(const PlannerRequest& r) {
  return std::tie(r.start, r.goal, r.time_budget, r.algorithm, r.w1, r.w2, r.goal_tolerance,
                  r.ignore_goal_heading, r.start_tolerance);
}

TEST(PlannerRequest, ThePlanServiceAndTheActionGoalGiveEveryField) {
  const PlannerRequest expected = filledIn<PlannerRequest>();  // a value of its own in each field
  const PlannerRequest from_plan = requestFrom(filledIn<Plan::Request>());
  const PlannerRequest from_goal = requestFrom(filledIn<PlanAnytimeGoal>());
  EXPECT_EQ(fields(from_plan), fields(expected));
  EXPECT_EQ(fields(from_goal), fields(expected));
}

TEST(PlannerRequest, MakePlanGivesItsPosesAndItsToleranceAsTheGoalTolerance) {
  nav_msgs::GetPlan::Request m;
  m.start.header.frame_id = "odom";
  m.start.pose.position.x = 1.5;
  m.goal.pose.position.y = -2.5;
  m.tolerance = 0.4f;
  PlannerRequest expected;  // the rest as configured
  expected.start = m.start;
  expected.goal = m.goal;
  expected.goal_tolerance = m.tolerance;
  const PlannerRequest r = requestFrom(m);
  EXPECT_EQ(fields(r), fields(expected));
}

TEST(PlannerRequest, TheQueryTakesTheParametersWhereTheRequestLeavesThemOpen) {
  PlannerParams p;
  p.default_time_budget = 7.0;
  p.start_tolerance = 0.6;
  p.start_escape_penalty = 3.0;
  PlanQuery q;
  std::string error;
  ASSERT_TRUE(queryFor(PlannerRequest{}, p, &q, &error)) << error;
  EXPECT_DOUBLE_EQ(q.time_budget, 7.0);
  EXPECT_EQ(q.config.algorithm, amha::Algorithm::kAmhaStar);
  EXPECT_DOUBLE_EQ(q.goal_options.tolerance, 0.0);
  EXPECT_FALSE(q.goal_options.any_heading);
  EXPECT_DOUBLE_EQ(q.start_options.tolerance, 0.6);
  EXPECT_DOUBLE_EQ(q.start_options.penalty, 3.0);
  p.ignore_goal_heading = true;
  ASSERT_TRUE(queryFor(PlannerRequest{}, p, &q, &error)) << error;
  EXPECT_TRUE(q.goal_options.any_heading) << "~ignore_goal_heading holds for every request";

  p.ignore_goal_heading = false;
  PlannerRequest r = requestFrom(filledIn<Plan::Request>());
  ASSERT_TRUE(queryFor(r, p, &q, &error)) << error;
  EXPECT_DOUBLE_EQ(q.time_budget, 3.0);
  EXPECT_EQ(q.config.algorithm, amha::Algorithm::kAraStar);
  EXPECT_DOUBLE_EQ(q.config.w1, 4.0);
  EXPECT_DOUBLE_EQ(q.goal_options.tolerance, 0.3);
  EXPECT_TRUE(q.goal_options.any_heading);
  EXPECT_DOUBLE_EQ(q.start_options.tolerance, 0.2);
}

TEST(PlannerRequest, BadRequestsAreRefusedWithTheirReasonInOrder) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const PlannerParams p;
  PlanQuery q;
  std::string error;
  PlannerRequest r;
  r.algorithm = "dijkstra";
  r.time_budget = -1.0;  // the algorithm is checked first
  EXPECT_FALSE(queryFor(r, p, &q, &error));
  EXPECT_NE(error.find("dijkstra"), std::string::npos) << error;
  // In the order they are checked: a bad value is reported when those before it are good,
  // whatever those after it are.
  const std::vector<std::pair<double PlannerRequest::*, std::string>> checked = {
      {&PlannerRequest::time_budget, "time_budget must be finite and >= 0 (0: the default)"},
      {&PlannerRequest::goal_tolerance,
       "goal_tolerance must be finite and >= 0 (metres; 0: the exact goal)"},
      {&PlannerRequest::start_tolerance,
       "start_tolerance must be finite and >= 0 (metres; 0: ~start_tolerance)"}};
  for (std::size_t i = 0; i < checked.size(); ++i) {
    for (double bad : {-0.1, -1.0, nan, inf}) {
      r = PlannerRequest{};
      r.*checked[i].first = bad;
      for (std::size_t later = i + 1; later < checked.size(); ++later)
        r.*checked[later].first = -1.0;
      EXPECT_FALSE(queryFor(r, p, &q, &error));
      EXPECT_EQ(error, checked[i].second) << bad;
    }
  }
  PlannerParams bad_default;
  bad_default.default_time_budget = -2.0;
  EXPECT_FALSE(queryFor(PlannerRequest{}, bad_default, &q, &error));
  EXPECT_EQ(error, "time_budget must be finite and >= 0 (0: the default)");
}

}  // namespace
}  // namespace amha_planner
