// Integration tests of ~plan_anytime's results (test/ros/planner_action_results.test): every
// terminal result carries an honest status, also for goals whose cancel overtook them, which
// actionlib answers by itself (issue 22, item 6: they read SUCCESS, status 0), and a goal
// cancelled while it waits in the queue or for a transform is answered at once, not after the
// request before it or the transform's timeout (item 9).
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <string>

#include <actionlib/client/simple_action_client.h>
#include <actionlib_msgs/GoalID.h>
#include <ros/ros.h>

#include "amha_planner/PlanAnytimeAction.h"
#include "rostest_support.h"

namespace amha_planner {
namespace test {
namespace {

using Client = actionlib::SimpleActionClient<PlanAnytimeAction>;
using State = actionlib::SimpleClientGoalState;
using Clock = std::chrono::steady_clock;
using actionlib_msgs::GoalStatus;

const geometry_msgs::PoseStamped kRoomStart = pose(0.0, 0.0, 0.0, "map");
const geometry_msgs::PoseStamped kRoomGoal = pose(9.0, 4.0, M_PI / 2, "map");
const geometry_msgs::PoseStamped kMazeGoal = pose(27.5, 16.5, 0.0, "map");

PlanAnytimeGoal goalTo(const geometry_msgs::PoseStamped& to, double budget) {
  PlanAnytimeGoal g;
  g.start = kRoomStart;
  g.goal = to;
  g.time_budget = budget;
  return g;
}

// The action's topics, spoken to directly: a cancel can then be made to arrive first.
struct RawActionTopics {
  ros::Publisher goal_pub, cancel_pub;
  ros::Subscriber result_sub;
  std::mutex mutex;
  std::condition_variable arrived;
  std::map<std::string, PlanAnytimeActionResult> results;  // by goal id

  explicit RawActionTopics(ros::NodeHandle& nh) {
    goal_pub = nh.advertise<PlanAnytimeActionGoal>("/planner/plan_anytime/goal", 10);
    cancel_pub = nh.advertise<actionlib_msgs::GoalID>("/planner/plan_anytime/cancel", 10);
    result_sub = nh.subscribe<PlanAnytimeActionResult>(
        "/planner/plan_anytime/result", 100, [this](const PlanAnytimeActionResultConstPtr& r) {
          std::lock_guard<std::mutex> lock(mutex);
          results[r->status.goal_id.id] = *r;
          arrived.notify_all();
        });
  }
  bool connected(double seconds) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < deadline) {
      if (goal_pub.getNumSubscribers() > 0 && cancel_pub.getNumSubscribers() > 0 &&
          result_sub.getNumPublishers() > 0) {
        return true;
      }
      ros::WallDuration(0.05).sleep();
    }
    return false;
  }
  void sendGoal(const std::string& id, const ros::Time& stamp) {
    PlanAnytimeActionGoal g;
    g.header.stamp = ros::Time::now();
    g.goal_id.id = id;
    g.goal_id.stamp = stamp;
    g.goal = goalTo(kRoomGoal, 2.0);
    goal_pub.publish(g);
  }
  bool waitResult(const std::string& id, PlanAnytimeActionResult* out) {
    std::unique_lock<std::mutex> lock(mutex);
    if (!arrived.wait_for(lock, std::chrono::seconds(10), [&] { return results.count(id) > 0; }))
      return false;
    *out = results[id];
    return true;
  }
};

// Sends `goal`, waits `delay` seconds, runs `before_cancel`, cancels the goal and returns the
// seconds from the cancel to its result callback (-1 if none came within 5 s).
double cancelLatency(Client& client, const PlanAnytimeGoal& goal, double delay,
                     const std::function<void()>& before_cancel = {}) {
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  Clock::time_point done_at;
  client.sendGoal(goal, [&](const State&, const PlanAnytimeResultConstPtr&) {
    std::lock_guard<std::mutex> lock(m);
    done = true;
    done_at = Clock::now();
    cv.notify_all();
  });
  ros::WallDuration(delay).sleep();
  if (before_cancel) before_cancel();
  const auto cancelled_at = Clock::now();
  client.cancelGoal();
  std::unique_lock<std::mutex> lock(m);
  if (!cv.wait_for(lock, std::chrono::seconds(5), [&] { return done; })) return -1.0;
  return std::chrono::duration<double>(done_at - cancelled_at).count();
}

TEST(PlanAnytimeResults, AGoalWhoseCancelCameFirstIsCancelledNotSuccessful) {
  ros::NodeHandle nh;
  RawActionTopics topics(nh);
  ASSERT_TRUE(topics.connected(10.0)) << "no connection to the action's topics";
  // The cancel of a goal id the server has not seen: actionlib keeps it, and answers the goal
  // RECALLED itself when it comes, without calling the planner.
  actionlib_msgs::GoalID cancel;
  cancel.id = "cancelled-before-sent";
  topics.cancel_pub.publish(cancel);
  ros::WallDuration(0.5).sleep();  // the cancel must get there first: separate connections
  topics.sendGoal(cancel.id, ros::Time::now());
  PlanAnytimeActionResult r;
  ASSERT_TRUE(topics.waitResult(cancel.id, &r));
  EXPECT_EQ(r.status.status, GoalStatus::RECALLED);
  EXPECT_EQ(r.result.status, PlanAnytimeResult::CANCELLED)
      << "status " << r.result.status << ": " << r.result.message;
  EXPECT_NE(r.result.message.find("before the planner received the goal"), std::string::npos)
      << r.result.message;
  EXPECT_TRUE(r.result.path.poses.empty());

  // A goal stamped before a cancel-everything-before stamp: actionlib cancels it on arrival.
  actionlib_msgs::GoalID before;
  before.stamp = ros::Time::now();
  topics.cancel_pub.publish(before);
  ros::WallDuration(0.5).sleep();
  topics.sendGoal("stamped-before-the-cancel", before.stamp - ros::Duration(1.0));
  ASSERT_TRUE(topics.waitResult("stamped-before-the-cancel", &r));
  EXPECT_EQ(r.status.status, GoalStatus::RECALLED);
  EXPECT_EQ(r.result.status, PlanAnytimeResult::CANCELLED) << r.result.message;

  // A goal sent normally after them still plans.
  ros::WallDuration(0.1).sleep();  // stamped after the cancel above
  topics.sendGoal("after-the-cancels", ros::Time::now());
  ASSERT_TRUE(topics.waitResult("after-the-cancels", &r));
  EXPECT_EQ(r.status.status, GoalStatus::SUCCEEDED);
  EXPECT_EQ(r.result.status, PlanAnytimeResult::SUCCESS) << r.result.message;
  EXPECT_FALSE(r.result.path.poses.empty());
}

// The soak test's finding: 3 of 150 goals cancelled right after send_goal ended RECALLED with
// status 0 (SUCCESS) and an empty path. Here each goal's cancel is sent right after it, on the
// action's own topics (actionlib's clients give such goals up as LOST when the cancel overtakes
// the goal, so they never see their results), and every result the server sends must go with
// its terminal state.
TEST(PlanAnytimeResults, CancelledRightAfterSendingEveryResultIsHonest) {
  ros::NodeHandle nh;
  RawActionTopics topics(nh);
  ASSERT_TRUE(topics.connected(10.0)) << "no connection to the action's topics";
  std::map<std::string, int> seen;
  for (int i = 0; i < 150; ++i) {
    const std::string id = "burst-" + std::to_string(i);
    topics.sendGoal(id, ros::Time::now());
    actionlib_msgs::GoalID cancel;
    cancel.id = id;
    topics.cancel_pub.publish(cancel);
    PlanAnytimeActionResult r;
    ASSERT_TRUE(topics.waitResult(id, &r)) << id << ": no result within 10 s";
    const auto& res = r.result;
    const std::uint8_t state = r.status.status;
    const bool recalled_by_actionlib = state == GoalStatus::RECALLED && res.request_id == 0;
    ++seen[std::to_string(state) + (recalled_by_actionlib ? " (actionlib)" : "")];
    switch (state) {
      case GoalStatus::SUCCEEDED:
        EXPECT_EQ(res.status, PlanAnytimeResult::SUCCESS) << id;
        EXPECT_FALSE(res.path.poses.empty()) << id;
        break;
      case GoalStatus::PREEMPTED:
      case GoalStatus::RECALLED:
        EXPECT_EQ(res.status, PlanAnytimeResult::CANCELLED) << id << ": " << res.message;
        break;
      case GoalStatus::REJECTED:
        EXPECT_EQ(res.status, PlanAnytimeResult::BUSY) << id;
        break;
      case GoalStatus::ABORTED:
        EXPECT_NE(res.status, PlanAnytimeResult::SUCCESS) << id;
        break;
      default:
        ADD_FAILURE() << id << ": not a terminal state: " << int(state);
    }
    if (res.status != PlanAnytimeResult::SUCCESS) {
      EXPECT_FALSE(res.message.empty()) << id;
      EXPECT_TRUE(res.path.poses.empty() || res.status == PlanAnytimeResult::CANCELLED) << id;
    }
  }
  std::string counts;
  for (const auto& [state, n] : seen) counts += " state " + state + ": " + std::to_string(n) + ";";
  std::printf("[ INFO     ] 150 goals cancelled right after sending:%s\n", counts.c_str());
}

// A goal waiting behind a running one (~max_queued_requests is 1 here) that is cancelled is
// answered at once, not when the running one ends (which may take its whole budget).
TEST(PlanAnytimeResults, AGoalCancelledWhileItWaitsIsAnsweredAtOnce) {
  Client running("/planner/plan_anytime", true), waiting("/planner/plan_anytime", true);
  ASSERT_TRUE(running.waitForServer(ros::Duration(10)) && waiting.waitForServer(ros::Duration(10)));
  PlanAnytimeGoal astar = goalTo(kMazeGoal, 30.0);
  astar.algorithm = "astar";  // one long search without feedback
  running.sendGoal(astar);
  ros::WallDuration(0.5).sleep();
  ASSERT_FALSE(running.getState().isDone()) << running.getState().toString();
  const double latency = cancelLatency(waiting, goalTo(kRoomGoal, 5.0), 0.3, [&] {
    ASSERT_FALSE(waiting.getState().isDone()) << waiting.getState().toString();
  });
  ASSERT_GE(latency, 0.0) << "no result within 5 s of the cancel";
  std::printf("[ INFO     ] a waiting goal's cancel -> result: %.1f ms\n", latency * 1e3);
  EXPECT_LT(latency, 0.050);
  EXPECT_EQ(waiting.getState(), State::PREEMPTED);
  EXPECT_EQ(waiting.getResult()->status, PlanAnytimeResult::CANCELLED);
  EXPECT_NE(waiting.getResult()->message.find("waiting in the queue"), std::string::npos)
      << waiting.getResult()->message;
  EXPECT_GT(waiting.getResult()->request_id, 0u);
  EXPECT_FALSE(running.getState().isDone()) << "the running goal went on";
  running.cancelGoal();
  ASSERT_TRUE(running.waitForResult(ros::Duration(5)));
  EXPECT_EQ(running.getResult()->status, PlanAnytimeResult::CANCELLED);
}

// A request waiting for a transform (here of a frame nobody publishes, for up to ~tf_timeout,
// 0.3 s) stops at its cancel: the soak test's slowest cancels were such waits (0.5 s).
TEST(PlanAnytimeResults, AGoalWaitingForATransformIsCancelledAtOnce) {
  Client client("/planner/plan_anytime", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(10)));
  PlanAnytimeGoal g = goalTo(kRoomGoal, 5.0);
  g.start.header.frame_id = "nowhere";
  const double latency = cancelLatency(client, g, 0.1);
  ASSERT_GE(latency, 0.0) << "no result within 5 s of the cancel";
  std::printf("[ INFO     ] cancel during a transform wait -> result: %.1f ms\n", latency * 1e3);
  EXPECT_LT(latency, 0.050);
  EXPECT_EQ(client.getResult()->status, PlanAnytimeResult::CANCELLED)
      << client.getResult()->message;
  EXPECT_NE(client.getResult()->message.find("waiting for a transform"), std::string::npos)
      << client.getResult()->message;
}

}  // namespace
}  // namespace test
}  // namespace amha_planner

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "action_results_rostest");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::Publisher map_pub = nh.advertise<nav_msgs::OccupancyGrid>("/map", 1, true);
  map_pub.publish(amha_planner::test::testMap());
  // The planner is ready once a valid request plans.
  ros::service::waitForService("/planner/plan", ros::Duration(30));
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}
