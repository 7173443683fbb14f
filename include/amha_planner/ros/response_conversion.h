// The interfaces' responses: the lattice planner's PlanResult as a Plan.srv response (status
// code, message, best path and its bounds), the same response as the action's result and as
// nav_msgs/GetPlan's, and the replies given without planning (BUSY, a status alone). Pure
// functions of their arguments: no node handle and no ROS master, so that they are unit-tested.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nav_msgs/GetPlan.h>
#include <ros/time.h>

#include "amha_planner/Plan.h"
#include "amha_planner/PlanAnytimeAction.h"
#include "amha_planner/lattice/lattice_planner.h"

namespace amha_planner {

/// The name of a status code of Plan.srv and PlanAnytime.action ("SUCCESS", "NO_MAP", ...),
/// "UNKNOWN" for a number that is none of them.
const char* statusCodeName(std::uint32_t status);

/// Plan.srv's no_path_proof for the lattice planner's NoPathProof (NO_PATH_NOT_PROVEN for kNone).
std::uint8_t noPathProofCode(amha::lattice::NoPathProof proof);

/// The status code of a query the lattice planner refused (INTERNAL_ERROR for kNone).
std::uint32_t statusForQueryError(amha::lattice::QueryError error);

/// A response that carries no path: `status`, `message`, the request's id and an empty path in
/// `frame` stamped `stamp`; every other field as the message type initialises it.
Plan::Response responseWithoutPath(std::uint32_t request_id, std::uint32_t status,
                                   std::string message, const std::string& frame,
                                   const ros::Time& stamp = ros::Time());

/// The reply to a request the queue has no room for: BUSY, saying how many wait
/// (~max_queued_requests), with an empty, unstamped path in `frame`.
Plan::Response busyResponse(std::uint32_t request_id, int max_queued_requests,
                            const std::string& frame);

/// "time budget of 2.50 s used up": how TIME_EXHAUSTED answers, and a search that its budget
/// stopped after a solution, begin.
std::string budgetUsedUp(double seconds);

/// What NO_MAP answers say: no map on `map_topic` yet, or why the last one was refused
/// (`refused_reason`, "" when none was).
std::string noMapMessage(const std::string& map_topic, const std::string& refused_reason);

/// How a request was planned, as its response quotes it.
struct ResponseContext {
  std::string frame;           ///< the global frame, the path's and the poses' frame
  ros::Time stamp;             ///< their stamp
  double time_budget = 0.0;    ///< seconds (0 already replaced by ~default_time_budget)
  double max_memory_mb = 0.0;  ///< ~max_memory_mb in force for the request
};

/// Completes `res` with the library's `result` of its request: planning time, expansions, and
/// either the status of the refused query (its message) or the search's outcome: status and
/// message (then the start escape's and the goal substitution's sentences), planned goal,
/// escape end and, after a solution, the best path through `best_poses` (the poses published
/// for the last solution: smoothed or not) with the cost and bounds of res->solutions.back().
/// res->solutions holds the message published for each solution, in the order found (empty
/// when there was none); request_id, the path's header and the solutions are kept.
void completeResponse(const amha::lattice::PlanResult& result,
                      const std::vector<amha::lattice::Pose2D>& best_poses,
                      const ResponseContext& context, Plan::Response* res);

/// The action's result carrying `res`, every field moved (a result with every solution's path
/// can be megabytes, and a cancelled goal's result should leave at once).
PlanAnytimeResult actionResult(Plan::Response&& res);

/// nav_msgs/GetPlan's response to `res`, as move_base's make_plan answers: the path on
/// SUCCESS, else an empty plan (the log says why); in `frame` with res's path's stamp either way.
nav_msgs::GetPlan::Response makePlanResponse(const Plan::Response& res, const std::string& frame);

}  // namespace amha_planner
