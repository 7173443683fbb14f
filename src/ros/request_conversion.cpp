// The interfaces' requests (see request_conversion.h).
#include "amha_planner/ros/request_conversion.h"

#include <cmath>

namespace amha_planner {

namespace {

/// Plan.srv's request and PlanAnytime.action's goal have the same fields (here in
/// PlannerRequest's order; PlannerRequest.* in request_conversion_test checks each).
template <class Message>
PlannerRequest requestFromPlanFields(const Message& m) {
  return PlannerRequest{m.start,
                        m.goal,
                        m.time_budget,
                        m.algorithm,
                        m.w1,
                        m.w2,
                        m.goal_tolerance,
                        m.ignore_goal_heading != 0,
                        m.start_tolerance};
}

}  // namespace

PlannerRequest requestFrom(const Plan::Request& req) { return requestFromPlanFields(req); }

PlannerRequest requestFrom(const PlanAnytimeGoal& goal) { return requestFromPlanFields(goal); }

PlannerRequest requestFrom(const nav_msgs::GetPlan::Request& req) {
  PlannerRequest r;
  r.start = req.start;
  r.goal = req.goal;
  r.goal_tolerance = req.tolerance;
  return r;
}

bool queryFor(const PlannerRequest& r, const PlannerParams& params, PlanQuery* q,
              std::string* error) {
  if (!searchConfigFor(params, r.algorithm, r.w1, r.w2, &q->config, error)) return false;
  q->time_budget = r.time_budget == 0.0 ? params.default_time_budget : r.time_budget;
  if (!std::isfinite(q->time_budget) || q->time_budget < 0.0) {
    *error = "time_budget must be finite and >= 0 (0: the default)";
    return false;
  }
  if (!std::isfinite(r.goal_tolerance) || r.goal_tolerance < 0.0) {
    *error = "goal_tolerance must be finite and >= 0 (metres; 0: the exact goal)";
    return false;
  }
  if (!std::isfinite(r.start_tolerance) || r.start_tolerance < 0.0) {
    *error = "start_tolerance must be finite and >= 0 (metres; 0: ~start_tolerance)";
    return false;
  }
  q->goal_options.tolerance = r.goal_tolerance;
  q->goal_options.any_heading = r.ignore_goal_heading || params.ignore_goal_heading;
  q->start_options.tolerance = r.start_tolerance > 0.0 ? r.start_tolerance : params.start_tolerance;
  q->start_options.penalty = params.start_escape_penalty;
  return true;
}

}  // namespace amha_planner
