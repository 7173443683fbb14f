// Integration test of planner_node without a map (test/ros/planner_node_no_map.test): every
// interface answers NO_MAP, bad maps leave it without a map, and a good map makes it plan.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <actionlib/client/simple_action_client.h>
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/GetPlan.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "amha_planner/Plan.h"
#include "amha_planner/PlanAnytimeAction.h"
#include "amha_planner/ros/planner_params.h"
#include "rostest_support.h"

namespace amha_planner {
namespace test {
namespace {

using Client = actionlib::SimpleActionClient<PlanAnytimeAction>;
using Status = Plan::Response;
ros::Publisher g_map_pub;

const geometry_msgs::PoseStamped kStart = pose(0.0, 0.0, 0.0, "map");
const geometry_msgs::PoseStamped kGoal = pose(3.5, -1.0, 0.0, "map");

Plan::Response plan() {
  Plan srv;
  srv.request.start = kStart;
  srv.request.goal = kGoal;
  srv.request.time_budget = 5.0;
  EXPECT_TRUE(ros::service::call("/planner/plan", srv));
  return srv.response;
}

TEST(PlannerNodeWithoutMap, EveryInterfaceSaysNoMap) {
  ASSERT_TRUE(ros::service::waitForService("/planner/plan", ros::Duration(30)));
  const auto res = plan();
  EXPECT_EQ(res.status, Status::NO_MAP) << res.message;
  EXPECT_NE(res.message.find("no valid map"), std::string::npos) << res.message;
  EXPECT_TRUE(res.path.poses.empty());

  nav_msgs::GetPlan make_plan;
  make_plan.request.start = kStart;
  make_plan.request.goal = kGoal;
  ASSERT_TRUE(ros::service::call("/planner/make_plan", make_plan));
  EXPECT_TRUE(make_plan.response.plan.poses.empty());

  Client client("/planner/plan_anytime", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10)));
  PlanAnytimeGoal goal;
  goal.start = kStart;
  goal.goal = kGoal;
  client.sendGoal(goal);
  ASSERT_TRUE(client.waitForResult(ros::Duration(10)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::ABORTED);
  EXPECT_EQ(client.getResult()->status, PlanAnytimeResult::NO_MAP);
}

// A map the robot cannot use, or one in a frame without a transform to the global frame, is
// refused, and NO_MAP says why (issue 22, items 2 and 10).
TEST(PlannerNodeWithoutMap, NoMapSaysWhyTheLastMapWasRefused) {
  MapBuilder tiny(-0.15, -0.15, 0.05, 6, 6,
                  "map");  // 0.3 m square: the 0.36 m wide robot fits nowhere
  g_map_pub.publish(tiny.grid);
  Plan::Response res;
  for (int i = 0; i < 50 && res.message.find("wider than the map") == std::string::npos; ++i) {
    ros::WallDuration(0.1).sleep();
    res = plan();
  }
  EXPECT_EQ(res.status, Status::NO_MAP) << res.message;
  EXPECT_NE(res.message.find("is wider than the map (0.3 x 0.3 m)"), std::string::npos)
      << res.message;

  auto in_odom = testMap();
  in_odom.header.frame_id = "odom";  // this launch has no transforms at all
  g_map_pub.publish(in_odom);
  for (int i = 0; i < 50 && res.message.find("odom") == std::string::npos; ++i) {
    ros::WallDuration(0.1).sleep();
    res = plan();
  }
  EXPECT_EQ(res.status, Status::NO_MAP) << res.message;
  EXPECT_NE(res.message.find(
                "it is in frame 'odom', and there is no transform to the global frame 'map'"),
            std::string::npos)
      << res.message;
}

// Parameters outside their ranges stop the planner at start-up with a message naming them
// (issue 22, item 1: weights; item 2: robot_radius up to 100 m was accepted).
TEST(PlannerParams, ValuesOutsideTheirRangesAreRefused) {
  ros::NodeHandle pnh("/param_checks");
  const std::vector<std::pair<std::string, double>> bad = {{"w1", 1e15},
                                                           {"w1", 0.5},
                                                           {"w2", 1e308},
                                                           {"eps", 2e6},
                                                           {"dw1", -2.0},
                                                           {"dw2", 1e7},
                                                           {"eps_decrement", -0.5},
                                                           {"robot_radius", 50.0},
                                                           {"robot_radius", 100.0},
                                                           {"turning_radius", 0.0},
                                                           {"turning_radius", 1e3}};
  for (const auto& [name, value] : bad) {
    pnh.setParam(name, value);
    try {
      loadPlannerParams(pnh);
      ADD_FAILURE() << name << " = " << value << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("/param_checks/" + name), std::string::npos) << e.what();
    }
    pnh.deleteParam(name);
  }
  pnh.setParam("coarse_block", 2000);
  EXPECT_THROW(loadPlannerParams(pnh), std::invalid_argument);
  pnh.deleteParam("coarse_block");
  pnh.setParam("w1", 1e6);
  pnh.setParam("robot_radius", 10.0);
  pnh.setParam("dw1", -1.0);  // the algorithm's preset, as in dynamic_reconfigure
  EXPECT_NO_THROW(loadPlannerParams(pnh));
  pnh.deleteParam("w1");
  pnh.deleteParam("robot_radius");
  pnh.deleteParam("dw1");
}

TEST(PlannerNodeWithoutMap, BadMapsAreRefusedThenAGoodMapIsUsed) {
  std::vector<std::pair<std::string, nav_msgs::OccupancyGrid>> bad;
  auto m = testMap();
  m.data.resize(m.data.size() / 2);
  bad.emplace_back("data length != width x height", m);
  m = testMap();
  m.info.resolution = 0.0f;
  bad.emplace_back("zero resolution", m);
  m = testMap();
  m.info.resolution = -0.05f;
  bad.emplace_back("negative resolution", m);
  m = testMap();
  m.info.resolution = std::numeric_limits<float>::quiet_NaN();
  bad.emplace_back("NaN resolution", m);
  m = testMap();
  m.info.origin.orientation.w = 0.0;  // zero quaternion
  bad.emplace_back("zero origin quaternion", m);
  for (const auto& b : bad) {
    g_map_pub.publish(b.second);
    ros::WallDuration(0.5).sleep();
    const auto res = plan();
    EXPECT_EQ(res.status, Status::NO_MAP) << b.first << ": " << res.message;
  }
  // A partial update with no map to patch is ignored (and does not become a map).
  ros::NodeHandle nh;
  ros::Publisher updates = nh.advertise<map_msgs::OccupancyGridUpdate>("/map_updates", 1);
  ASSERT_TRUE(waitForSubscriber(updates, 5.0)) << "the node is not on /map_updates";
  map_msgs::OccupancyGridUpdate u;
  u.header.frame_id = "map";
  u.width = 2;
  u.height = 2;
  u.data.assign(4, 0);
  updates.publish(u);
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(plan().status, Status::NO_MAP) << "an update before any map was used";
  g_map_pub.publish(testMap());
  Plan::Response res;
  for (int i = 0; i < 200; ++i) {
    res = plan();
    if (res.status != Status::NO_MAP) break;
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_EQ(res.status, Status::SUCCESS) << res.message;
  EXPECT_EQ(checkPathCollisionFree(res.path, testMap(), testFootprint(), 65), "");
  // The footprint, given as a costmap_2d-style string, was parsed into the test's rectangle:
  // the start's outline on ~footprints has exactly its corners.
  const auto markers = ros::topic::waitForMessage<visualization_msgs::MarkerArray>(
      "/planner/footprints", ros::Duration(5));
  ASSERT_TRUE(markers);
  const visualization_msgs::Marker* outline = nullptr;
  for (const auto& m : markers->markers) {
    if (m.ns == "start_footprint") outline = &m;
  }
  ASSERT_NE(outline, nullptr);
  const auto corners = testFootprint();
  ASSERT_EQ(outline->points.size(), 2 * corners.size());  // one segment per side
  for (std::size_t i = 0; i < corners.size(); ++i) {
    EXPECT_NEAR(outline->points[2 * i].x, kStart.pose.position.x + corners[i][0], 1e-9);
    EXPECT_NEAR(outline->points[2 * i].y, kStart.pose.position.y + corners[i][1], 1e-9);
  }
}

}  // namespace
}  // namespace test
}  // namespace amha_planner

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "no_map_rostest");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  amha_planner::test::g_map_pub = nh.advertise<nav_msgs::OccupancyGrid>("/map", 1, true);
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}
