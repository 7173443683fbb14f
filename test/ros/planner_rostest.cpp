// Integration tests of amha_planner/PlannerNodelet (test/ros/planner_nodelet.test): the nodelet
// runs in a manager, this node publishes the map, calls ~plan, ~make_plan and ~plan_anytime, and
// checks the answers independently (paths against the published map, bounds, timing).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <future>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

#include <actionlib/client/simple_action_client.h>
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/GetPlan.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "amha_planner/Plan.h"
#include "amha_planner/PlanAnytimeAction.h"
#include "amha_planner/PlanSolution.h"
#include "rostest_support.h"

namespace amha_planner {
namespace test {
namespace {

using Client = actionlib::SimpleActionClient<PlanAnytimeAction>;
using Clock = std::chrono::steady_clock;
using Status = Plan::Response;
constexpr double kResolution = 0.05;  // the test map's
constexpr int kLethal = 65;           // the test config's lethal_threshold
constexpr double kHeadingBin = 2 * M_PI / 16;

ros::NodeHandle* g_nh = nullptr;
ros::Publisher g_map_pub;
ros::Publisher g_map_updates_pub;  // /map_updates, where costmap_2d would send partial updates

// Every message on ~solutions, for comparing with the responses.
std::mutex g_solutions_mutex;
std::vector<PlanSolution> g_solutions;

void onSolution(const PlanSolution::ConstPtr& s) {
  std::lock_guard<std::mutex> lock(g_solutions_mutex);
  g_solutions.push_back(*s);
}

std::vector<PlanSolution> solutionsOf(std::uint32_t request_id, std::size_t expected) {
  for (int i = 0; i < 200; ++i) {
    {
      std::lock_guard<std::mutex> lock(g_solutions_mutex);
      std::vector<PlanSolution> out;
      for (const auto& s : g_solutions) {
        if (s.request_id == request_id) out.push_back(s);
      }
      if (out.size() >= expected) return out;
    }
    ros::WallDuration(0.01).sleep();
  }
  std::lock_guard<std::mutex> lock(g_solutions_mutex);
  std::vector<PlanSolution> out;
  for (const auto& s : g_solutions) {
    if (s.request_id == request_id) out.push_back(s);
  }
  return out;
}

Plan::Response plan(const geometry_msgs::PoseStamped& start, const geometry_msgs::PoseStamped& goal,
                    double budget, const std::string& algorithm = "", double w1 = 0, double w2 = 0,
                    double goal_tolerance = 0) {
  Plan srv;
  srv.request.start = start;
  srv.request.goal = goal;
  srv.request.time_budget = budget;
  srv.request.algorithm = algorithm;
  srv.request.w1 = w1;
  srv.request.w2 = w2;
  srv.request.goal_tolerance = goal_tolerance;
  EXPECT_TRUE(ros::service::call("/planner/plan", srv)) << "the ~plan service call failed";
  return srv.response;
}

// Queries the planner without searching to learn which map it uses: the start lies in the
// maze's door, closed in testMapWithExtraBlock() (INVALID_START) and open in testMap() (then
// the goal, in the block of both maps, gives INVALID_GOAL).
std::uint32_t probeMap() {
  return plan(pose(11.0, 8.0, 0, "map"), pose(2.5, 4.0, 0, "map"), 1.0).status;
}
bool waitForProbe(std::uint32_t expected, double seconds) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < deadline) {
    if (probeMap() == expected) return true;
    ros::WallDuration(0.05).sleep();
  }
  return false;
}

// The path must be in the map frame, start at the start and end at the goal (within the
// lattice's resolution and heading bin), and be collision-free on `map`.
void expectValidPath(const nav_msgs::Path& path, const geometry_msgs::PoseStamped& start,
                     const geometry_msgs::PoseStamped& goal, const nav_msgs::OccupancyGrid& map) {
  ASSERT_FALSE(path.poses.empty());
  EXPECT_EQ(path.header.frame_id, "map");
  const auto& first = path.poses.front().pose;
  const auto& last = path.poses.back().pose;
  EXPECT_LE(std::hypot(first.position.x - start.pose.position.x,
                       first.position.y - start.pose.position.y),
            kResolution);
  EXPECT_LE(angleDiff(yawOf(first), yawOf(start.pose)), kHeadingBin / 2 + 1e-6);
  EXPECT_LE(
      std::hypot(last.position.x - goal.pose.position.x, last.position.y - goal.pose.position.y),
      kResolution);
  EXPECT_LE(angleDiff(yawOf(last), yawOf(goal.pose)), kHeadingBin / 2 + 1e-6);
  for (const auto& p : path.poses) EXPECT_EQ(p.header.frame_id, "map");
  const std::string collision = checkPathCollisionFree(path, map, testFootprint(), kLethal);
  EXPECT_EQ(collision, "") << "the path collides";
}

// Costs non-increasing, bounds >= 1 and non-increasing, certified <= nominal.
void expectMonotone(const std::vector<PlanSolution>& solutions) {
  for (std::size_t i = 0; i < solutions.size(); ++i) {
    const auto& s = solutions[i];
    EXPECT_GE(s.certified_bound, 1.0);
    EXPECT_GE(s.bound, 1.0);
    EXPECT_LE(s.certified_bound, s.bound + 1e-9);
    EXPECT_GT(s.cost, 0.0);
    if (i > 0) {
      const auto& p = solutions[i - 1];
      EXPECT_LE(s.cost, p.cost + 1e-9) << "solution " << i;
      EXPECT_LE(s.bound, p.bound + 1e-9) << "solution " << i;
      EXPECT_LE(s.certified_bound, p.certified_bound + 1e-9) << "solution " << i;
      EXPECT_GE(s.elapsed, p.elapsed);
    }
  }
}

// In a response's solutions[], a path repeated from the previous solution is left out.
void expectSolutionPaths(const std::vector<PlanSolution>& solutions,
                         const geometry_msgs::PoseStamped& start,
                         const geometry_msgs::PoseStamped& goal) {
  ASSERT_FALSE(solutions.empty());
  EXPECT_FALSE(solutions.front().same_path_as_previous);
  for (std::size_t i = 0; i < solutions.size(); ++i) {
    const auto& s = solutions[i];
    if (s.same_path_as_previous) {
      EXPECT_TRUE(s.path.poses.empty()) << "solution " << i;
      EXPECT_DOUBLE_EQ(s.cost, solutions[i - 1].cost) << "solution " << i;
    } else {
      expectValidPath(s.path, start, goal, testMap());
    }
  }
}

// A query across the rooms (through a door) and one through the whole maze (a long search).
const geometry_msgs::PoseStamped kRoomStart = pose(0.0, 0.0, 0.0, "map");
const geometry_msgs::PoseStamped kRoomGoal = pose(9.0, 4.0, M_PI / 2, "map");
const geometry_msgs::PoseStamped kMazeStart = pose(0.0, 0.0, 0.0, "map");
const geometry_msgs::PoseStamped kMazeGoal = pose(27.5, 16.5, 0.0, "map");

TEST(PlannerNodelet, ServesItsInterfaces) {
  EXPECT_TRUE(ros::service::waitForService("/planner/plan", ros::Duration(5)));
  EXPECT_TRUE(ros::service::waitForService("/planner/make_plan", ros::Duration(5)));
  Client client("/planner/plan_anytime", true);
  EXPECT_TRUE(client.waitForServer(ros::Duration(5)));
}

TEST(PlannerNodelet, PlanSucceedsWithAValidPathAndStreamsItsSolutions) {
  const auto res = plan(kRoomStart, kRoomGoal, 5.0);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  expectValidPath(res.path, kRoomStart, kRoomGoal, testMap());
  ASSERT_FALSE(res.solutions.empty());
  expectMonotone(res.solutions);
  const auto& best = res.solutions.back();
  EXPECT_DOUBLE_EQ(res.cost, best.cost);
  EXPECT_DOUBLE_EQ(res.bound, best.bound);
  EXPECT_DOUBLE_EQ(res.certified_bound, best.certified_bound);
  // The best path is the last one sent in full (a solution that repeats it leaves it out).
  auto sent = res.solutions.rbegin();
  while (sent != res.solutions.rend() && sent->same_path_as_previous) ++sent;
  ASSERT_NE(sent, res.solutions.rend());
  EXPECT_EQ(res.path.poses.size(), sent->path.poses.size());
  // The straight-line distance is a lower bound on the cost (metres-equivalent).
  EXPECT_GE(res.cost + 1e-6, std::hypot(9.0, 4.0));
  expectSolutionPaths(res.solutions, kRoomStart, kRoomGoal);
  for (const auto& s : res.solutions) EXPECT_EQ(s.request_id, res.request_id);
  // ~solutions carried the same solutions, in order, each with its full path.
  const auto streamed = solutionsOf(res.request_id, res.solutions.size());
  ASSERT_EQ(streamed.size(), res.solutions.size());
  expectMonotone(streamed);
  for (std::size_t i = 0; i < streamed.size(); ++i) {
    EXPECT_DOUBLE_EQ(streamed[i].cost, res.solutions[i].cost);
    EXPECT_DOUBLE_EQ(streamed[i].bound, res.solutions[i].bound);
    EXPECT_EQ(streamed[i].same_path_as_previous, res.solutions[i].same_path_as_previous);
    expectValidPath(streamed[i].path, kRoomStart, kRoomGoal, testMap());
    if (i > 0 && streamed[i].same_path_as_previous) {
      EXPECT_EQ(streamed[i].path.poses.size(), streamed[i - 1].path.poses.size());
    }
  }
  // ~plan (latched) holds the latest path; ~footprints the markers along it.
  auto latched = ros::topic::waitForMessage<nav_msgs::Path>("/planner/plan", ros::Duration(5));
  ASSERT_TRUE(latched);
  EXPECT_EQ(latched->poses.size(), res.path.poses.size());
  auto markers = ros::topic::waitForMessage<visualization_msgs::MarkerArray>("/planner/footprints",
                                                                             ros::Duration(5));
  ASSERT_TRUE(markers);
  bool footprints = false, start = false, goal = false;
  for (const auto& m : markers->markers) {
    footprints |= m.ns == "footprints" && m.points.size() >= 8;
    start |= m.ns == "start";
    goal |= m.ns == "goal";
  }
  EXPECT_TRUE(footprints && start && goal);
}

TEST(PlannerNodelet, EveryAlgorithmGivesValidMonotoneSolutions) {
  for (const char* algorithm : {"amha", "mha", "ara", "ana", "wastar", "astar"}) {
    SCOPED_TRACE(algorithm);
    const auto res = plan(kRoomStart, kRoomGoal, 5.0, algorithm);
    ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
    expectValidPath(res.path, kRoomStart, kRoomGoal, testMap());
    expectMonotone(res.solutions);
  }
}

TEST(PlannerNodelet, PublishesSmoothedPathsAndKeepsTheLatticePaths) {
  // ~smooth_path is on by default: every solution's path is smoothed, no costlier than its
  // lattice path, which comes along; both are valid paths from the start to the goal.
  const auto res = plan(kMazeStart, kMazeGoal, 5.0);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  ASSERT_FALSE(res.solutions.empty());
  expectMonotone(res.solutions);
  int differ = 0;
  const PlanSolution* previous = nullptr;
  for (const auto& s : res.solutions) {
    EXPECT_TRUE(s.smoothed);
    EXPECT_LE(s.cost, s.lattice_cost + 1e-9);
    // The lattice path is left out only where it repeats the previous one.
    if (!s.lattice_path.poses.empty()) {
      expectValidPath(s.lattice_path, kMazeStart, kMazeGoal, testMap());
      if (!s.path.poses.empty()) {
        const auto& a = s.path.poses;
        const auto& b = s.lattice_path.poses;
        EXPECT_EQ(a.front().pose.position.x, b.front().pose.position.x);
        EXPECT_EQ(a.front().pose.position.y, b.front().pose.position.y);
        EXPECT_EQ(a.back().pose.position.x, b.back().pose.position.x);
        EXPECT_EQ(a.back().pose.position.y, b.back().pose.position.y);
        differ += s.cost < s.lattice_cost - 1e-9;
      }
    } else {
      ASSERT_NE(previous, nullptr);
    }
    previous = &s;
  }
  EXPECT_GT(differ, 0) << "the maze's lattice paths should be shortened";
  EXPECT_NE(res.message.find("smoothed"), std::string::npos) << res.message;
  expectValidPath(res.path, kMazeStart, kMazeGoal, testMap());
}

TEST(PlannerNodelet, ActionSendsOneFeedbackPerSolution) {
  // Declared before the client, whose destructor stops its callback thread: a feedback still
  // in flight when the test returns must not write into destroyed locals.
  std::mutex m;
  std::condition_variable cv;
  std::vector<PlanSolution> feedback;
  Client client("/planner/plan_anytime", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(5)));
  PlanAnytimeGoal goal;
  goal.start = kRoomStart;
  goal.goal = kRoomGoal;
  goal.time_budget = 5.0;
  client.sendGoal(goal, Client::SimpleDoneCallback(), Client::SimpleActiveCallback(),
                  [&](const PlanAnytimeFeedbackConstPtr& f) {
                    std::lock_guard<std::mutex> lock(m);
                    feedback.push_back(f->solution);
                    cv.notify_all();
                  });
  ASSERT_TRUE(client.waitForResult(ros::Duration(30)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);
  const auto result = client.getResult();
  ASSERT_EQ(result->status, PlanAnytimeResult::SUCCESS) << result->message;
  expectValidPath(result->path, kRoomStart, kRoomGoal, testMap());
  std::unique_lock<std::mutex> lock(m);
  // Feedback and result travel on separate topics, so the last feedback may arrive after the
  // result: give it time (a missing one still fails below).
  cv.wait_for(lock, std::chrono::seconds(5),
              [&] { return feedback.size() >= result->solutions.size(); });
  ASSERT_EQ(feedback.size(), result->solutions.size());
  for (std::size_t i = 0; i < feedback.size(); ++i) {
    EXPECT_DOUBLE_EQ(feedback[i].cost, result->solutions[i].cost);
    expectValidPath(feedback[i].path, kRoomStart, kRoomGoal, testMap());  // always a full path
  }
  expectMonotone(feedback);
  expectSolutionPaths(result->solutions, kRoomStart, kRoomGoal);
}

TEST(PlannerNodelet, CancelStopsWithinFiftyMillisecondsWithTheBestPath) {
  std::mutex m;  // (before the client: see ActionSendsOneFeedbackPerSolution)
  std::condition_variable cv;
  std::vector<PlanSolution> feedback;
  bool done = false;
  Clock::time_point done_at;
  Client client("/planner/plan_anytime", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(5)));
  PlanAnytimeGoal goal;
  goal.start = kMazeStart;
  goal.goal = kMazeGoal;
  goal.time_budget = 60.0;
  client.sendGoal(
      goal,
      [&](const actionlib::SimpleClientGoalState&, const PlanAnytimeResultConstPtr&) {
        std::lock_guard<std::mutex> lock(m);
        done = true;
        done_at = Clock::now();
        cv.notify_all();
      },
      Client::SimpleActiveCallback(),
      [&](const PlanAnytimeFeedbackConstPtr& f) {
        std::lock_guard<std::mutex> lock(m);
        feedback.push_back(f->solution);
        cv.notify_all();
      });
  {
    std::unique_lock<std::mutex> lock(m);
    ASSERT_TRUE(
        cv.wait_for(lock, std::chrono::seconds(30), [&] { return !feedback.empty() || done; }));
    ASSERT_FALSE(done) << "the maze search finished before it could be cancelled: make it harder";
  }
  ros::WallDuration(0.05).sleep();  // cancel in the middle of an improvement, not right after one
  Clock::time_point cancelled_at;
  {
    std::lock_guard<std::mutex> lock(m);
    ASSERT_FALSE(done) << "the maze search finished before it could be cancelled: make it harder";
    cancelled_at = Clock::now();
  }
  client.cancelGoal();
  {
    std::unique_lock<std::mutex> lock(m);
    ASSERT_TRUE(cv.wait_for(lock, std::chrono::seconds(5), [&] { return done; }));
  }
  const double latency = std::chrono::duration<double>(done_at - cancelled_at).count();
  const auto result = client.getResult();
  std::printf("[ INFO     ] cancel -> result: %.1f ms, %zu solution(s) before it, result %u kB\n",
              latency * 1e3, feedback.size(),
              ros::serialization::serializationLength(*result) / 1024);
  EXPECT_LT(latency, 0.050) << "the result must arrive within 50 ms of the cancel";
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::PREEMPTED);
  EXPECT_EQ(result->status, PlanAnytimeResult::CANCELLED) << result->message;
  ASSERT_FALSE(result->solutions.empty());
  std::unique_lock<std::mutex> lock(m);
  cv.wait_for(lock, std::chrono::seconds(5),
              [&] { return feedback.size() >= result->solutions.size(); });
  EXPECT_EQ(result->solutions.size(), feedback.size());
  EXPECT_DOUBLE_EQ(result->cost, feedback.back().cost) << "the best path so far";
  expectValidPath(result->path, kMazeStart, kMazeGoal, testMap());
}

TEST(PlannerNodelet, MakePlanWorks) {
  nav_msgs::GetPlan srv;
  srv.request.start = kRoomStart;
  srv.request.goal = pose(3.5, -1.0, 0.0, "map");
  ASSERT_TRUE(ros::service::call("/planner/make_plan", srv));
  expectValidPath(srv.response.plan, srv.request.start, srv.request.goal, testMap());
  // A failure is an empty plan (as move_base's make_plan does).
  srv.request.goal = pose(2.5, 4.0, 0.0, "map");  // in the block
  ASSERT_TRUE(ros::service::call("/planner/make_plan", srv));
  EXPECT_TRUE(srv.response.plan.poses.empty());
}

// Sends one goal to ~plan_anytime and waits for its end (10 s at most; result null if none).
struct ActionOutcome {
  actionlib::SimpleClientGoalState state{actionlib::SimpleClientGoalState::LOST};
  PlanAnytimeResultConstPtr result;
};
ActionOutcome runAction(const PlanAnytimeGoal& goal) {
  Client client("/planner/plan_anytime", true);
  ActionOutcome out;
  if (!client.waitForServer(ros::Duration(5))) return out;
  client.sendGoal(goal);
  if (!client.waitForResult(ros::Duration(10))) return out;
  out.state = client.getState();
  out.result = client.getResult();
  return out;
}

Plan::Response planWithTolerance(const geometry_msgs::PoseStamped& goal, double tolerance) {
  Plan srv;
  srv.request.start = kRoomStart;
  srv.request.goal = goal;
  srv.request.time_budget = 5.0;
  srv.request.goal_tolerance = tolerance;
  EXPECT_TRUE(ros::service::call("/planner/plan", srv)) << "the ~plan service call failed";
  return srv.response;
}

// A substitute goal: a valid path to planned_goal, which lies within the tolerance of the goal.
void expectSubstitute(const Plan::Response& res, const geometry_msgs::PoseStamped& goal,
                      double tolerance) {
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_TRUE(res.goal_substituted);
  EXPECT_NE(res.message.find("instead"), std::string::npos) << res.message;
  EXPECT_EQ(res.planned_goal.header.frame_id, "map");
  const auto& p = res.planned_goal.pose.position;
  EXPECT_LE(std::hypot(p.x - goal.pose.position.x, p.y - goal.pose.position.y), tolerance);
  expectValidPath(res.path, kRoomStart, res.planned_goal, testMap());
}

TEST(PlannerNodelet, GoalToleranceReplacesAnObstructedGoalByAReachableOne) {
  // A goal in the block: refused without a tolerance or with too small a one, replaced with one.
  const auto in_block = pose(2.5, 4.0, 0.0, "map");
  auto res = planWithTolerance(in_block, 0.0);
  EXPECT_EQ(res.status, Status::INVALID_GOAL) << res.message;
  EXPECT_FALSE(res.goal_substituted);
  res = planWithTolerance(in_block, 0.3);
  EXPECT_EQ(res.status, Status::INVALID_GOAL) << res.message;
  EXPECT_NE(res.message.find("goal tolerance"), std::string::npos) << res.message;
  expectSubstitute(planWithTolerance(in_block, 1.0), in_block, 1.0);

  // A free goal is planned to exactly, tolerance or not.
  res = planWithTolerance(kRoomGoal, 1.0);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_FALSE(res.goal_substituted);
  expectValidPath(res.path, kRoomStart, kRoomGoal, testMap());

  // In the closed pocket's wall: the free poses inside are nearer (about 0.3 m against 0.4 m)
  // but out of reach, so the substitute is outside; with a tolerance that reaches only the
  // inside, there is no path.
  const auto in_pocket_wall = pose(7.15, 15.0, 0.0, "map");
  res = planWithTolerance(in_pocket_wall, 0.6);
  expectSubstitute(res, in_pocket_wall, 0.6);
  EXPECT_LT(res.planned_goal.pose.position.x, 7.0);
  res = planWithTolerance(pose(7.3, 15.0, M_PI / 2, "map"), 0.2);
  EXPECT_EQ(res.status, Status::NO_PATH_FOUND) << res.message;
  EXPECT_TRUE(res.path.poses.empty());

  // make_plan reads GetPlan's tolerance.
  nav_msgs::GetPlan srv;
  srv.request.start = kRoomStart;
  srv.request.goal = in_block;
  srv.request.tolerance = 1.0;
  ASSERT_TRUE(ros::service::call("/planner/make_plan", srv));
  ASSERT_FALSE(srv.response.plan.poses.empty());
  const auto& end = srv.response.plan.poses.back().pose.position;
  EXPECT_LE(std::hypot(end.x - 2.5, end.y - 4.0), 1.0);
  EXPECT_EQ(checkPathCollisionFree(srv.response.plan, testMap(), testFootprint(), kLethal), "");
  srv.request.tolerance = -1.0;
  ASSERT_TRUE(ros::service::call("/planner/make_plan", srv));
  EXPECT_TRUE(srv.response.plan.poses.empty());

  // The action too.
  PlanAnytimeGoal goal;
  goal.start = kRoomStart;
  goal.goal = in_block;
  goal.goal_tolerance = 1.0;
  const ActionOutcome out = runAction(goal);
  ASSERT_TRUE(out.result);
  EXPECT_EQ(out.state, actionlib::SimpleClientGoalState::SUCCEEDED);
  EXPECT_TRUE(out.result->goal_substituted);
  EXPECT_EQ(out.result->planned_goal.header.frame_id, "map");
  expectValidPath(out.result->path, kRoomStart, out.result->planned_goal, testMap());
}

// `map` with every cell whose centre lies inside the footprint at `p`, grown by `margin` metres
// on each side, made free: the obstacle cells a start escape may cross.
nav_msgs::OccupancyGrid clearedUnder(nav_msgs::OccupancyGrid map, const geometry_msgs::Pose& p,
                                     double margin) {
  std::vector<std::array<double, 2>> poly = testFootprint();
  const double yaw = yawOf(p), c = std::cos(yaw), sn = std::sin(yaw);
  for (auto& v : poly) {
    const double x = v[0] + std::copysign(margin, v[0]), y = v[1] + std::copysign(margin, v[1]);
    v = {p.position.x + c * x - sn * y, p.position.y + sn * x + c * y};
  }
  const double r = map.info.resolution;
  const unsigned w = map.info.width;
  for (std::size_t k = 0; k < map.data.size(); ++k) {
    const double x = map.info.origin.position.x + (k % w + 0.5) * r;
    const double y = map.info.origin.position.y + (k / w + 0.5) * r;
    bool inside = false;  // even-odd rule
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
      if ((poly[i][1] > y) != (poly[j][1] > y) && x < poly[i][0] + (y - poly[i][1]) *
                                                                       (poly[j][0] - poly[i][0]) /
                                                                       (poly[j][1] - poly[i][1])) {
        inside = !inside;
      }
    }
    if (inside) map.data[k] = 0;
  }
  return map;
}

// Where `end` lies on `path` (a pose equal to it), or the path's length if nowhere.
std::size_t indexOf(const nav_msgs::Path& path, const geometry_msgs::Pose& end) {
  for (std::size_t k = 0; k < path.poses.size(); ++k) {
    const auto& q = path.poses[k].pose;
    if (std::hypot(q.position.x - end.position.x, q.position.y - end.position.y) < 1e-6 &&
        angleDiff(yawOf(q), yawOf(end)) < 1e-6) {
      return k;
    }
  }
  return path.poses.size();
}

// An escape: the path begins at the start, reaches escape_end within the tolerance touching no
// obstacle but those under the start's footprint, and goes on collision-free to the goal.
template <class Response>
void expectEscape(const Response& res, const geometry_msgs::PoseStamped& start,
                  const geometry_msgs::PoseStamped& goal, double tolerance) {
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_TRUE(res.start_escaped);
  EXPECT_NE(res.message.find("is in collision"), std::string::npos) << res.message;
  EXPECT_NE(res.message.find("leaves it by"), std::string::npos) << res.message;
  EXPECT_NE(res.message.find("relative to the optimum"), std::string::npos) << res.message;
  EXPECT_EQ(res.escape_end.header.frame_id, "map");
  const auto& e = res.escape_end.pose.position;
  EXPECT_LE(std::hypot(e.x - start.pose.position.x, e.y - start.pose.position.y),
            tolerance + kResolution);
  const std::size_t k = indexOf(res.path, res.escape_end.pose);
  ASSERT_LT(k, res.path.poses.size()) << "escape_end is not on the path";
  ASSERT_GT(k, 0u);
  nav_msgs::Path escape = res.path, rest = res.path;
  escape.poses.resize(k + 1);
  rest.poses.erase(rest.poses.begin(), rest.poses.begin() + static_cast<std::ptrdiff_t>(k));
  EXPECT_NE(checkPathCollisionFree(escape, testMap(), testFootprint(), kLethal), "")
      << "the start collides";
  EXPECT_EQ(checkPathCollisionFree(escape, clearedUnder(testMap(), start.pose, kResolution),
                                   testFootprint(), kLethal),
            "")
      << "the escape touches an obstacle the robot was not on";
  expectValidPath(rest, res.escape_end, goal, testMap());
  EXPECT_LE(std::hypot(res.path.poses.front().pose.position.x - start.pose.position.x,
                       res.path.poses.front().pose.position.y - start.pose.position.y),
            kResolution);
}

TEST(PlannerNodelet, StartToleranceLeavesAStartInCollision) {
  // Facing away from the block, its rear 0.15 m inside it.
  const auto at_block = pose(1.9, 4.0, M_PI, "map");
  Plan srv;
  srv.request.start = at_block;
  srv.request.goal = kRoomGoal;
  srv.request.time_budget = 5.0;
  ASSERT_TRUE(ros::service::call("/planner/plan", srv));
  EXPECT_EQ(srv.response.status, Status::INVALID_START) << srv.response.message;
  EXPECT_FALSE(srv.response.start_escaped);
  srv.request.start_tolerance = 0.5;
  ASSERT_TRUE(ros::service::call("/planner/plan", srv));
  expectEscape(srv.response, at_block, kRoomGoal, 0.5);
  expectMonotone(srv.response.solutions);

  // The action too, with the same request.
  const Plan::Request& r = srv.request;
  PlanAnytimeGoal goal;
  goal.start = r.start;
  goal.goal = r.goal;
  goal.time_budget = r.time_budget;
  goal.start_tolerance = r.start_tolerance;
  const ActionOutcome out = runAction(goal);
  ASSERT_TRUE(out.result);
  EXPECT_EQ(out.state, actionlib::SimpleClientGoalState::SUCCEEDED);
  expectEscape(*out.result, at_block, kRoomGoal, 0.5);

  // Deep in the block no escape crosses only what the robot stands on.
  srv.request.start = pose(2.5, 4.0, 0.0, "map");
  ASSERT_TRUE(ros::service::call("/planner/plan", srv));
  EXPECT_EQ(srv.response.status, Status::INVALID_START) << srv.response.message;
  EXPECT_NE(srv.response.message.find("within the start tolerance of 0.500 m"), std::string::npos)
      << srv.response.message;
  // ~make_plan has no start tolerance: ~start_tolerance (0 in the test's parameters) refuses it.
  nav_msgs::GetPlan mp;
  mp.request.start = at_block;
  mp.request.goal = kRoomGoal;
  ASSERT_TRUE(ros::service::call("/planner/make_plan", mp));
  EXPECT_TRUE(mp.response.plan.poses.empty());
  // A bad tolerance.
  srv.request.start = at_block;
  for (const double bad :
       {-0.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    srv.request.start_tolerance = bad;
    ASSERT_TRUE(ros::service::call("/planner/plan", srv));
    EXPECT_EQ(srv.response.status, Status::INVALID_REQUEST) << bad;
  }
}

TEST(PlannerNodelet, IgnoreGoalHeadingEndsWithTheCheapestHeading) {
  // A goal 1.5 m ahead, facing back: held to its heading the robot must turn around there;
  // free, it drives straight in.
  const auto facing_back = pose(1.5, 0.0, M_PI, "map");
  const auto fixed = plan(kRoomStart, facing_back, 5.0, "astar");
  ASSERT_EQ(fixed.status, Status::SUCCESS) << fixed.message;
  Plan srv;
  srv.request.start = kRoomStart;
  srv.request.goal = facing_back;
  srv.request.time_budget = 5.0;
  srv.request.algorithm = "astar";
  srv.request.ignore_goal_heading = true;
  ASSERT_TRUE(ros::service::call("/planner/plan", srv));
  const auto& res = srv.response;
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  // A*'s lattice optima (the published paths are smoothed, each from its own).
  EXPECT_LT(res.solutions.back().lattice_cost, fixed.solutions.back().lattice_cost);
  EXPECT_FALSE(res.goal_substituted);
  EXPECT_EQ(res.planned_goal.header.frame_id, "map");
  EXPECT_LE(angleDiff(yawOf(res.planned_goal.pose), 0.0), kHeadingBin / 2)
      << "it arrives facing ahead";
  expectValidPath(res.path, kRoomStart, res.planned_goal, testMap());
  EXPECT_LE(std::hypot(res.planned_goal.pose.position.x - 1.5, res.planned_goal.pose.position.y),
            kResolution);
}

TEST(PlannerNodelet, StartFromTfAndGoalInAnotherFrame) {
  // planner_nodelet.test publishes map -> base_link (1, 1, yaw 0.5) and map -> odom
  // (0.5, -0.5, yaw 0.3).
  geometry_msgs::PoseStamped start;  // empty frame: the robot's pose
  const auto goal_in_odom = pose(3.0, 2.0, 0.2, "odom");
  const double c = std::cos(0.3), s = std::sin(0.3);
  const auto goal_in_map = pose(0.5 + c * 3.0 - s * 2.0, -0.5 + s * 3.0 + c * 2.0, 0.5, "map");
  const auto res = plan(start, goal_in_odom, 5.0);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  expectValidPath(res.path, pose(1.0, 1.0, 0.5, "map"), goal_in_map, testMap());

  nav_msgs::GetPlan srv;  // make_plan: the same convention
  srv.request.goal = goal_in_odom;
  ASSERT_TRUE(ros::service::call("/planner/make_plan", srv));
  expectValidPath(srv.response.plan, pose(1.0, 1.0, 0.5, "map"), goal_in_map, testMap());
}

TEST(PlannerNodelet, BadRequestsGetTheirStatusAndTheNodeStaysUp) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto with_quaternion = [](geometry_msgs::PoseStamped p, double x, double y, double z, double w) {
    p.pose.orientation.x = x;
    p.pose.orientation.y = y;
    p.pose.orientation.z = z;
    p.pose.orientation.w = w;
    return p;
  };
  struct Case {
    const char* what;
    geometry_msgs::PoseStamped start, goal;
    double budget;
    std::string algorithm;
    double w1;
    std::uint32_t expected;
    double goal_tolerance = 0.0;
  };
  auto nan_position = kRoomStart;
  nan_position.pose.position.x = nan;
  const std::vector<Case> cases = {
      {"start in an obstacle", pose(2.5, 4.0, 0, "map"), kRoomGoal, 2, "", 0,
       Status::INVALID_START},
      {"goal in an obstacle", kRoomStart, pose(2.5, 4.0, 0, "map"), 2, "", 0, Status::INVALID_GOAL},
      {"goal in a wall", kRoomStart, pose(5.0, 5.0, 0, "map"), 2, "", 0, Status::INVALID_GOAL},
      {"start outside the map", pose(-5.0, 0.0, 0, "map"), kRoomGoal, 2, "", 0, Status::OUT_OF_MAP},
      {"goal outside the map", kRoomStart, pose(0.0, 30.0, 0, "map"), 2, "", 0, Status::OUT_OF_MAP},
      {"NaN start quaternion", with_quaternion(kRoomStart, 0, 0, nan, 1), kRoomGoal, 2, "", 0,
       Status::INVALID_START},
      {"zero start quaternion", with_quaternion(kRoomStart, 0, 0, 0, 0), kRoomGoal, 2, "", 0,
       Status::INVALID_START},
      {"non-normalised goal quaternion", kRoomStart, with_quaternion(kRoomGoal, 0, 0, 0, 2), 2, "",
       0, Status::INVALID_GOAL},
      {"slightly non-normalised goal quaternion", kRoomStart,
       with_quaternion(kRoomGoal, 0, 0, 0, 1.01), 2, "", 0, Status::INVALID_GOAL},
      {"NaN start position", nan_position, kRoomGoal, 2, "", 0, Status::INVALID_START},
      {"start in an unknown frame", pose(0, 0, 0, "nowhere"), kRoomGoal, 2, "", 0,
       Status::TF_ERROR},
      {"goal in an unknown frame", kRoomStart, pose(1, 1, 0, "nowhere"), 2, "", 0,
       Status::TF_ERROR},
      {"unknown algorithm", kRoomStart, kRoomGoal, 2, "dijkstra", 0, Status::INVALID_REQUEST},
      {"weight below 1", kRoomStart, kRoomGoal, 2, "", 0.5, Status::INVALID_REQUEST},
      {"negative time budget", kRoomStart, kRoomGoal, -1, "", 0, Status::INVALID_REQUEST},
      {"negative goal tolerance", kRoomStart, kRoomGoal, 2, "", 0, Status::INVALID_REQUEST, -0.5},
      {"NaN goal tolerance", kRoomStart, kRoomGoal, 2, "", 0, Status::INVALID_REQUEST, nan},
      {"goal in a closed pocket", kRoomStart, pose(8.0, 15.0, 0, "map"), 20, "", 0,
       Status::NO_PATH_FOUND},
      {"no time for A* through the maze", kMazeStart, kMazeGoal, 1e-4, "astar", 0,
       Status::TIME_EXHAUSTED},
      {"quaternion within 1e-3 of unit norm", kRoomStart,
       with_quaternion(kRoomGoal, 0, 0, std::sin(M_PI / 4) * 1.0005, std::cos(M_PI / 4) * 1.0005),
       5, "", 0, Status::SUCCESS},
  };
  for (const auto& c : cases) {
    const auto res = plan(c.start, c.goal, c.budget, c.algorithm, c.w1, 0, c.goal_tolerance);
    EXPECT_EQ(res.status, c.expected) << c.what << ": " << res.message;
    EXPECT_FALSE(res.message.empty()) << c.what;
    if (c.expected != Status::SUCCESS) {
      EXPECT_TRUE(res.path.poses.empty()) << c.what;
    }
  }
  // The action reports the same statuses (aborted).
  PlanAnytimeGoal goal;
  goal.start = kRoomStart;
  goal.goal = pose(2.5, 4.0, 0, "map");
  const ActionOutcome out = runAction(goal);
  ASSERT_TRUE(out.result);
  EXPECT_EQ(out.state, actionlib::SimpleClientGoalState::ABORTED);
  EXPECT_EQ(out.result->status, PlanAnytimeResult::INVALID_GOAL);
  // And the node still plans.
  const auto res = plan(kRoomStart, kRoomGoal, 5.0);
  EXPECT_EQ(res.status, Status::SUCCESS) << res.message;
}

TEST(PlannerNodelet, BadMapsAreRefusedAndTheCurrentMapKept) {
  // Each bad map is the closed-door map broken in one way: were it accepted, the probe's start
  // would be blocked (INVALID_START) instead of free (INVALID_GOAL).
  ASSERT_EQ(probeMap(), Status::INVALID_GOAL);
  std::vector<std::pair<std::string, nav_msgs::OccupancyGrid>> bad;
  auto m = testMapWithExtraBlock();
  m.data.pop_back();
  bad.emplace_back("data length != width x height", m);
  m = testMapWithExtraBlock();
  m.info.resolution = 0.0f;
  bad.emplace_back("zero resolution", m);
  m = testMapWithExtraBlock();
  m.info.resolution = std::numeric_limits<float>::quiet_NaN();
  bad.emplace_back("NaN resolution", m);
  m = testMapWithExtraBlock();
  m.info.origin.position.x = std::numeric_limits<double>::infinity();
  bad.emplace_back("infinite origin", m);
  m = testMapWithExtraBlock();
  m.info.width = 0;
  m.info.height = 0;
  m.data.clear();
  bad.emplace_back("empty map", m);
  m = testMapWithExtraBlock();
  m.info.width = 2000;  // 2000 x 1000 = 2e6 cells > ~max_map_cells (1e6) of the test config
  m.info.height = 1000;
  m.data.assign(2000u * 1000u, 0);
  bad.emplace_back("too many cells", m);
  for (const auto& b : bad) {
    g_map_pub.publish(b.second);
    ros::WallDuration(0.5).sleep();  // a refusal takes microseconds; leave time to process it
    EXPECT_EQ(probeMap(), Status::INVALID_GOAL) << b.first << ": the bad map was used";
  }
  const auto res = plan(kRoomStart, kRoomGoal, 5.0);
  EXPECT_EQ(res.status, Status::SUCCESS) << res.message;
  expectValidPath(res.path, kRoomStart, kRoomGoal, testMap());
}

TEST(PlannerNodelet, NewMapDuringALongPlanNeitherCrashesNorCorruptsIt) {
  std::atomic<int> feedback{0};  // before the client: see ActionSendsOneFeedbackPerSolution
  Client client("/planner/plan_anytime", true);
  ASSERT_TRUE(sendAndAwaitFeedback(client, kMazeStart, kMazeGoal, 3.0, feedback));
  EXPECT_FALSE(client.getState().isDone()) << "the plan should still be running";
  // The new map closes the maze's door: the running plan must not notice.
  g_map_pub.publish(testMapWithExtraBlock());
  ASSERT_TRUE(client.waitForResult(ros::Duration(30)));
  const auto result = client.getResult();
  ASSERT_EQ(result->status, PlanAnytimeResult::SUCCESS) << result->message;
  expectValidPath(result->path, kMazeStart, kMazeGoal, testMap());  // the map it started on
  expectMonotone(result->solutions);
  expectSolutionPaths(result->solutions, kMazeStart, kMazeGoal);
  // The next requests use the new map: the maze cannot be reached any more.
  EXPECT_TRUE(waitForProbe(Status::INVALID_START, 20.0)) << "the new map was not adopted";
  const auto closed = plan(kMazeStart, kMazeGoal, 5.0);
  EXPECT_EQ(closed.status, Status::NO_PATH_FOUND) << closed.message;
  // The answer says what proved it (the walk, the search or the heuristics).
  EXPECT_NE(closed.message.find("cannot be reached from the start on this map (proven "),
            std::string::npos)
      << closed.message;
  EXPECT_NE(closed.no_path_proof, Status::NO_PATH_NOT_PROVEN);
  // Then the original one again.
  g_map_pub.publish(testMap());
  EXPECT_TRUE(waitForProbe(Status::INVALID_GOAL, 20.0)) << "the original map was not restored";
}

// The update that turns map `from` into `to`: the bounding box of the cells that differ.
map_msgs::OccupancyGridUpdate updateBetween(const nav_msgs::OccupancyGrid& from,
                                            const nav_msgs::OccupancyGrid& to) {
  const int w = static_cast<int>(from.info.width), h = static_cast<int>(from.info.height);
  int x0 = w, y0 = h, x1 = -1, y1 = -1;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (from.data[y * w + x] == to.data[y * w + x]) continue;
      x0 = std::min(x0, x);
      y0 = std::min(y0, y);
      x1 = std::max(x1, x);
      y1 = std::max(y1, y);
    }
  }
  map_msgs::OccupancyGridUpdate u;
  u.header.frame_id = "map";
  u.x = x0;
  u.y = y0;
  u.width = static_cast<std::uint32_t>(x1 - x0 + 1);
  u.height = static_cast<std::uint32_t>(y1 - y0 + 1);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) u.data.push_back(to.data[y * w + x]);
  }
  return u;
}

TEST(PlannerNodelet, MapUpdatesPatchTheMapAndBadOnesAreRefused) {
  ASSERT_EQ(probeMap(), Status::INVALID_GOAL);
  ASSERT_TRUE(waitForSubscriber(g_map_updates_pub, 5.0)) << "the planner is not on /map_updates";
  // Close the maze's door with an update only (no new map).
  const auto close = updateBetween(testMap(), testMapWithExtraBlock());
  ASSERT_GT(close.data.size(), 0u);
  ASSERT_LT(close.data.size(), testMap().data.size() / 100) << "the update should be small";
  g_map_updates_pub.publish(close);
  EXPECT_TRUE(waitForProbe(Status::INVALID_START, 20.0)) << "the update was not applied";
  EXPECT_EQ(plan(kMazeStart, kMazeGoal, 5.0).status, Status::NO_PATH_FOUND);
  // Bad updates: each would reopen the door if applied; the closed map must stay.
  std::vector<std::pair<std::string, map_msgs::OccupancyGridUpdate>> bad;
  auto open = updateBetween(testMapWithExtraBlock(), testMap());
  auto u = open;
  u.data.pop_back();
  bad.emplace_back("data length != width x height", u);
  u = open;
  u.x = static_cast<std::int32_t>(testMap().info.width - u.width + 1);
  bad.emplace_back("rectangle past the right edge", u);
  u = open;
  u.header.frame_id = "odom";
  bad.emplace_back("another frame", u);
  for (const auto& b : bad) {
    g_map_updates_pub.publish(b.second);
    ros::WallDuration(0.5).sleep();
    EXPECT_EQ(probeMap(), Status::INVALID_START) << b.first << ": the bad update was used";
  }
  // Reopen it: the map is testMap() again, cell for cell, and plans through the maze work.
  g_map_updates_pub.publish(open);
  EXPECT_TRUE(waitForProbe(Status::INVALID_GOAL, 20.0)) << "the reopening update was not applied";
  const auto res = plan(kMazeStart, kMazeGoal, 5.0);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  expectValidPath(res.path, kMazeStart, kMazeGoal, testMap());
}

// Updates that come faster than planners are built are folded into fewer builds: whatever the
// folding, the planner must end on the last update (none lost, no older build swapped in after
// a newer one), and stay there.
TEST(PlannerNodelet, ABurstOfUpdatesEndsOnTheLastOne) {
  ASSERT_EQ(probeMap(), Status::INVALID_GOAL);
  ASSERT_TRUE(waitForSubscriber(g_map_updates_pub, 5.0)) << "the planner is not on /map_updates";
  const auto close = updateBetween(testMap(), testMapWithExtraBlock());
  const auto open = updateBetween(testMapWithExtraBlock(), testMap());
  const auto stays = [](std::uint32_t expected) {
    for (int i = 0; i < 10; ++i) {
      if (probeMap() != expected) return false;
      ros::WallDuration(0.1).sleep();
    }
    return true;
  };
  // 41 updates back to back, alternately closing and opening the maze's door: closed at the end.
  for (int i = 0; i <= 40; ++i) g_map_updates_pub.publish(i % 2 == 0 ? close : open);
  EXPECT_TRUE(waitForProbe(Status::INVALID_START, 20.0)) << "the last update (closed) never came";
  EXPECT_TRUE(stays(Status::INVALID_START)) << "an older map replaced the last one";
  // The same, ending open: the map is testMap() again, cell for cell.
  for (int i = 0; i <= 40; ++i) g_map_updates_pub.publish(i % 2 == 0 ? open : close);
  EXPECT_TRUE(waitForProbe(Status::INVALID_GOAL, 20.0)) << "the last update (open) never came";
  EXPECT_TRUE(stays(Status::INVALID_GOAL)) << "an older map replaced the last one";
  const auto res = plan(kMazeStart, kMazeGoal, 5.0);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  expectValidPath(res.path, kMazeStart, kMazeGoal, testMap());
}

TEST(PlannerNodelet, ASecondRequestWaitsAndAThirdGetsBusy) {
  // planner_nodelet.test sets ~max_queued_requests to 1.
  std::atomic<int> feedback{0};  // before the client: see ActionSendsOneFeedbackPerSolution
  Client client("/planner/plan_anytime", true);
  ASSERT_TRUE(sendAndAwaitFeedback(client, kMazeStart, kMazeGoal, 2.0, feedback));
  auto second = std::async(std::launch::async, [] { return plan(kRoomStart, kRoomGoal, 5.0); });
  ros::WallDuration(0.3).sleep();  // let the second request reach the queue
  const auto t0 = Clock::now();
  const auto third = plan(kRoomStart, kRoomGoal, 5.0);
  const double third_s = std::chrono::duration<double>(Clock::now() - t0).count();
  EXPECT_EQ(third.status, Status::BUSY) << third.message;
  EXPECT_LT(third_s, 0.5) << "BUSY must be answered at once";
  EXPECT_FALSE(client.getState().isDone()) << "the first request should still be running";
  // An action goal is rejected the same way.
  Client other("/planner/plan_anytime", true);
  ASSERT_TRUE(other.waitForServer(ros::Duration(5)));
  PlanAnytimeGoal room;
  room.start = kRoomStart;
  room.goal = kRoomGoal;
  other.sendGoal(room);
  ASSERT_TRUE(other.waitForResult(ros::Duration(5)));
  EXPECT_EQ(other.getState(), actionlib::SimpleClientGoalState::REJECTED);
  EXPECT_EQ(other.getResult()->status, PlanAnytimeResult::BUSY);

  ASSERT_TRUE(client.waitForResult(ros::Duration(30)));
  EXPECT_EQ(client.getResult()->status, PlanAnytimeResult::SUCCESS) << client.getResult()->message;
  const auto res = second.get();
  EXPECT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_GT(res.request_id, client.getResult()->request_id) << "served in arrival order";
  expectValidPath(res.path, kRoomStart, kRoomGoal, testMap());
}

// A map in another frame than the global one was used as if it were in it (issue 22, item 10).
// Now it is transformed with tf2 when a transform exists (planner_nodelet.test publishes
// map -> odom: (0.5, -0.5), yaw 0.3), and refused when none does.
TEST(PlannerNodelet, AMapInAnotherFrameIsTransformedOrRefused) {
  ASSERT_EQ(probeMap(), Status::INVALID_GOAL);
  auto nowhere = testMapWithExtraBlock();
  nowhere.header.frame_id = "nowhere";
  g_map_pub.publish(nowhere);
  ros::WallDuration(1.5).sleep();  // ~tf_timeout is 0.3 s
  EXPECT_EQ(probeMap(), Status::INVALID_GOAL) << "a map without a transform to 'map' was used";

  auto in_odom = testMap();
  in_odom.header.frame_id = "odom";
  g_map_pub.publish(in_odom);
  // A start on the odom map's left wall: outside the map as given (x < -1 in 'map'), in the
  // wall once the map is placed where 'odom' is.
  const auto on_wall = pose(-0.9, 8.0, 0.0, "odom");
  std::uint32_t status = Status::OUT_OF_MAP;
  for (int i = 0; i < 100 && status != Status::INVALID_START; ++i) {
    status = plan(on_wall, pose(9.0, 4.0, 0.0, "odom"), 1.0).status;
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_EQ(status, Status::INVALID_START) << "the map in 'odom' was not placed by its transform";
  // A path across the rooms in odom coordinates is collision-free on the map in its own frame.
  const auto res = plan(pose(0.0, 0.0, 0.0, "odom"), pose(9.0, 4.0, M_PI / 2, "odom"), 5.0);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_EQ(res.path.header.frame_id, "map");
  nav_msgs::Path in_odom_frame = res.path;
  const double c = std::cos(0.3), s = std::sin(0.3);
  for (auto& p : in_odom_frame.poses) {  // map -> odom: the inverse of the static transform
    const double x = p.pose.position.x - 0.5, y = p.pose.position.y + 0.5,
                 yaw = yawOf(p.pose) - 0.3;
    p.pose.position.x = c * x + s * y;
    p.pose.position.y = -s * x + c * y;
    p.pose.orientation.z = std::sin(yaw / 2);
    p.pose.orientation.w = std::cos(yaw / 2);
  }
  const auto& first = in_odom_frame.poses.front().pose.position;
  const auto& last = in_odom_frame.poses.back().pose.position;
  EXPECT_LE(std::hypot(first.x, first.y), kResolution);
  EXPECT_LE(std::hypot(last.x - 9.0, last.y - 4.0), kResolution);
  EXPECT_EQ(checkPathCollisionFree(in_odom_frame, testMap(), testFootprint(), kLethal), "");

  g_map_pub.publish(testMap());  // back to the map the other tests use
  ASSERT_TRUE(waitForProbe(Status::INVALID_GOAL, 30.0));
}

}  // namespace
}  // namespace test
}  // namespace amha_planner

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "planner_rostest");
  ros::NodeHandle nh;
  amha_planner::test::g_nh = &nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::Subscriber solutions =
      nh.subscribe("/planner/solutions", 1000, &amha_planner::test::onSolution);
  amha_planner::test::g_map_pub = nh.advertise<nav_msgs::OccupancyGrid>("/map", 1, true);
  amha_planner::test::g_map_updates_pub =
      nh.advertise<map_msgs::OccupancyGridUpdate>("/map_updates", 100);
  amha_planner::test::g_map_pub.publish(amha_planner::test::testMap());
  // Wait for the planner to adopt the map (the probe answers INVALID_GOAL once it has).
  if (!ros::service::waitForService("/planner/plan", ros::Duration(30)) ||
      !amha_planner::test::waitForProbe(amha_planner::Plan::Response::INVALID_GOAL, 60.0)) {
    ROS_FATAL("the planner did not come up with the test map");
    return 1;
  }
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}
