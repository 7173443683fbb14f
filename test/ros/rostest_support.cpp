// Helpers shared by the rostest nodes (see rostest_support.h).
#include "rostest_support.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <ros/time.h>

namespace amha_planner {
namespace test {

MapBuilder::MapBuilder(double origin_x, double origin_y, double resolution, unsigned width,
                       unsigned height, const std::string& frame) {
  grid.header.frame_id = frame;
  grid.info.resolution = static_cast<float>(resolution);
  grid.info.width = width;
  grid.info.height = height;
  grid.info.origin.position.x = origin_x;
  grid.info.origin.position.y = origin_y;
  grid.info.origin.orientation.w = 1.0;
  grid.data.assign(static_cast<std::size_t>(width) * height, 0);
}

void MapBuilder::fill(double x0, double y0, double x1, double y1, signed char value) {
  const double r = grid.info.resolution;
  const double ox = grid.info.origin.position.x, oy = grid.info.origin.position.y;
  const int w = static_cast<int>(grid.info.width), h = static_cast<int>(grid.info.height);
  for (int cy = 0; cy < h; ++cy) {
    const double y = oy + (cy + 0.5) * r;
    if (y < y0 || y > y1) continue;
    for (int cx = 0; cx < w; ++cx) {
      const double x = ox + (cx + 0.5) * r;
      if (x < x0 || x > x1) continue;
      grid.data[static_cast<std::size_t>(cy) * w + cx] = value;
    }
  }
}

void MapBuilder::box(double x0, double y0, double x1, double y1, double t) {
  fill(x0, y0, x1, y0 + t, 100);
  fill(x0, y1 - t, x1, y1, 100);
  fill(x0, y0, x0 + t, y1, 100);
  fill(x1 - t, y0, x1, y1, 100);
}

nav_msgs::OccupancyGrid testMap() {
  static const nav_msgs::OccupancyGrid map = [] {
    MapBuilder m(-1.0, -2.0, 0.05, 600, 400, "map");
    m.box(-1.0, -2.0, 29.0, 18.0, 0.2);  // outer wall
    // Rooms: a wall at x = 5 with doors at y in [1, 2.2] and [12, 13.5].
    m.fill(4.9, -2.0, 5.1, 1.0, 100);
    m.fill(4.9, 2.2, 5.1, 12.0, 100);
    m.fill(4.9, 13.5, 5.1, 18.0, 100);
    m.fill(2.0, 3.0, 3.0, 5.0, 100);   // a block
    m.box(7.0, 14.0, 9.0, 16.0, 0.2);  // a closed pocket: (8, 15) is free but unreachable
    // The maze: a wall at x = 11 with a door at y in [7, 9], then a serpentine of walls open
    // alternately at the top and at the bottom.
    m.fill(10.9, -2.0, 11.1, 7.0, 100);
    m.fill(10.9, 9.0, 11.1, 18.0, 100);
    const double walls[] = {13.5, 16.0, 18.5, 21.0, 23.5, 26.0};
    for (int i = 0; i < 6; ++i) {
      if (i % 2 == 0) {
        m.fill(walls[i] - 0.1, -2.0, walls[i] + 0.1, 16.0, 100);  // open at the top
      } else {
        m.fill(walls[i] - 0.1, 0.0, walls[i] + 0.1, 18.0, 100);  // open at the bottom
      }
    }
    return m.grid;
  }();
  return map;
}

nav_msgs::OccupancyGrid testMapWithExtraBlock() {
  nav_msgs::OccupancyGrid g = testMap();
  MapBuilder m(-1.0, -2.0, 0.05, 600, 400, "map");
  m.grid = g;
  m.fill(10.5, 6.9, 11.5, 9.1, 100);  // closes the maze's only door
  return m.grid;
}

std::vector<std::array<double, 2>> testFootprint() {
  return {{0.25, 0.18}, {0.25, -0.18}, {-0.25, -0.18}, {-0.25, 0.18}};
}

namespace {
bool insidePolygon(const std::vector<std::array<double, 2>>& poly, double x, double y) {
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const double xi = poly[i][0], yi = poly[i][1], xj = poly[j][0], yj = poly[j][1];
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}
}  // namespace

std::string checkPathCollisionFree(const nav_msgs::Path& path, const nav_msgs::OccupancyGrid& map,
                                   const std::vector<std::array<double, 2>>& footprint,
                                   int lethal_threshold) {
  const double r = map.info.resolution;
  const double ox = map.info.origin.position.x, oy = map.info.origin.position.y;
  const int w = static_cast<int>(map.info.width), h = static_cast<int>(map.info.height);
  for (std::size_t k = 0; k < path.poses.size(); ++k) {
    const auto& p = path.poses[k].pose;
    const double yaw = yawOf(p), c = std::cos(yaw), s = std::sin(yaw);
    std::vector<std::array<double, 2>> poly;
    double minx = 1e18, maxx = -1e18, miny = 1e18, maxy = -1e18;
    for (const auto& v : footprint) {
      const double x = p.position.x + c * v[0] - s * v[1];
      const double y = p.position.y + s * v[0] + c * v[1];
      poly.push_back({x, y});
      minx = std::min(minx, x);
      maxx = std::max(maxx, x);
      miny = std::min(miny, y);
      maxy = std::max(maxy, y);
    }
    const int cx0 = static_cast<int>(std::floor((minx - ox) / r)) - 1;
    const int cx1 = static_cast<int>(std::floor((maxx - ox) / r)) + 1;
    const int cy0 = static_cast<int>(std::floor((miny - oy) / r)) - 1;
    const int cy1 = static_cast<int>(std::floor((maxy - oy) / r)) + 1;
    for (int cy = cy0; cy <= cy1; ++cy) {
      for (int cx = cx0; cx <= cx1; ++cx) {
        const double x = ox + (cx + 0.5) * r, y = oy + (cy + 0.5) * r;
        if (!insidePolygon(poly, x, y)) continue;
        const bool outside = cx < 0 || cy < 0 || cx >= w || cy >= h;
        const int v = outside ? -1 : map.data[static_cast<std::size_t>(cy) * w + cx];
        if (!outside && v >= 0 && v < lethal_threshold) continue;
        std::ostringstream why;
        why << "pose " << k << " (" << p.position.x << ", " << p.position.y << ", " << yaw
            << "): footprint covers cell (" << cx << ", " << cy << ")";
        if (outside) return why.str() + " outside the map";
        return why.str() + " with occupancy " + std::to_string(v);
      }
    }
  }
  return "";
}

bool sendAndAwaitFeedback(actionlib::SimpleActionClient<PlanAnytimeAction>& client,
                          const geometry_msgs::PoseStamped& start,
                          const geometry_msgs::PoseStamped& goal, double budget,
                          std::atomic<int>& feedback) {
  if (!client.waitForServer(ros::Duration(5))) return false;
  PlanAnytimeGoal g;
  g.start = start;
  g.goal = goal;
  g.time_budget = budget;
  client.sendGoal(g, actionlib::SimpleActionClient<PlanAnytimeAction>::SimpleDoneCallback(),
                  actionlib::SimpleActionClient<PlanAnytimeAction>::SimpleActiveCallback(),
                  [&feedback](const PlanAnytimeFeedbackConstPtr&) { ++feedback; });
  for (int i = 0; i < 3000 && feedback == 0; ++i) ros::WallDuration(0.01).sleep();
  return feedback > 0;
}

bool waitForSubscriber(const ros::Publisher& pub, double seconds) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(seconds);
  while (pub.getNumSubscribers() == 0 && ros::WallTime::now() < deadline) {
    ros::WallDuration(0.01).sleep();
  }
  return pub.getNumSubscribers() > 0;
}

geometry_msgs::PoseStamped pose(double x, double y, double yaw, const std::string& frame) {
  geometry_msgs::PoseStamped p;
  p.header.frame_id = frame;
  p.pose.position.x = x;
  p.pose.position.y = y;
  p.pose.orientation.z = std::sin(yaw / 2);
  p.pose.orientation.w = std::cos(yaw / 2);
  return p;
}

double yawOf(const geometry_msgs::Pose& p) {
  const auto& q = p.orientation;
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

double angleDiff(double a, double b) {
  double d = std::fmod(std::abs(a - b), 2 * M_PI);
  return d > M_PI ? 2 * M_PI - d : d;
}

}  // namespace test
}  // namespace amha_planner
