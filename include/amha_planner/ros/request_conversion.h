// The interfaces' requests: ~plan's, ~make_plan's (nav_msgs/GetPlan) and ~plan_anytime's goal
// as the one PlannerRequest the server plans, and a PlannerRequest checked against the parameters
// in force as the library's query options. Pure functions: no node handle, no ROS master.
#pragma once

#include <string>

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/GetPlan.h>

#include "amha_planner/Plan.h"
#include "amha_planner/PlanAnytimeAction.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/ros/planner_params.h"

namespace amha_planner {

/// One request, whichever interface it came through (the fields mean what Plan.srv says).
struct PlannerRequest {
  geometry_msgs::PoseStamped start, goal;
  double time_budget = 0.0;
  std::string algorithm;
  double w1 = 0.0, w2 = 0.0;
  double goal_tolerance = 0.0;  ///< metres (nav_msgs/GetPlan's tolerance)
  bool ignore_goal_heading = false;
  double start_tolerance = 0.0;  ///< metres; 0: ~start_tolerance
};

PlannerRequest requestFrom(const Plan::Request& req);
PlannerRequest requestFrom(const PlanAnytimeGoal& goal);
/// move_base's make_plan: its tolerance is the goal tolerance (used when the goal is
/// obstructed); everything else as configured.
PlannerRequest requestFrom(const nav_msgs::GetPlan::Request& req);

/// What the library is asked for a request, with the parameters in force applied.
struct PlanQuery {
  amha::PlannerConfig config;
  double time_budget = 0.0;  ///< seconds (the request's, or ~default_time_budget for 0)
  amha::lattice::GoalOptions goal_options;
  amha::lattice::StartOptions start_options;
};

/// Checks `request` against `params` and gives its query; false with the reason in *error (an
/// INVALID_REQUEST answer) for an unknown algorithm, weights out of range, or a time budget or
/// tolerance that is negative or not finite.
bool queryFor(const PlannerRequest& request, const PlannerParams& params, PlanQuery* query,
              std::string* error);

}  // namespace amha_planner
