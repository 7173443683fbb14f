// Integration test of dynamic_reconfigure on amha_planner/PlannerNodelet
// (test/ros/reconfigure.test): parameters changed through ~set_parameters between requests take
// effect on the next request (search parameters at once, robot and map parameters by a rebuild the
// next request waits for), never on a request already planning; bad values are refused with a
// logged message and leave the parameters as they were.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include <actionlib/client/simple_action_client.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <nav_msgs/GetPlan.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>

#include "amha_planner/Plan.h"
#include "amha_planner/PlanAnytimeAction.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "rostest_support.h"

namespace amha_planner {
namespace test {
namespace {

using Client = actionlib::SimpleActionClient<PlanAnytimeAction>;
using Status = Plan::Response;
constexpr int kLethal = 65;  // the test config's lethal_threshold

ros::Publisher g_map_pub;
std::mutex g_log_mutex;
std::vector<std::string> g_errors;  // every ERROR on /rosout

void onLog(const rosgraph_msgs::Log::ConstPtr& m) {
  if (m->level < rosgraph_msgs::Log::ERROR) return;
  std::lock_guard<std::mutex> lock(g_log_mutex);
  g_errors.push_back(m->msg);
}

// Waits (up to 5 s) for an ERROR on /rosout that contains every one of `parts`.
bool errorLogged(const std::vector<std::string>& parts) {
  for (int i = 0; i < 500; ++i) {
    {
      std::lock_guard<std::mutex> lock(g_log_mutex);
      for (const std::string& e : g_errors) {
        bool all = true;
        for (const std::string& p : parts) all = all && e.find(p) != std::string::npos;
        if (all) return true;
      }
    }
    ros::WallDuration(0.01).sleep();
  }
  return false;
}

// A change for ~set_parameters.
struct Change {
  dynamic_reconfigure::Config config;
  Change& set(const std::string& name, double v) { return add(config.doubles, name, v); }
  Change& set(const std::string& name, int v) { return add(config.ints, name, v); }
  Change& set(const std::string& name, bool v) { return add(config.bools, name, v); }
  Change& set(const std::string& name, const char* v) {
    return add(config.strs, name, std::string(v));
  }

 private:
  template <class Parameter, class Value>
  Change& add(std::vector<Parameter>& list, const std::string& name, const Value& v) {
    Parameter p;
    p.name = name;
    p.value = v;
    list.push_back(p);
    return *this;
  }
};

// Applies a change; returns the configuration the server replied with (what is in force).
dynamic_reconfigure::Config apply(const Change& change) {
  dynamic_reconfigure::Reconfigure srv;
  srv.request.config = change.config;
  EXPECT_TRUE(ros::service::call("/planner/set_parameters", srv)) << "~set_parameters failed";
  return srv.response.config;
}

double doubleIn(const dynamic_reconfigure::Config& c, const std::string& name) {
  for (const auto& p : c.doubles) {
    if (p.name == name) return p.value;
  }
  ADD_FAILURE() << name << " is not in the reply";
  return NAN;
}
int intIn(const dynamic_reconfigure::Config& c, const std::string& name) {
  for (const auto& p : c.ints) {
    if (p.name == name) return p.value;
  }
  ADD_FAILURE() << name << " is not in the reply";
  return -1;
}
std::string strIn(const dynamic_reconfigure::Config& c, const std::string& name) {
  for (const auto& p : c.strs) {
    if (p.name == name) return p.value;
  }
  ADD_FAILURE() << name << " is not in the reply";
  return "";
}

Plan::Response plan(const geometry_msgs::PoseStamped& start, const geometry_msgs::PoseStamped& goal,
                    double budget = 5.0) {
  Plan srv;
  srv.request.start = start;
  srv.request.goal = goal;
  srv.request.time_budget = budget;
  EXPECT_TRUE(ros::service::call("/planner/plan", srv)) << "the ~plan service call failed";
  return srv.response;
}

// testMap() with a patch of occupancy 50 around (0, 0): free under lethal_threshold 65, an
// obstacle under 40, and costly to cross in between.
nav_msgs::OccupancyGrid softMap() {
  MapBuilder m(-1.0, -2.0, 0.05, 600, 400, "map");
  m.grid = testMap();
  m.fill(-0.5, -0.5, 0.5, 0.5, 50);
  return m.grid;
}

const geometry_msgs::PoseStamped kStart = pose(0.0, 0.0, 0.0, "map");  // in the soft patch
const geometry_msgs::PoseStamped kRoomGoal = pose(9.0, 4.0, M_PI / 2, "map");
const geometry_msgs::PoseStamped kMazeGoal = pose(27.5, 16.5, 0.0, "map");

TEST(Reconfigure, SearchParametersApplyToTheNextRequest) {
  // The loaded configuration: A-MHA* with the lattice's preset weights (w1 = 1.03, w2 = 5).
  const amha::PlannerConfig preset =
      amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar);
  auto res = plan(kStart, kRoomGoal);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  ASSERT_FALSE(res.solutions.empty());
  EXPECT_DOUBLE_EQ(res.solutions.front().w1, preset.w1);
  EXPECT_DOUBLE_EQ(res.solutions.front().bound, preset.w1 * preset.w2);

  // What is in force is what the ~parameters said (the footprint in costmap_2d's string form,
  // unset weights as -1, the algorithm's preset), not the .cfg's defaults.
  auto in_force = apply(Change());
  EXPECT_EQ(strIn(in_force, "footprint"),
            "[[0.25, 0.18], [0.25, -0.18], [-0.25, -0.18], [-0.25, 0.18]]");
  EXPECT_DOUBLE_EQ(doubleIn(in_force, "w1"), -1.0);
  EXPECT_DOUBLE_EQ(doubleIn(in_force, "default_time_budget"), 2.0);
  EXPECT_EQ(intIn(in_force, "num_headings"), 16);

  in_force = apply(Change().set("algorithm", "astar"));
  EXPECT_EQ(strIn(in_force, "algorithm"), "astar");
  res = plan(kStart, kRoomGoal);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  ASSERT_EQ(res.solutions.size(), 1u) << "A* finds one solution";
  EXPECT_DOUBLE_EQ(res.bound, 1.0);
  const double optimal = res.cost;

  in_force = apply(Change().set("algorithm", "amha").set("w1", 3.0).set("w2", 2.0));
  EXPECT_DOUBLE_EQ(doubleIn(in_force, "w1"), 3.0);
  res = plan(kStart, kRoomGoal);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_DOUBLE_EQ(res.solutions.front().w1, 3.0);
  EXPECT_DOUBLE_EQ(res.solutions.front().w2, 2.0);
  EXPECT_DOUBLE_EQ(res.solutions.front().bound, 6.0);
  EXPECT_NEAR(res.cost, optimal, 1e-9) << "it ends at the optimum, as A* did";

  // A tiny default budget: a request without its own budget runs out of time.
  apply(Change().set("default_time_budget", 1e-3).set("algorithm", "astar"));
  res = plan(kStart, kMazeGoal, 0.0);
  EXPECT_EQ(res.status, Status::TIME_EXHAUSTED) << res.message;
  EXPECT_NE(res.message.find("time budget of 0.00 s"), std::string::npos) << res.message;

  // ~start_tolerance: ~make_plan (which cannot ask for one) leaves a start in collision.
  nav_msgs::GetPlan mp;
  mp.request.start = pose(1.9, 4.0, M_PI, "map");  // its rear in the block
  mp.request.goal = kRoomGoal;
  apply(Change().set("default_time_budget", 5.0));
  ASSERT_TRUE(ros::service::call("/planner/make_plan", mp));
  EXPECT_TRUE(mp.response.plan.poses.empty()) << "refused without a start tolerance";
  apply(Change().set("start_tolerance", 0.5));
  ASSERT_TRUE(ros::service::call("/planner/make_plan", mp));
  EXPECT_FALSE(mp.response.plan.poses.empty()) << "left with one";
  apply(
      Change().set("start_tolerance", 0.0).set("algorithm", "amha").set("w1", 5.0).set("w2", 5.0));
}

TEST(Reconfigure, BadValuesAreRefusedWithAMessage) {
  const auto before = apply(Change());
  struct Case {
    const char* what;
    Change change;
    std::vector<std::string> logged;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Case> cases = {
      {"a weight below 1", Change().set("w1", 0.5), {"refused", "/planner/w1", "neither -1"}},
      {"a NaN budget",
       Change().set("default_time_budget", nan),
       {"refused", "default_time_budget", "expected a number"}},
      {"an unknown algorithm",
       Change().set("algorithm", "dijkstra"),
       {"refused", "unknown algorithm 'dijkstra'"}},
      {"an unknown motion model",
       Change().set("motion_model", "tank"),
       {"refused", "motion_model", "unknown motion model 'tank'"}},
      {"headings not a multiple of 8",
       Change().set("num_headings", 12),
       {"refused", "num_headings", "multiple of 8"}},
      {"a two-point footprint",
       Change().set("footprint", "[[0, 0], [1, 1]]"),
       {"refused", "footprint", "at least 3"}},
      {"a malformed footprint",
       Change().set("footprint", "[[0, 0], [1, 1]"),
       {"refused", "footprint", "unbalanced"}},
      {"a flat footprint",
       Change().set("footprint", "[[0, 0], [1, 0], [2, 0]]"),
       {"refused", "area"}},
      {"a missing primitive file",
       Change().set("mprim_file", "/nonexistent/x.mprim"),
       {"refused", "x.mprim"}},
      // The test map is 30 x 20 m.
      {"a robot wider than the map",
       Change().set("footprint", "[[12, 12], [12, -12], [-12, -12], [-12, 12]]"),
       {"refused", "footprint", "wider than the map"}},
      {"a bad value among good ones", Change().set("w2", 3.0).set("eps", 0.9), {"refused", "eps"}},
  };
  for (const Case& c : cases) {
    const auto after = apply(c.change);
    EXPECT_EQ(after.doubles.size(), before.doubles.size()) << c.what;
    for (std::size_t i = 0; i < before.doubles.size() && i < after.doubles.size(); ++i) {
      EXPECT_DOUBLE_EQ(after.doubles[i].value, before.doubles[i].value)
          << c.what << ": " << before.doubles[i].name;
    }
    for (std::size_t i = 0; i < before.strs.size() && i < after.strs.size(); ++i) {
      EXPECT_EQ(after.strs[i].value, before.strs[i].value) << c.what << ": " << before.strs[i].name;
    }
    EXPECT_EQ(intIn(after, "num_headings"), intIn(before, "num_headings")) << c.what;
    EXPECT_TRUE(errorLogged(c.logged)) << c.what << ": no ERROR on /rosout with the reason";
  }
  // Planning goes on with the parameters in force (A-MHA*, w2 still 5).
  const auto res = plan(kStart, kRoomGoal);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_DOUBLE_EQ(res.solutions.front().w2, 5.0);
}

TEST(Reconfigure, RobotAndMapParametersRebuildForTheNextRequest) {
  // Each answer comes right after the reconfigure reply: the request waits for the rebuild.
  auto res = plan(kStart, kRoomGoal);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  const double cost_before = res.cost;
  // The soft patch becomes an obstacle: the start is in it.
  apply(Change().set("lethal_threshold", 40));
  res = plan(kStart, kRoomGoal);
  EXPECT_EQ(res.status, Status::INVALID_START) << res.message;
  apply(Change().set("lethal_threshold", kLethal));
  res = plan(kStart, kRoomGoal);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_DOUBLE_EQ(res.cost, cost_before);
  // Crossing the patch costs more.
  apply(Change().set("cost_penalty", 10.0).set("algorithm", "astar"));
  res = plan(kStart, kRoomGoal);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_GT(res.cost, cost_before + 0.1);
  apply(Change().set("cost_penalty", 1.0).set("algorithm", "amha"));
  // A square robot 1.52 m wide fits neither door between the rooms (1.2 m and 1.5 m).
  apply(Change().set("footprint", "[[0.76, 0.76], [0.76, -0.76], [-0.76, -0.76], [-0.76, 0.76]]"));
  res = plan(kStart, kRoomGoal);
  EXPECT_EQ(res.status, Status::NO_PATH_FOUND) << res.message;
  // Primitives: 8 headings instead of 16. A goal facing atan(1/2), one of the 16 headings (the
  // directions of small lattice vectors), is reached at it with 16, at a multiple of 45 degrees
  // with 8.
  apply(Change().set("footprint", "[[0.25, 0.18], [0.25, -0.18], [-0.25, -0.18], [-0.25, 0.18]]"));
  const auto oblique = pose(3.0, -1.0, std::atan(0.5), "map");
  res = plan(kStart, oblique);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_NEAR(yawOf(res.path.poses.back().pose), std::atan(0.5), 1e-6);
  apply(Change().set("num_headings", 8));
  res = plan(kStart, oblique);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  const double eighths = yawOf(res.path.poses.back().pose) / (M_PI / 4);
  EXPECT_NEAR(eighths, std::round(eighths), 1e-6) << "a heading of the 8";
  apply(Change().set("num_headings", 16));
  // The motion model: a diff-drive robot turns around on the spot, an Ackermann one (which
  // never turns in place) must drive a loop.
  const auto facing_up = pose(8.0, 4.0, M_PI / 2, "map"),
             facing_down = pose(8.0, 4.0, -M_PI / 2, "map");
  auto farthest = [](const nav_msgs::Path& path) {  // from where it starts
    double d = 0.0;
    for (const auto& p : path.poses) {
      d = std::max(d, std::hypot(p.pose.position.x - path.poses[0].pose.position.x,
                                 p.pose.position.y - path.poses[0].pose.position.y));
    }
    return d;
  };
  res = plan(facing_up, facing_down);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  ASSERT_FALSE(res.path.poses.empty());
  EXPECT_LT(farthest(res.path), 0.01) << "a diff-drive robot turns on the spot";
  apply(Change().set("motion_model", "ackermann"));
  res = plan(facing_up, facing_down);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  ASSERT_FALSE(res.path.poses.empty());
  EXPECT_GT(farthest(res.path), 0.4) << "an Ackermann robot drives a loop";
  EXPECT_EQ(checkPathCollisionFree(res.path, softMap(), testFootprint(), kLethal), "");
  apply(Change().set("motion_model", "diff"));
  res = plan(kStart, kRoomGoal);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_DOUBLE_EQ(res.cost, cost_before) << "the original configuration again";
  EXPECT_EQ(checkPathCollisionFree(res.path, softMap(), testFootprint(), kLethal), "");
}

TEST(Reconfigure, AChangeNeverTouchesARunningRequest) {
  std::atomic<int> feedback{0};  // before the client, whose destructor stops its callbacks
  Client client("/planner/plan_anytime", true);
  // A-MHA*'s second solution is the optimum, proven (certified schedule): 2-3 s on this maze
  // on a loaded 2-core machine, hence a budget with room to spare.
  ASSERT_TRUE(sendAndAwaitFeedback(client, kStart, kMazeGoal, 10.0, feedback));
  ASSERT_FALSE(client.getState().isDone()) << "the maze plan should still be running";
  // Mid-request: another algorithm, and the start made an obstacle (a rebuild).
  apply(Change().set("algorithm", "astar").set("lethal_threshold", 40));
  ASSERT_TRUE(client.waitForResult(ros::Duration(30)));
  const auto result = client.getResult();
  ASSERT_EQ(result->status, PlanAnytimeResult::SUCCESS) << result->message;
  ASSERT_GT(result->solutions.size(), 1u) << "A-MHA*'s improvements, not A*'s single solution";
  EXPECT_DOUBLE_EQ(result->solutions.front().w1, 5.0);
  EXPECT_EQ(checkPathCollisionFree(result->path, softMap(), testFootprint(), kLethal), "")
      << "planned on the map as the running request read it";
  // The next request has both changes.
  EXPECT_EQ(plan(kStart, kRoomGoal).status, Status::INVALID_START);
  apply(Change().set("lethal_threshold", kLethal));
  const auto res = plan(kStart, kRoomGoal);
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_EQ(res.solutions.size(), 1u) << "A* now";
  apply(Change().set("algorithm", "amha"));
}

}  // namespace
}  // namespace test
}  // namespace amha_planner

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "reconfigure_rostest");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::Subscriber log = nh.subscribe("/rosout", 1000, &amha_planner::test::onLog);
  amha_planner::test::g_map_pub = nh.advertise<nav_msgs::OccupancyGrid>("/map", 1, true);
  amha_planner::test::g_map_pub.publish(amha_planner::test::softMap());
  // Wait for the planner to have the map: the start plans.
  bool ready = ros::service::waitForService("/planner/set_parameters", ros::Duration(30));
  for (int i = 0; ready && i < 600; ++i) {
    amha_planner::Plan srv;
    srv.request.start = amha_planner::test::kStart;
    srv.request.goal = amha_planner::test::pose(1.0, 0.0, 0.0, "map");
    srv.request.time_budget = 2.0;
    if (ros::service::call("/planner/plan", srv) &&
        srv.response.status == amha_planner::Plan::Response::SUCCESS)
      break;
    ros::WallDuration(0.1).sleep();
    ready = i + 1 < 600;
  }
  if (!ready) {
    ROS_FATAL("the planner did not come up with the test map");
    return 1;
  }
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}
