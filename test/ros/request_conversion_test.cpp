// The interfaces' requests as the one PlannerRequest, and its checks against the parameters,
// without a ROS master.
#include <gtest/gtest.h>

#include <limits>
#include <string>

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

template <class Message>
void expectEveryField(const Message& m) {
  const PlannerRequest r = requestFrom(m);
  EXPECT_EQ(r.start, m.start);
  EXPECT_EQ(r.goal, m.goal);
  EXPECT_DOUBLE_EQ(r.time_budget, 3.0);
  EXPECT_EQ(r.algorithm, "ara");
  EXPECT_DOUBLE_EQ(r.w1, 4.0);
  EXPECT_DOUBLE_EQ(r.w2, 2.0);
  EXPECT_DOUBLE_EQ(r.goal_tolerance, 0.3);
  EXPECT_TRUE(r.ignore_goal_heading);
  EXPECT_DOUBLE_EQ(r.start_tolerance, 0.2);
}

TEST(PlannerRequest, ThePlanServiceAndTheActionGoalGiveEveryField) {
  expectEveryField(filledIn<Plan::Request>());
  expectEveryField(filledIn<PlanAnytimeGoal>());
}

TEST(PlannerRequest, MakePlanGivesItsPosesAndItsToleranceAsTheGoalTolerance) {
  nav_msgs::GetPlan::Request m;
  m.start.header.frame_id = "odom";
  m.start.pose.position.x = 1.5;
  m.goal.pose.position.y = -2.5;
  m.tolerance = 0.4f;
  const PlannerRequest r = requestFrom(m);
  EXPECT_EQ(r.start, m.start);
  EXPECT_EQ(r.goal, m.goal);
  EXPECT_DOUBLE_EQ(r.goal_tolerance, 0.4f);
  const PlannerRequest configured;  // the rest as configured
  EXPECT_EQ(r.time_budget, configured.time_budget);
  EXPECT_EQ(r.algorithm, configured.algorithm);
  EXPECT_EQ(r.w1, configured.w1);
  EXPECT_EQ(r.w2, configured.w2);
  EXPECT_EQ(r.ignore_goal_heading, configured.ignore_goal_heading);
  EXPECT_EQ(r.start_tolerance, configured.start_tolerance);
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
  for (double budget : {-1.0, nan, inf}) {
    r = PlannerRequest{};
    r.time_budget = budget;
    r.goal_tolerance = -1.0;
    EXPECT_FALSE(queryFor(r, p, &q, &error));
    EXPECT_EQ(error, "time_budget must be finite and >= 0 (0: the default)") << budget;
  }
  for (double tolerance : {-0.1, nan, inf}) {
    r = PlannerRequest{};
    r.goal_tolerance = tolerance;
    r.start_tolerance = -1.0;
    EXPECT_FALSE(queryFor(r, p, &q, &error));
    EXPECT_EQ(error, "goal_tolerance must be finite and >= 0 (metres; 0: the exact goal)") << tolerance;
    r.goal_tolerance = 0.0;
    r.start_tolerance = tolerance;
    EXPECT_FALSE(queryFor(r, p, &q, &error));
    EXPECT_EQ(error, "start_tolerance must be finite and >= 0 (metres; 0: ~start_tolerance)") << tolerance;
  }
  PlannerParams bad_default;
  bad_default.default_time_budget = -2.0;
  EXPECT_FALSE(queryFor(PlannerRequest{}, bad_default, &q, &error));
  EXPECT_EQ(error, "time_budget must be finite and >= 0 (0: the default)");
}

}  // namespace
}  // namespace amha_planner
