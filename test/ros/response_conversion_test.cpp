// The interfaces' responses built from the lattice planner's results, without a ROS master:
// every status and query error gives its code and message; solutions give the best path with
// its cost and bounds.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include <ros/serialization.h>

#include "amha_planner/ros/response_conversion.h"

namespace amha_planner {
namespace {

namespace lat = amha::lattice;
using Status = Plan::Response;
using amha::SearchStatus;

ResponseContext context() {
  ResponseContext c;
  c.frame = "map";
  c.stamp = ros::Time(12, 500);
  c.time_budget = 2.5;
  c.max_memory_mb = 1024.0;
  return c;
}

PlanSolution solutionMsg(double cost, double bound, double certified) {
  PlanSolution m;
  m.cost = cost;
  m.bound = bound;
  m.certified_bound = certified;
  return m;
}

/// A response as execute() has it when the search returns: the request's id, its empty path's
/// header and the messages of `solutions` solutions (the last the best: cost 12.3456, bound
/// 1.5, certified 1.25).
Plan::Response streamed(int solutions) {
  Plan::Response res =
      responseWithoutPath(9, Status::INTERNAL_ERROR, "", "map", ros::Time(12, 500));
  for (int i = solutions; i > 0; --i)
    res.solutions.push_back(solutionMsg(12.3456 + i, 1.5 + i, 1.25 + i));
  return res;
}

lat::PlanResult searchEnded(SearchStatus status, int solutions) {
  lat::PlanResult r;
  r.search.status = status;
  r.search.expansions = 4321;
  r.search.elapsed_s = 0.5;
  r.heuristic_seconds = 0.25;
  r.goal_seconds = 0.125;
  r.escape_seconds = 0.0625;
  r.planned_goal = lat::Pose2D{3.0, 4.0, 0.0};
  for (int i = 0; i < solutions; ++i) {
    lat::LatticeSolution s;
    for (double x : {0.0, 1.0, 2.0}) s.poses.push_back(lat::Pose2D{x, x / 2.0, 0.0});
    r.solutions.push_back(s);
  }
  return r;
}

Plan::Response complete(const lat::PlanResult& result, int solutions,
                        const std::vector<lat::Pose2D>& best_poses = {{0, 0, 0}, {1, 1, 0}}) {
  Plan::Response res = streamed(solutions);
  completeResponse(result, best_poses, context(), &res);
  return res;
}

TEST(PlanResponse, EveryStatusCodeHasItsName) {
  const std::vector<std::pair<std::uint32_t, std::string>> codes = {
      {Status::SUCCESS, "SUCCESS"},
      {Status::CANCELLED, "CANCELLED"},
      {Status::INVALID_START, "INVALID_START"},
      {Status::INVALID_GOAL, "INVALID_GOAL"},
      {Status::NO_PATH_FOUND, "NO_PATH_FOUND"},
      {Status::TIME_EXHAUSTED, "TIME_EXHAUSTED"},
      {Status::MEMORY_EXHAUSTED, "MEMORY_EXHAUSTED"},
      {Status::TF_ERROR, "TF_ERROR"},
      {Status::NO_MAP, "NO_MAP"},
      {Status::INVALID_REQUEST, "INVALID_REQUEST"},
      {Status::INTERNAL_ERROR, "INTERNAL_ERROR"},
      {Status::OUT_OF_MAP, "OUT_OF_MAP"},
      {Status::BUSY, "BUSY"}};
  for (const auto& [code, name] : codes) EXPECT_EQ(statusCodeName(code), name) << code;
  EXPECT_STREQ(statusCodeName(1), "UNKNOWN");
  EXPECT_STREQ(statusCodeName(63), "UNKNOWN");
}

TEST(PlanResponse, EveryQueryErrorGivesItsCodeAndTheLibrarysMessage) {
  const std::vector<std::pair<lat::QueryError, std::uint32_t>> errors = {
      {lat::QueryError::kStartNotFinite, Status::INVALID_START},
      {lat::QueryError::kStartInCollision, Status::INVALID_START},
      {lat::QueryError::kGoalNotFinite, Status::INVALID_GOAL},
      {lat::QueryError::kGoalInCollision, Status::INVALID_GOAL},
      {lat::QueryError::kGoalUnreachable, Status::NO_PATH_FOUND},
      {lat::QueryError::kStartOutOfMap, Status::OUT_OF_MAP},
      {lat::QueryError::kGoalOutOfMap, Status::OUT_OF_MAP}};
  for (const auto& [error, code] : errors) {
    EXPECT_EQ(statusForQueryError(error), code);
    lat::PlanResult r = searchEnded(SearchStatus::kNoSolution, 0);
    r.error = error;
    r.message = "the start (1.000, 2.000) is outside the map";
    r.goal_substituted = true;  // not reported after a refused query
    const Plan::Response res = complete(r, 0);
    EXPECT_EQ(res.status, code);
    EXPECT_EQ(res.message, r.message);
    EXPECT_EQ(res.request_id, 9u);
    EXPECT_DOUBLE_EQ(res.planning_time, 0.9375);
    EXPECT_EQ(res.expansions, 4321u);
    EXPECT_FALSE(res.goal_substituted);
    EXPECT_TRUE(res.planned_goal.header.frame_id.empty()) << "no search ran";
    EXPECT_TRUE(res.path.poses.empty());
    EXPECT_EQ(res.path.header.frame_id, "map");
  }
  EXPECT_EQ(statusForQueryError(lat::QueryError::kNone), Status::INTERNAL_ERROR);
}

TEST(PlanResponse, EverySearchStatusWithoutASolutionGivesItsCodeAndMessage) {
  struct Case {
    SearchStatus status;
    std::uint32_t code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {SearchStatus::kNoSolution, Status::NO_PATH_FOUND,
       "no path: the goal cannot be reached from the start on this map"},
      {SearchStatus::kTimeLimit, Status::TIME_EXHAUSTED,
       "time budget of 2.50 s used up before any path was found"},
      {SearchStatus::kMemoryLimit, Status::MEMORY_EXHAUSTED,
       "memory cap of 1024 MB (~max_memory_mb) reached before any path was found"},
      {SearchStatus::kCancelled, Status::CANCELLED, "cancelled before any path was found"},
      {SearchStatus::kProvenOptimal, Status::INTERNAL_ERROR,
       "the search ended (proven_optimal) without a solution"},
      {SearchStatus::kBoundReached, Status::INTERNAL_ERROR,
       "the search ended (bound_reached) without a solution"},
      {SearchStatus::kExpansionLimit, Status::INTERNAL_ERROR,
       "the search ended (expansion_limit) without a solution"},
  };
  for (const Case& c : cases) {
    const Plan::Response res = complete(searchEnded(c.status, 0), 0);
    EXPECT_EQ(res.status, c.code) << amha::statusName(c.status);
    EXPECT_EQ(res.message, c.message);
    EXPECT_TRUE(res.path.poses.empty());
    EXPECT_EQ(res.path.header.frame_id, "map");
    EXPECT_EQ(res.path.header.stamp, ros::Time(12, 500));
    EXPECT_DOUBLE_EQ(res.cost, 0.0);
    EXPECT_DOUBLE_EQ(res.bound, 0.0);
    EXPECT_DOUBLE_EQ(res.planning_time, 0.9375);
    EXPECT_EQ(res.expansions, 4321u);
    EXPECT_EQ(res.planned_goal.header.frame_id, "map");
    EXPECT_DOUBLE_EQ(res.planned_goal.pose.position.x, 3.0);
  }
}

TEST(PlanResponse, NoPathSaysWhatProvedIt) {
  lat::PlanResult r = searchEnded(SearchStatus::kNoSolution, 0);
  r.no_path = lat::NoPathProof::kGoalEnclosed;
  r.enclosed_states = 2006;
  r.no_path_reason = "proven from the goal's side: only 2006 lattice states lead to the goal";
  const Plan::Response res = complete(r, 0);
  EXPECT_EQ(res.status, Status::NO_PATH_FOUND);
  EXPECT_EQ(res.message,
            "no path: the goal cannot be reached from the start on this map (proven from the "
            "goal's side: only 2006 lattice states lead to the goal)");
  EXPECT_EQ(res.no_path_proof, Status::NO_PATH_GOAL_ENCLOSED);
  EXPECT_EQ(res.enclosed_states, 2006u);
  EXPECT_EQ(noPathProofCode(lat::NoPathProof::kNone), Status::NO_PATH_NOT_PROVEN);
  EXPECT_EQ(noPathProofCode(lat::NoPathProof::kSearch), Status::NO_PATH_SEARCH);
  EXPECT_EQ(noPathProofCode(lat::NoPathProof::kStartEnclosed), Status::NO_PATH_START_ENCLOSED);
  // Any other answer is not proven, whatever the result holds (a goal tolerance's refusal).
  lat::PlanResult refused = r;
  refused.error = lat::QueryError::kGoalUnreachable;
  const Plan::Response other = complete(refused, 0);
  EXPECT_EQ(other.status, Status::NO_PATH_FOUND);
  EXPECT_EQ(other.no_path_proof, Status::NO_PATH_NOT_PROVEN);
  EXPECT_EQ(other.enclosed_states, 0u);
  // Only a search without a solution says it: after one, the status is an internal error.
  lat::PlanResult after = searchEnded(SearchStatus::kNoSolution, 1);
  after.no_path_reason = r.no_path_reason;
  EXPECT_EQ(complete(after, 1).message.find("proven"), std::string::npos);
}

TEST(PlanResponse, EverySearchStatusAfterASolutionGivesItsCodeAndMessage) {
  const std::string summary = "2 solution(s), best cost 13.346 m, bound 2.50, certified 2.25";
  const std::string so_far = "; returning the best path so far: " + summary;
  struct Case {
    SearchStatus status;
    std::uint32_t code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {SearchStatus::kProvenOptimal, Status::SUCCESS, "optimal path: " + summary},
      {SearchStatus::kBoundReached, Status::SUCCESS, "path within the requested bound: " + summary},
      {SearchStatus::kTimeLimit, Status::SUCCESS, "time budget of 2.50 s used up" + so_far},
      {SearchStatus::kMemoryLimit, Status::SUCCESS, "search stopped (memory_limit)" + so_far},
      {SearchStatus::kExpansionLimit, Status::SUCCESS, "search stopped (expansion_limit)" + so_far},
      {SearchStatus::kCancelled, Status::CANCELLED, "cancelled" + so_far},
      {SearchStatus::kNoSolution, Status::INTERNAL_ERROR,
       "the search reported no solution after finding one: " + summary},
  };
  for (const Case& c : cases) {
    const Plan::Response res = complete(searchEnded(c.status, 2), 2);
    EXPECT_EQ(res.status, c.code) << amha::statusName(c.status);
    EXPECT_EQ(res.message, c.message);
    EXPECT_EQ(res.path.poses.size(), 2u);
  }
}

TEST(PlanResponse, TheBestSolutionGivesThePathCostAndBounds) {
  const std::vector<lat::Pose2D> published = {{0.0, 0.0, 0.0}, {0.5, 0.25, 0.5}, {1.0, 1.0, 1.0}};
  const Plan::Response res = complete(searchEnded(SearchStatus::kProvenOptimal, 3), 3, published);
  ASSERT_EQ(res.solutions.size(), 3u) << "the streamed messages are kept";
  EXPECT_EQ(res.request_id, 9u);
  EXPECT_DOUBLE_EQ(res.cost, 13.3456);
  EXPECT_DOUBLE_EQ(res.bound, 2.5);
  EXPECT_DOUBLE_EQ(res.certified_bound, 2.25);
  EXPECT_DOUBLE_EQ(res.planning_time, 0.9375);
  EXPECT_EQ(res.expansions, 4321u);
  ASSERT_EQ(res.path.poses.size(), published.size()) << "the published (smoothed) poses";
  EXPECT_EQ(res.path.header.frame_id, "map");
  EXPECT_EQ(res.path.header.stamp, ros::Time(12, 500));
  EXPECT_DOUBLE_EQ(res.path.poses[1].pose.position.x, 0.5);
  EXPECT_DOUBLE_EQ(res.path.poses[1].pose.position.y, 0.25);
  EXPECT_EQ(res.path.poses[1].header.frame_id, "map");
  EXPECT_EQ(res.planned_goal.header.frame_id, "map");
  EXPECT_EQ(res.planned_goal.header.stamp, ros::Time(12, 500));
  EXPECT_DOUBLE_EQ(res.planned_goal.pose.position.y, 4.0);
  EXPECT_FALSE(res.goal_substituted);
  EXPECT_FALSE(res.start_escaped);
  EXPECT_TRUE(res.escape_end.header.frame_id.empty());
  EXPECT_EQ(res.message,
            "optimal path: 3 solution(s), best cost 13.346 m, bound 2.50, certified 2.25");
}

TEST(PlanResponse, ASmoothedBestSolutionQuotesItsLatticeCost) {
  Plan::Response res = streamed(1);
  res.solutions.back().smoothed = true;
  res.solutions.back().lattice_cost = 14.0;
  completeResponse(searchEnded(SearchStatus::kBoundReached, 1), {{0, 0, 0}}, context(), &res);
  EXPECT_EQ(res.message,
            "path within the requested bound: 1 solution(s), best cost 13.346 m, bound 2.50, "
            "certified 2.25 (smoothed; lattice path 14.000 m)");
}

TEST(PlanResponse, TheStartEscapeAndTheGoalSubstituteAreToldAfterTheOutcome) {
  lat::PlanResult r = searchEnded(SearchStatus::kTimeLimit, 1);
  r.start_escaped = true;
  r.escape_message = "start (0.000, 0.000) is in collision; the path leaves it by 1.000 m";
  r.solutions.back().escape_poses = 2;
  r.goal_substituted = true;
  r.message = "goal (3.100, 4.000) is in collision; planning to (3.000, 4.000) instead";
  const Plan::Response res = complete(r, 1);
  EXPECT_EQ(res.status, Status::SUCCESS);
  EXPECT_EQ(
      res.message,
      "time budget of 2.50 s used up; returning the best path so far: 1 solution(s), best cost "
      "13.346 m, bound 2.50, certified 2.25; " +
          r.escape_message + "; " + r.message);
  EXPECT_TRUE(res.start_escaped);
  EXPECT_EQ(res.escape_end.header.frame_id, "map");
  EXPECT_DOUBLE_EQ(res.escape_end.pose.position.x, 1.0) << "the path's first collision-free pose";
  EXPECT_TRUE(res.goal_substituted);
  EXPECT_DOUBLE_EQ(res.planned_goal.pose.position.x, 3.0);

  // Without a solution the sentences still follow the outcome; there is no escape end.
  lat::PlanResult none = searchEnded(SearchStatus::kCancelled, 0);
  none.start_escaped = true;
  none.escape_message = r.escape_message;
  const Plan::Response cancelled = complete(none, 0);
  EXPECT_EQ(cancelled.status, Status::CANCELLED);
  EXPECT_EQ(cancelled.message, "cancelled before any path was found; " + r.escape_message);
  EXPECT_TRUE(cancelled.escape_end.header.frame_id.empty());
}

TEST(PlanResponse, RepliesWithoutPlanningCarryTheirStatusAndAnEmptyPath) {
  const Plan::Response busy = busyResponse(17, 2, "world");
  EXPECT_EQ(busy.request_id, 17u);
  EXPECT_EQ(busy.status, Status::BUSY);
  EXPECT_EQ(
      busy.message,
      "busy: one request is planning and 2 are waiting (~max_queued_requests); try again later");
  EXPECT_EQ(busy.path.header.frame_id, "world");
  EXPECT_EQ(busy.path.header.stamp, ros::Time());
  EXPECT_TRUE(busy.path.poses.empty());
  EXPECT_TRUE(busy.solutions.empty());

  const Plan::Response cancelled =
      responseWithoutPath(3, Status::CANCELLED, "cancelled", "map", ros::Time(5, 0));
  EXPECT_EQ(cancelled.request_id, 3u);
  EXPECT_EQ(cancelled.status, Status::CANCELLED);
  EXPECT_EQ(cancelled.message, "cancelled");
  EXPECT_EQ(cancelled.path.header.stamp, ros::Time(5, 0));

  EXPECT_EQ(noMapMessage("/map", ""), "no valid map received on /map yet");
  EXPECT_EQ(noMapMessage("/map", "map size 0 x 0"),
            "no usable map on /map yet: the last one was refused: map size 0 x 0");
}

/// A message's bytes on the wire.
template <class Message>
std::vector<std::uint8_t> serialized(const Message& m) {
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(m));
  ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::serialize(stream, m);
  return bytes;
}

TEST(PlanResponse, TheActionResultCarriesEveryField) {
  Plan::Response res = complete(searchEnded(SearchStatus::kCancelled, 2), 2);
  res.start_escaped = true;
  res.goal_substituted = true;
  res.escape_end.header.frame_id = "map";
  res.escape_end.pose.position.x = 0.5;
  res.no_path_proof = Status::NO_PATH_START_ENCLOSED;  // not a cancel's, but every field counts
  res.enclosed_states = 77;
  const std::vector<std::uint8_t> response = serialized(res);
  // The result repeats the response's fields in the same order: the same bytes when every
  // field is carried over.
  EXPECT_EQ(serialized(actionResult(std::move(res))), response);
}

TEST(PlanResponse, MakePlanGetsThePathOnSuccessOnlyAlwaysInTheGlobalFrame) {
  const Plan::Response ok = complete(searchEnded(SearchStatus::kProvenOptimal, 1), 1);
  const nav_msgs::GetPlan::Response plan = makePlanResponse(ok, "map");
  EXPECT_EQ(plan.plan, ok.path);

  for (const Plan::Response& failed :
       {complete(searchEnded(SearchStatus::kCancelled, 1), 1),
        responseWithoutPath(4, Status::TF_ERROR, "no tf", "", ros::Time(7, 0))}) {
    const nav_msgs::GetPlan::Response empty = makePlanResponse(failed, "map");
    EXPECT_TRUE(empty.plan.poses.empty()) << failed.message;
    EXPECT_EQ(empty.plan.header.frame_id, "map");
    EXPECT_EQ(empty.plan.header.stamp, failed.path.header.stamp);
  }
}

}  // namespace
}  // namespace amha_planner
