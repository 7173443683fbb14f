// demo_client: asks the planner's ~plan_anytime action for a path between two places, prints
// every improved solution as it streams in (elapsed, cost, bounds), then draws the map with
// every improved path into a PNG and exits (0 on SUCCESS).
// Parameters: ~start and ~goal ([x, y, yaw] in the map frame), ~time_budget (s), ~algorithm
// (""), ~output_image (PNG path, "" for none), ~frame_id ("map"), ~wait (s to wait for the
// map and the server). The action is "plan_anytime" (remap it to the planner's).
// With ~robot_tf (default true) the client also stands in for the robot: it publishes the
// static transform frame_id -> ~robot_frame ("base_link") at ~start and asks for a plan from
// "wherever the robot is" (an empty start frame), so the planner takes the start from tf2.
#include <cmath>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include <actionlib/client/simple_action_client.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <opencv2/imgproc.hpp>

#include "amha_planner/PlanAnytimeAction.h"
#include "amha_planner/lattice/image_file.h"
#include "amha_planner/ros/conversions.h"

namespace {

using Client = actionlib::SimpleActionClient<amha_planner::PlanAnytimeAction>;

bool readPose(const ros::NodeHandle& pnh, const std::string& name, geometry_msgs::PoseStamped* out,
              const std::string& frame) {
  std::vector<double> v;
  if (!pnh.getParam(name, v) || v.size() != 3) {
    ROS_FATAL("demo_client: set ~%s to [x, y, yaw]", name.c_str());
    return false;
  }
  out->header.frame_id = frame;
  out->pose.position.x = v[0];
  out->pose.position.y = v[1];
  out->pose.orientation = amha_planner::quaternionFromYaw(v[2]);
  return true;
}

// Map (metres) -> image pixel, for a map drawn `scale` pixels per cell, row 0 at the top.
struct Projector {
  const nav_msgs::OccupancyGrid* map;
  int scale;
  cv::Point operator()(double x, double y) const {
    const auto& o = map->info.origin;
    const double yaw = amha_planner::pose2DFromPose(o).theta;
    const double dx = x - o.position.x, dy = y - o.position.y;
    const double cx = (std::cos(yaw) * dx + std::sin(yaw) * dy) / map->info.resolution;
    const double cy = (-std::sin(yaw) * dx + std::cos(yaw) * dy) / map->info.resolution;
    return {static_cast<int>(std::lround(cx * scale)),
            static_cast<int>(std::lround((map->info.height - cy) * scale))};
  }
};

void drawPicture(const nav_msgs::OccupancyGrid& map,
                 const std::vector<amha_planner::PlanSolution>& solutions,
                 const geometry_msgs::PoseStamped& start, const geometry_msgs::PoseStamped& goal,
                 const std::string& caption, const std::string& path) {
  const int w = static_cast<int>(map.info.width), h = static_cast<int>(map.info.height);
  const int scale = std::max(1, std::min(4, 1400 / std::max(w, h)));
  cv::Mat cells(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int v = map.data[static_cast<std::size_t>(y) * w + x];
      const cv::Vec3b c = v < 0     ? cv::Vec3b(205, 205, 205)
                          : v >= 65 ? cv::Vec3b(0, 0, 0)
                                    : cv::Vec3b(255, 255, 255);
      cells.at<cv::Vec3b>(h - 1 - y, x) = c;
    }
  }
  cv::Mat image;
  cv::resize(cells, image, cv::Size(w * scale, h * scale), 0, 0, cv::INTER_NEAREST);
  const Projector to_px{&map, scale};
  // A solution that only tightens the bound repeats the previous path: draw each path once,
  // early ones warm (orange), later ones cool (blue), the final one thickest.
  std::vector<const amha_planner::PlanSolution*> distinct;
  for (const auto& s : solutions) {
    if (distinct.empty() || s.cost < distinct.back()->cost) distinct.push_back(&s);
  }
  const cv::Point legend(12, image.rows - 14 - 22 * static_cast<int>(distinct.size()));
  for (std::size_t i = 0; i < distinct.size(); ++i) {
    const double t = distinct.size() > 1 ? double(i) / double(distinct.size() - 1) : 1.0;
    const cv::Scalar color(255 * t, 140 * (1 - t) + 60 * t, 255 * (1 - t));  // BGR
    const bool last = i + 1 == distinct.size();
    std::vector<cv::Point> pts;
    for (const auto& p : distinct[i]->path.poses) {
      pts.push_back(to_px(p.pose.position.x, p.pose.position.y));
    }
    cv::polylines(image, pts, false, color, last ? 4 : 2, cv::LINE_AA);
    char text[160];
    std::snprintf(text, sizeof text, "%.3f s: cost %.2f m, bound %.2f, certified %.2f",
                  distinct[i]->elapsed, distinct[i]->cost, distinct[i]->bound,
                  distinct[i]->certified_bound);
    const cv::Point at = legend + cv::Point(0, 22 * static_cast<int>(i + 1));
    cv::line(image, at + cv::Point(0, -6), at + cv::Point(30, -6), color, 4);
    cv::putText(image, text, at + cv::Point(40, 0), cv::FONT_HERSHEY_SIMPLEX, 0.55, {0, 0, 0}, 1,
                cv::LINE_AA);
  }
  cv::circle(image, to_px(start.pose.position.x, start.pose.position.y), 4 * scale, {0, 170, 0},
             -1);
  cv::circle(image, to_px(goal.pose.position.x, goal.pose.position.y), 4 * scale, {0, 0, 220}, -1);
  cv::putText(image, caption, {12, 28}, cv::FONT_HERSHEY_SIMPLEX, 0.7, {0, 0, 0}, 2, cv::LINE_AA);
  cv::putText(image, "start green, goal red; each improved path, early orange .. final blue",
              {12, 56}, cv::FONT_HERSHEY_SIMPLEX, 0.55, {60, 60, 60}, 1, cv::LINE_AA);
  try {
    amha::lattice::writeImageFile(path, image);  // the codecs module, loaded on first use
  } catch (const std::exception& e) {
    ROS_ERROR("demo_client: could not write %s: %s", path.c_str(), e.what());
    return;
  }
  std::printf("demo: picture of the map with %zu distinct improved path(s) saved to %s\n",
              distinct.size(), path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "demo_client");
  ros::NodeHandle nh, pnh("~");
  std::string frame, output_image, algorithm, robot_frame;
  double time_budget = 10.0, wait = 60.0;
  bool robot_tf = true;
  pnh.param<std::string>("frame_id", frame, "map");
  pnh.param<std::string>("robot_frame", robot_frame, "base_link");
  pnh.param("robot_tf", robot_tf, robot_tf);
  pnh.param<std::string>("output_image", output_image, "");
  pnh.param<std::string>("algorithm", algorithm, "");
  pnh.param("time_budget", time_budget, time_budget);
  pnh.param("wait", wait, wait);
  amha_planner::PlanAnytimeGoal goal;
  if (!readPose(pnh, "start", &goal.start, frame) || !readPose(pnh, "goal", &goal.goal, frame)) {
    return 2;
  }
  goal.time_budget = time_budget;
  goal.algorithm = algorithm;
  const geometry_msgs::PoseStamped start = goal.start;
  tf2_ros::StaticTransformBroadcaster robot_broadcaster;
  if (robot_tf) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time::now();
    t.header.frame_id = frame;
    t.child_frame_id = robot_frame;
    t.transform.translation.x = start.pose.position.x;
    t.transform.translation.y = start.pose.position.y;
    t.transform.rotation = start.pose.orientation;
    robot_broadcaster.sendTransform(t);
    goal.start = geometry_msgs::PoseStamped();  // empty frame: the robot's pose from tf2
  }

  ros::AsyncSpinner spinner(2);
  spinner.start();
  std::mutex map_mutex;
  nav_msgs::OccupancyGrid::ConstPtr map;
  ros::Subscriber map_sub = nh.subscribe<nav_msgs::OccupancyGrid>(
      "map", 1, [&](const nav_msgs::OccupancyGrid::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(map_mutex);
        map = m;
      });

  Client client(nh, "plan_anytime", /*spin_thread=*/false);
  if (!client.waitForServer(ros::Duration(wait))) {
    ROS_FATAL("demo_client: no plan_anytime server after %.0f s", wait);
    return 1;
  }
  // The planner needs the map before a request makes sense; wait for it like the planner does.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(wait);
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(map_mutex);
      if (map) break;
    }
    if (ros::WallTime::now() > deadline || !ros::ok()) {
      ROS_FATAL("demo_client: no map on %s after %.0f s", map_sub.getTopic().c_str(), wait);
      return 1;
    }
    ros::WallDuration(0.05).sleep();
  }
  ros::WallDuration(0.5).sleep();  // let the planner build its lattice for the latched map

  std::printf("demo: planning from %s(%.2f, %.2f) to (%.2f, %.2f) in '%s', budget %.1f s\n",
              robot_tf ? "the robot's pose on tf, " : "", start.pose.position.x,
              start.pose.position.y, goal.goal.pose.position.x, goal.goal.pose.position.y,
              frame.c_str(), time_budget);
  std::printf("demo: %4s %10s %12s %9s %10s %7s %7s %12s\n", "#", "elapsed s", "cost m", "bound",
              "certified", "w1", "w2", "expansions");
  std::fflush(stdout);
  int improvements = 0;
  for (int attempt = 0;; ++attempt) {
    improvements = 0;
    client.sendGoal(goal, Client::SimpleDoneCallback(), Client::SimpleActiveCallback(),
                    [&](const amha_planner::PlanAnytimeFeedbackConstPtr& f) {
                      const auto& s = f->solution;
                      std::printf("demo: %4d %10.3f %12.3f %9.3f %10.3f %7.2f %7.2f %12llu\n",
                                  ++improvements, s.elapsed, s.cost, s.bound, s.certified_bound,
                                  s.w1, s.w2, static_cast<unsigned long long>(s.expansions));
                      std::fflush(stdout);
                    });
    if (!client.waitForResult(ros::Duration(time_budget + wait))) {
      ROS_FATAL("demo_client: no result within %.0f s", time_budget + wait);
      client.cancelGoal();
      return 1;
    }
    const auto result = client.getResult();
    // The planner may still be building the lattice of the map we saw: try again shortly.
    if (result->status == amha_planner::PlanAnytimeResult::NO_MAP && attempt < 100) {
      ros::WallDuration(0.2).sleep();
      continue;
    }
    break;
  }
  const auto result = client.getResult();
  const bool ok = result->status == amha_planner::PlanAnytimeResult::SUCCESS;
  std::printf("demo: result: %s (status %u): %s\n", ok ? "SUCCESS" : "FAILED", result->status,
              result->message.c_str());
  std::printf(
      "demo: %d improvement(s) streamed; final cost %.3f m, bound %.3f, certified %.3f, "
      "%.3f s, %llu expansions\n",
      improvements, result->cost, result->bound, result->certified_bound, result->planning_time,
      static_cast<unsigned long long>(result->expansions));
  if (!output_image.empty()) {
    std::string name = algorithm;
    if (name.empty() && !ros::param::get("/amha_planner/algorithm", name)) name = "amha";
    char caption[200];
    std::snprintf(caption, sizeof caption,
                  "%s: %zu solutions, final cost %.2f m, bound %.2f (certified %.2f), "
                  "%.2f s",
                  name.c_str(), result->solutions.size(), result->cost, result->bound,
                  result->certified_bound, result->planning_time);
    std::lock_guard<std::mutex> lock(map_mutex);
    drawPicture(*map, result->solutions, start, goal.goal, caption, output_image);
  }
  std::printf("demo: finished %s\n", ok ? "SUCCESS" : "FAILED");
  std::fflush(stdout);
  return ok ? 0 : 1;
}
