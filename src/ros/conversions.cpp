// Message <-> library conversions (see conversions.h).
#include "amha_planner/ros/conversions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include <tf2/LinearMath/Quaternion.h>
#include <tf2/utils.h>

#include "amha_planner/lattice/map_loaders.h"  // occupancyToCost
#include "amha_planner/ros/planner_params.h"   // normaliseFrame

namespace amha_planner {

namespace lat = amha::lattice;

lat::GridMap gridMapFromOccupancy(const nav_msgs::OccupancyGrid& msg,
                                  const lat::OccupancyConversion& conversion,
                                  std::size_t max_cells) {
  const geometry_msgs::Pose& o = msg.info.origin;
  std::string why;
  if (!checkPose(o, &why)) {
    throw lat::LatticeError(lat::LatticeError::Kind::kMap, "map origin: " + why);
  }
  // A grid tilted out of the plane cannot be planned on in (x, y, theta).
  tf2::Quaternion q(o.orientation.x, o.orientation.y, o.orientation.z, o.orientation.w);
  double roll = 0, pitch = 0, yaw = 0;
  tf2::Matrix3x3(q.normalized()).getRPY(roll, pitch, yaw);
  if (std::abs(roll) > 1e-3 || std::abs(pitch) > 1e-3) {
    throw lat::LatticeError(lat::LatticeError::Kind::kMap,
                            "map origin is not planar (roll/pitch not zero)");
  }
  // The library checks sizes against the data length before reading it.
  if (msg.info.width > static_cast<std::uint32_t>(std::numeric_limits<int>::max()) ||
      msg.info.height > static_cast<std::uint32_t>(std::numeric_limits<int>::max())) {
    std::ostringstream s;
    s << "map size " << msg.info.width << " x " << msg.info.height << " is too large";
    throw lat::LatticeError(lat::LatticeError::Kind::kMap, s.str());
  }
  return lat::gridMapFromOccupancy(
      static_cast<int>(msg.info.width), static_cast<int>(msg.info.height), msg.info.resolution,
      o.position.x, o.position.y, yaw, msg.data.data(), msg.data.size(), conversion, max_cells);
}

void convertOccupancyCells(const nav_msgs::OccupancyGrid& msg, const lat::CellRect& rect,
                           const lat::OccupancyConversion& conversion, lat::GridMap* grid) {
  const std::uint64_t w = msg.info.width, h = msg.info.height;
  if (static_cast<std::uint64_t>(grid->width) != w ||
      static_cast<std::uint64_t>(grid->height) != h || msg.data.size() != w * h ||
      grid->cost.size() != w * h) {
    throw lat::LatticeError(lat::LatticeError::Kind::kMap,
                            "map cells: the grid and the message differ in size");
  }
  if (rect.empty()) return;
  if (rect.x0 < 0 || rect.y0 < 0 || static_cast<std::uint64_t>(rect.x1) > w ||
      static_cast<std::uint64_t>(rect.y1) > h) {
    throw lat::LatticeError(lat::LatticeError::Kind::kMap, "map cells: rectangle leaves the map");
  }
  std::uint8_t table[256];
  for (int v = -128; v < 128; ++v) {
    table[static_cast<std::uint8_t>(v)] = lat::occupancyToCost(v, conversion);
  }
  for (int y = rect.y0; y < rect.y1; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * w;
    for (int x = rect.x0; x < rect.x1; ++x) {
      grid->cost[row + x] = table[static_cast<std::uint8_t>(msg.data[row + x])];
    }
  }
}

void applyOccupancyGridUpdate(const map_msgs::OccupancyGridUpdate& update,
                              nav_msgs::OccupancyGrid* grid) {
  auto refuse = [](const std::string& why) {
    throw lat::LatticeError(lat::LatticeError::Kind::kMap, "map update refused: " + why);
  };
  if (grid->data.size() != static_cast<std::uint64_t>(grid->info.width) * grid->info.height) {
    refuse("the map it would change is malformed");
  }
  const std::uint64_t w = update.width, h = update.height;
  if (update.data.size() != w * h) {
    std::ostringstream s;
    s << "data length " << update.data.size() << " != width x height = " << w << " x " << h;
    refuse(s.str());
  }
  // Unsigned 64-bit sums: x + width cannot wrap for 32-bit inputs.
  const std::uint64_t x = update.x, y = update.y;
  if (update.x < 0 || update.y < 0 || x + w > grid->info.width || y + h > grid->info.height) {
    std::ostringstream s;
    s << "rectangle (" << update.x << ", " << update.y << ") + " << w << " x " << h
      << " leaves the " << grid->info.width << " x " << grid->info.height << " map";
    refuse(s.str());
  }
  const std::string& uf = update.header.frame_id;
  const std::string& gf = grid->header.frame_id;
  if (!uf.empty() && !gf.empty() && normaliseFrame(uf) != normaliseFrame(gf)) {
    refuse("frame '" + uf + "' is not the map's frame '" + gf + "'");
  }
  for (std::uint64_t r = 0; r < h; ++r) {
    const auto src = update.data.begin() + static_cast<std::ptrdiff_t>(r * w);
    std::copy(src, src + static_cast<std::ptrdiff_t>(w),
              grid->data.begin() + static_cast<std::ptrdiff_t>((y + r) * grid->info.width + x));
  }
}

bool checkPose(const geometry_msgs::Pose& pose, std::string* why) {
  const auto& p = pose.position;
  const auto& q = pose.orientation;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
    *why = "position is not finite";
    return false;
  }
  if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) || !std::isfinite(q.w)) {
    *why = "orientation quaternion is not finite";
    return false;
  }
  const double norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (std::abs(norm - 1.0) > 1e-3) {
    std::ostringstream s;
    s << "orientation quaternion is not normalised (norm " << norm << ")";
    *why = s.str();
    return false;
  }
  return true;
}

lat::Pose2D pose2DFromPose(const geometry_msgs::Pose& pose) {
  const auto& q = pose.orientation;
  lat::Pose2D out;
  out.x = pose.position.x;
  out.y = pose.position.y;
  out.theta = tf2::getYaw(tf2::Quaternion(q.x, q.y, q.z, q.w));
  return out;
}

geometry_msgs::Quaternion quaternionFromYaw(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(yaw / 2);
  q.w = std::cos(yaw / 2);
  return q;
}

geometry_msgs::PoseStamped poseStampedFromPose2D(const lat::Pose2D& pose, const std::string& frame,
                                                 const ros::Time& stamp) {
  geometry_msgs::PoseStamped ps;
  ps.header.frame_id = frame;
  ps.header.stamp = stamp;
  ps.pose.position.x = pose.x;
  ps.pose.position.y = pose.y;
  ps.pose.orientation = quaternionFromYaw(pose.theta);
  return ps;
}

nav_msgs::Path pathFromPoses(const std::vector<lat::Pose2D>& poses, const std::string& frame,
                             const ros::Time& stamp) {
  nav_msgs::Path path;
  path.header.frame_id = frame;
  path.header.stamp = stamp;
  path.poses.reserve(poses.size());
  for (const lat::Pose2D& p : poses) path.poses.push_back(poseStampedFromPose2D(p, frame, stamp));
  return path;
}

PlanSolution planSolutionMsg(const lat::LatticeSolution& solution, std::uint32_t request_id,
                             const std::string& frame, const ros::Time& stamp) {
  PlanSolution m;
  m.request_id = request_id;
  m.path = pathFromPoses(solution.poses, frame, stamp);
  m.cost = costInMetres(solution.search.cost);
  m.w1 = solution.search.w1;
  m.w2 = solution.search.w2;
  m.bound = solution.search.nominal_bound;
  m.certified_bound = solution.search.certified_bound;
  m.elapsed = solution.elapsed_total_s;  // heuristic grids for a new goal included
  m.expansions = solution.search.expansions;
  m.iteration = solution.search.iteration;
  m.lattice_cost = m.cost;
  return m;
}

PlanSolution smoothedSolutionMsg(const lat::LatticeSolution& published,
                                 const lat::LatticeSolution& lattice, std::uint32_t request_id,
                                 const std::string& frame, const ros::Time& stamp) {
  PlanSolution m = planSolutionMsg(published, request_id, frame, stamp);
  m.smoothed = true;
  m.lattice_path = pathFromPoses(lattice.poses, frame, stamp);
  m.lattice_cost = costInMetres(lattice.search.cost);
  return m;
}

namespace {

visualization_msgs::Marker baseMarker(const std::string& ns, int id, int type,
                                      const std::string& frame, const ros::Time& stamp) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  return m;
}

void addOutline(const std::vector<std::array<double, 2>>& polygon,
                visualization_msgs::Marker* lines) {
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const auto& a = polygon[i];
    const auto& b = polygon[(i + 1) % polygon.size()];
    geometry_msgs::Point pa, pb;
    pa.x = a[0];
    pa.y = a[1];
    pb.x = b[0];
    pb.y = b[1];
    lines->points.push_back(pa);
    lines->points.push_back(pb);
  }
}

std_msgs::ColorRGBA color(float r, float g, float b, float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

visualization_msgs::Marker poseArrow(const std::string& ns, const lat::Pose2D& p,
                                     const std_msgs::ColorRGBA& c, const std::string& frame,
                                     const ros::Time& stamp) {
  auto m = baseMarker(ns, 0, visualization_msgs::Marker::ARROW, frame, stamp);
  m.pose.position.x = p.x;
  m.pose.position.y = p.y;
  m.pose.position.z = 0.05;
  m.pose.orientation = quaternionFromYaw(p.theta);
  m.scale.x = 1.0;
  m.scale.y = 0.2;
  m.scale.z = 0.2;
  m.color = c;
  return m;
}

}  // namespace

visualization_msgs::MarkerArray footprintMarkers(const lat::LatticePlanner& planner,
                                                 const std::vector<lat::Pose2D>& poses,
                                                 const lat::Pose2D& start, const lat::Pose2D& goal,
                                                 const std::string& frame, const ros::Time& stamp,
                                                 double spacing) {
  visualization_msgs::MarkerArray out;
  auto clear = baseMarker("", 0, visualization_msgs::Marker::LINE_LIST, frame, stamp);
  clear.action = visualization_msgs::Marker::DELETEALL;
  out.markers.push_back(clear);

  auto along = baseMarker("footprints", 0, visualization_msgs::Marker::LINE_LIST, frame, stamp);
  along.scale.x = 0.04;
  along.color = color(1.0f, 0.55f, 0.0f, 0.9f);  // orange around the (blue) path
  double travelled = 0.0, next = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (i > 0) travelled += std::hypot(poses[i].x - poses[i - 1].x, poses[i].y - poses[i - 1].y);
    if (travelled >= next || i + 1 == poses.size()) {
      addOutline(planner.footprintAt(poses[i]), &along);
      next = travelled + spacing;
    }
  }
  if (!along.points.empty()) out.markers.push_back(along);

  const auto green = color(0.0f, 0.8f, 0.0f, 1.0f);
  const auto red = color(0.9f, 0.0f, 0.0f, 1.0f);
  out.markers.push_back(poseArrow("start", start, green, frame, stamp));
  out.markers.push_back(poseArrow("goal", goal, red, frame, stamp));
  auto start_fp =
      baseMarker("start_footprint", 0, visualization_msgs::Marker::LINE_LIST, frame, stamp);
  start_fp.scale.x = 0.06;
  start_fp.color = green;
  addOutline(planner.footprintAt(start), &start_fp);
  out.markers.push_back(start_fp);
  auto goal_fp = start_fp;
  goal_fp.ns = "goal_footprint";
  goal_fp.points.clear();
  goal_fp.color = red;
  addOutline(planner.footprintAt(goal), &goal_fp);
  out.markers.push_back(goal_fp);
  return out;
}

}  // namespace amha_planner
