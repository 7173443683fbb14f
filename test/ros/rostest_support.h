// Helpers shared by the rostest nodes: a synthetic test map, an independent collision check
// of a path against the published occupancy grid, and small message builders.
#pragma once

#include <array>
#include <atomic>
#include <string>
#include <vector>

#include <actionlib/client/simple_action_client.h>

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <ros/publisher.h>

#include "amha_planner/PlanAnytimeAction.h"

namespace amha_planner {
namespace test {

/// An occupancy grid being drawn in world coordinates (0 free, 100 occupied).
struct MapBuilder {
  nav_msgs::OccupancyGrid grid;
  MapBuilder(double origin_x, double origin_y, double resolution, unsigned width, unsigned height,
             const std::string& frame);
  /// Sets every cell whose centre lies in [x0, x1] x [y0, y1] to `value`.
  void fill(double x0, double y0, double x1, double y1, signed char value);
  /// A closed rectangular wall of the given thickness.
  void box(double x0, double y0, double x1, double y1, double thickness);
};

/// The map the planner tests use: 30 m x 20 m at 0.05 m, origin (-1, -2). Rooms on the left
/// (a wall at x = 5 with two doors, a block at [2, 3] x [3, 5], a closed pocket around
/// (8, 15)), a serpentine maze on the right (x in [11, 29]) for long searches.
nav_msgs::OccupancyGrid testMap();
/// testMap() with the maze's door closed by a block at [10.5, 11.5] x [6.9, 9.1]: a "new map"
/// that can be told apart (see probeMap in planner_rostest.cpp), on which the maze is unreachable.
nav_msgs::OccupancyGrid testMapWithExtraBlock();

/// The footprint the tests configure (base frame, metres): 0.5 m x 0.36 m.
std::vector<std::array<double, 2>> testFootprint();

/// Independent collision check: every cell whose centre lies inside the footprint placed at a
/// path pose must be known and below `lethal_threshold`. Returns "" or the first violation.
std::string checkPathCollisionFree(const nav_msgs::Path& path, const nav_msgs::OccupancyGrid& map,
                                   const std::vector<std::array<double, 2>>& footprint,
                                   int lethal_threshold);

/// Waits up to `seconds` for `pub` to have a subscriber (a message published before the
/// connection exists is lost); true once it has one.
bool waitForSubscriber(const ros::Publisher& pub, double seconds);

/// Sends a ~plan_anytime goal from start to goal with `budget` seconds through `client`,
/// counting its feedback in `feedback` (which must outlive the client), and waits up to 30 s for
/// the first: true once it came (the goal is then planning, or done).
bool sendAndAwaitFeedback(actionlib::SimpleActionClient<PlanAnytimeAction>& client,
                          const geometry_msgs::PoseStamped& start,
                          const geometry_msgs::PoseStamped& goal, double budget,
                          std::atomic<int>& feedback);

geometry_msgs::PoseStamped pose(double x, double y, double yaw, const std::string& frame);
double yawOf(const geometry_msgs::Pose& p);
/// Smallest absolute difference between two angles.
double angleDiff(double a, double b);

}  // namespace test
}  // namespace amha_planner
