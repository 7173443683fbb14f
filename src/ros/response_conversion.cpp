// The interfaces' responses (see response_conversion.h).
#include "amha_planner/ros/response_conversion.h"

#include <sstream>
#include <utility>

#include "amha_planner/ros/conversions.h"

namespace amha_planner {

namespace lat = amha::lattice;
using Status = Plan::Response;

// The action result repeats the service's codes; keep them identical.
#define AMHA_SAME_CODE(c)                                                                        \
  static_assert(static_cast<unsigned>(Status::c) == static_cast<unsigned>(PlanAnytimeResult::c), \
                "Plan.srv and PlanAnytime.action disagree on " #c)
AMHA_SAME_CODE(SUCCESS);
AMHA_SAME_CODE(CANCELLED);
AMHA_SAME_CODE(INVALID_START);
AMHA_SAME_CODE(INVALID_GOAL);
AMHA_SAME_CODE(NO_PATH_FOUND);
AMHA_SAME_CODE(TIME_EXHAUSTED);
AMHA_SAME_CODE(MEMORY_EXHAUSTED);
AMHA_SAME_CODE(TF_ERROR);
AMHA_SAME_CODE(NO_MAP);
AMHA_SAME_CODE(INVALID_REQUEST);
AMHA_SAME_CODE(INTERNAL_ERROR);
AMHA_SAME_CODE(OUT_OF_MAP);
AMHA_SAME_CODE(BUSY);
AMHA_SAME_CODE(NO_PATH_NOT_PROVEN);
AMHA_SAME_CODE(NO_PATH_SEARCH);
AMHA_SAME_CODE(NO_PATH_GOAL_ENCLOSED);
AMHA_SAME_CODE(NO_PATH_START_ENCLOSED);
#undef AMHA_SAME_CODE

namespace {

std::string fmt(double v, int precision = 3) {
  std::ostringstream s;
  s.precision(precision);
  s << std::fixed << v;
  return s.str();
}

struct Outcome {
  std::uint32_t status;
  std::string message;
};

/// The status and message of a search that ended with `status`; `best` describes its best
/// solution, or is null when it found none.
Outcome searchOutcome(amha::SearchStatus status, const std::string* best,
                      const ResponseContext& c) {
  using S = amha::SearchStatus;
  const std::string so_far = best ? "; returning the best path so far: " + *best : "";
  switch (status) {
    case S::kProvenOptimal:
      if (best) return {Status::SUCCESS, "optimal path: " + *best};
      break;
    case S::kBoundReached:
      if (best) return {Status::SUCCESS, "path within the requested bound: " + *best};
      break;
    case S::kTimeLimit:
      return {best ? Status::SUCCESS : Status::TIME_EXHAUSTED,
              budgetUsedUp(c.time_budget) + (best ? so_far : " before any path was found")};
    case S::kMemoryLimit:
      if (!best) {
        return {Status::MEMORY_EXHAUSTED,
                "memory cap of " + fmt(c.max_memory_mb, 0) +
                    " MB (~max_memory_mb) reached before any path was found"};
      }
      [[fallthrough]];
    case S::kExpansionLimit:
      if (best)
        return {Status::SUCCESS,
                std::string("search stopped (") + amha::statusName(status) + ")" + so_far};
      break;
    case S::kCancelled:
      return {Status::CANCELLED,
              best ? "cancelled" + so_far : "cancelled before any path was found"};
    case S::kNoSolution:
      if (best)
        return {Status::INTERNAL_ERROR,
                "the search reported no solution after finding one: " + *best};
      return {Status::NO_PATH_FOUND,
              "no path: the goal cannot be reached from the start on this map"};
  }
  return {Status::INTERNAL_ERROR,
          std::string("the search ended (") + amha::statusName(status) + ") without a solution"};
}

/// "3 solution(s), best cost 12.345 m, bound 1.50, certified 1.20" (and the lattice path's cost
/// when the best was smoothed).
std::string solutionsSummary(const std::vector<PlanSolution>& solutions) {
  const PlanSolution& best = solutions.back();
  return std::to_string(solutions.size()) + " solution(s), best cost " + fmt(best.cost) +
         " m, bound " + fmt(best.bound, 2) + ", certified " + fmt(best.certified_bound, 2) +
         (best.smoothed ? " (smoothed; lattice path " + fmt(best.lattice_cost) + " m)" : "");
}

// Moves rather than copies: with every solution's path a result can be megabytes, and a
// cancelled goal's result should leave at once.
template <class Result>
void moveResponse(Plan::Response&& in, Result* out) {
  out->status = in.status;
  out->message = std::move(in.message);
  out->request_id = in.request_id;
  out->path = std::move(in.path);
  out->cost = in.cost;
  out->bound = in.bound;
  out->certified_bound = in.certified_bound;
  out->planning_time = in.planning_time;
  out->expansions = in.expansions;
  out->solutions = std::move(in.solutions);
  out->goal_substituted = in.goal_substituted;
  out->planned_goal = std::move(in.planned_goal);
  out->start_escaped = in.start_escaped;
  out->escape_end = std::move(in.escape_end);
  out->no_path_proof = in.no_path_proof;
  out->enclosed_states = in.enclosed_states;
}

}  // namespace

std::uint8_t noPathProofCode(lat::NoPathProof p) {
  switch (p) {
    case lat::NoPathProof::kSearch:
      return Status::NO_PATH_SEARCH;
    case lat::NoPathProof::kGoalEnclosed:
      return Status::NO_PATH_GOAL_ENCLOSED;
    case lat::NoPathProof::kStartEnclosed:
      return Status::NO_PATH_START_ENCLOSED;
    case lat::NoPathProof::kNone:
      break;
  }
  return Status::NO_PATH_NOT_PROVEN;
}

const char* statusCodeName(std::uint32_t s) {
  switch (s) {
    case Status::SUCCESS:
      return "SUCCESS";
    case Status::CANCELLED:
      return "CANCELLED";
    case Status::INVALID_START:
      return "INVALID_START";
    case Status::INVALID_GOAL:
      return "INVALID_GOAL";
    case Status::NO_PATH_FOUND:
      return "NO_PATH_FOUND";
    case Status::TIME_EXHAUSTED:
      return "TIME_EXHAUSTED";
    case Status::MEMORY_EXHAUSTED:
      return "MEMORY_EXHAUSTED";
    case Status::TF_ERROR:
      return "TF_ERROR";
    case Status::NO_MAP:
      return "NO_MAP";
    case Status::INVALID_REQUEST:
      return "INVALID_REQUEST";
    case Status::INTERNAL_ERROR:
      return "INTERNAL_ERROR";
    case Status::OUT_OF_MAP:
      return "OUT_OF_MAP";
    case Status::BUSY:
      return "BUSY";
  }
  return "UNKNOWN";
}

std::uint32_t statusForQueryError(lat::QueryError e) {
  switch (e) {
    case lat::QueryError::kStartNotFinite:
    case lat::QueryError::kStartInCollision:
      return Status::INVALID_START;
    case lat::QueryError::kGoalNotFinite:
    case lat::QueryError::kGoalInCollision:
      return Status::INVALID_GOAL;
    case lat::QueryError::kGoalUnreachable:
      return Status::NO_PATH_FOUND;
    case lat::QueryError::kStartOutOfMap:
    case lat::QueryError::kGoalOutOfMap:
      return Status::OUT_OF_MAP;
    case lat::QueryError::kNone:
      break;
  }
  return Status::INTERNAL_ERROR;
}

Plan::Response responseWithoutPath(std::uint32_t request_id, std::uint32_t status,
                                   std::string message, const std::string& frame,
                                   const ros::Time& stamp) {
  Plan::Response res;
  res.request_id = request_id;
  res.status = status;
  res.message = std::move(message);
  res.path.header.frame_id = frame;
  res.path.header.stamp = stamp;
  return res;
}

Plan::Response busyResponse(std::uint32_t request_id, int max_queued_requests,
                            const std::string& frame) {
  return responseWithoutPath(request_id, Status::BUSY,
                             "busy: one request is planning and " +
                                 std::to_string(max_queued_requests) +
                                 " are waiting (~max_queued_requests); try again later",
                             frame);
}

std::string budgetUsedUp(double seconds) {
  return "time budget of " + fmt(seconds, 2) + " s used up";
}

std::string noMapMessage(const std::string& map_topic, const std::string& refused_reason) {
  return refused_reason.empty() ? "no valid map received on " + map_topic + " yet"
                                : "no usable map on " + map_topic +
                                      " yet: the last one was refused: " + refused_reason;
}

void completeResponse(const lat::PlanResult& result, const std::vector<lat::Pose2D>& best_poses,
                      const ResponseContext& context, Plan::Response* res) {
  res->planning_time = result.totalSeconds();
  res->expansions = result.search.expansions;
  if (result.error != lat::QueryError::kNone) {
    res->status = statusForQueryError(result.error);
    res->message = result.message;
    return;
  }
  const std::string& frame = context.frame;
  const ros::Time& stamp = context.stamp;
  res->goal_substituted = result.goal_substituted;
  if (result.planned_goal)
    res->planned_goal = poseStampedFromPose2D(*result.planned_goal, frame, stamp);
  res->start_escaped = result.start_escaped;
  if (result.start_escaped && !result.solutions.empty()) {
    const lat::LatticeSolution& best = result.solutions.back();
    res->escape_end = poseStampedFromPose2D(best.poses[best.escape_poses - 1], frame, stamp);
  }
  std::string summary;
  if (!res->solutions.empty()) {
    const PlanSolution& best = res->solutions.back();
    res->path = pathFromPoses(best_poses, frame, stamp);
    res->cost = best.cost;
    res->bound = best.bound;
    res->certified_bound = best.certified_bound;
    summary = solutionsSummary(res->solutions);
  }
  Outcome outcome =
      searchOutcome(result.search.status, res->solutions.empty() ? nullptr : &summary, context);
  res->status = outcome.status;
  // Told after the outcome: "...; start (..) is in collision; the path leaves it by ...",
  // "...; goal (..) is in collision; planning to ... instead".
  res->message = std::move(outcome.message);
  if (res->status == Status::NO_PATH_FOUND && !result.no_path_reason.empty()) {
    res->message += " (" + result.no_path_reason + ")";
    res->no_path_proof = noPathProofCode(result.no_path);
    res->enclosed_states = result.enclosed_states;
  }
  if (result.start_escaped) res->message += "; " + result.escape_message;
  if (result.goal_substituted) res->message += "; " + result.message;
}

PlanAnytimeResult actionResult(Plan::Response&& in) {
  PlanAnytimeResult out;
  moveResponse(std::move(in), &out);
  return out;
}

nav_msgs::GetPlan::Response makePlanResponse(const Plan::Response& res, const std::string& frame) {
  nav_msgs::GetPlan::Response out;
  if (res.status == Status::SUCCESS) out.plan = res.path;
  out.plan.header.frame_id = frame;
  out.plan.header.stamp = res.path.header.stamp;
  return out;
}

}  // namespace amha_planner
