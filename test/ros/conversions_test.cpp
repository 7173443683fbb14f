// The ROS layer's conversions and request overrides, without a ROS master.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "amha_planner/ros/conversions.h"
#include "amha_planner/ros/planner_params.h"

namespace amha_planner {
namespace {

geometry_msgs::Pose poseWith(double x, double y, double qx, double qy, double qz, double qw) {
  geometry_msgs::Pose p;
  p.position.x = x;
  p.position.y = y;
  p.orientation.x = qx;
  p.orientation.y = qy;
  p.orientation.z = qz;
  p.orientation.w = qw;
  return p;
}

TEST(CheckPose, RefusesNonFiniteZeroAndNonNormalisedQuaternions) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::string why;
  EXPECT_TRUE(checkPose(poseWith(1, 2, 0, 0, 0, 1), &why));
  EXPECT_TRUE(checkPose(poseWith(1, 2, 0, 0, 0, 1.0009), &why)) << "within 1e-3 of unit norm";
  EXPECT_FALSE(checkPose(poseWith(1, 2, 0, 0, 0, 1.002), &why));
  EXPECT_NE(why.find("not normalised"), std::string::npos) << why;
  EXPECT_FALSE(checkPose(poseWith(1, 2, 0, 0, 0, 0), &why));
  EXPECT_FALSE(checkPose(poseWith(1, 2, 0, 0, nan, 1), &why));
  EXPECT_NE(why.find("not finite"), std::string::npos) << why;
  EXPECT_FALSE(checkPose(poseWith(nan, 2, 0, 0, 0, 1), &why));
  EXPECT_FALSE(checkPose(poseWith(1, std::numeric_limits<double>::infinity(), 0, 0, 0, 1), &why));
}

TEST(Conversions, YawRoundTripsThroughQuaternions) {
  for (double yaw : {-3.0, -1.2, 0.0, 0.4, 1.5707, 3.1}) {
    geometry_msgs::Pose p;
    p.position.x = 3;
    p.position.y = -4;
    p.orientation = quaternionFromYaw(yaw);
    std::string why;
    ASSERT_TRUE(checkPose(p, &why)) << why;
    const auto q = pose2DFromPose(p);
    EXPECT_DOUBLE_EQ(q.x, 3);
    EXPECT_DOUBLE_EQ(q.y, -4);
    EXPECT_NEAR(q.theta, yaw, 1e-9);
  }
}

nav_msgs::OccupancyGrid grid(unsigned w, unsigned h, double yaw) {
  nav_msgs::OccupancyGrid g;
  g.info.width = w;
  g.info.height = h;
  g.info.resolution = 0.1f;
  g.info.origin.position.x = 2.0;
  g.info.origin.position.y = -1.0;
  g.info.origin.orientation = quaternionFromYaw(yaw);
  g.data.assign(static_cast<std::size_t>(w) * h, 0);
  return g;
}

TEST(Conversions, OccupancyGridBecomesAGridMapWithItsOrigin) {
  auto g = grid(4, 3, 0.5);
  g.data[1] = 100;  // cell (1, 0)
  g.data[4] = -1;   // cell (0, 1)
  const auto map = gridMapFromOccupancy(g, amha::lattice::OccupancyConversion(), 1000);
  EXPECT_EQ(map.width, 4);
  EXPECT_EQ(map.height, 3);
  EXPECT_NEAR(map.resolution, 0.1, 1e-7);
  EXPECT_DOUBLE_EQ(map.origin_x, 2.0);
  EXPECT_DOUBLE_EQ(map.origin_y, -1.0);
  EXPECT_NEAR(map.origin_yaw, 0.5, 1e-9);
  EXPECT_EQ(map.at(0, 0), amha::lattice::kFreeCost);
  EXPECT_EQ(map.at(1, 0), amha::lattice::kLethalCost);
  EXPECT_EQ(map.at(0, 1), amha::lattice::kUnknownCost);
}

TEST(Conversions, BadGridsAreRefusedWithAReason) {
  using amha::lattice::LatticeError;
  const amha::lattice::OccupancyConversion c;
  auto g = grid(4, 3, 0.0);
  g.data.pop_back();
  EXPECT_THROW(gridMapFromOccupancy(g, c, 1000), LatticeError);
  g = grid(4, 3, 0.0);
  g.info.resolution = 0.0f;
  EXPECT_THROW(gridMapFromOccupancy(g, c, 1000), LatticeError);
  g = grid(4, 3, 0.0);
  g.info.origin.orientation.w = 0.0;
  EXPECT_THROW(gridMapFromOccupancy(g, c, 1000), LatticeError);
  g = grid(4, 3, 0.0);
  g.info.origin.orientation.x = std::sin(0.2);  // rolled: not a planar map
  g.info.origin.orientation.w = std::cos(0.2);
  EXPECT_THROW(gridMapFromOccupancy(g, c, 1000), LatticeError);
  g = grid(40, 30, 0.0);
  EXPECT_THROW(gridMapFromOccupancy(g, c, 1000), LatticeError) << "over max_cells";
  g = grid(4, 3, 0.0);
  g.info.width = 4000000000u;  // larger than an int
  try {
    gridMapFromOccupancy(g, c, 1000);
    FAIL() << "a width beyond int must be refused";
  } catch (const LatticeError& e) {
    EXPECT_NE(std::string(e.what()).find("too large"), std::string::npos) << e.what();
  }
}

map_msgs::OccupancyGridUpdate gridUpdate(int x, int y, unsigned w, unsigned h, std::int8_t first) {
  map_msgs::OccupancyGridUpdate u;
  u.x = x;
  u.y = y;
  u.width = w;
  u.height = h;
  for (unsigned i = 0; i < w * h; ++i) u.data.push_back(static_cast<std::int8_t>(first + i));
  return u;
}

TEST(MapUpdate, WritesItsRectangleRowByRowAndNothingElse) {
  auto g = grid(5, 4, 0.0);
  g.header.frame_id = "map";
  auto u = gridUpdate(1, 2, 3, 2, 10);  // cells (1..3, 2..3) get 10..15
  u.header.frame_id = "/map";           // the same frame, spelt with a slash
  applyOccupancyGridUpdate(u, &g);
  for (unsigned y = 0; y < 4; ++y) {
    for (unsigned x = 0; x < 5; ++x) {
      const bool inside = x >= 1 && x <= 3 && y >= 2;
      const int expected = inside ? static_cast<int>(10 + (y - 2) * 3 + (x - 1)) : 0;
      EXPECT_EQ(g.data[y * 5 + x], expected) << "cell (" << x << ", " << y << ")";
    }
  }
  // An empty rectangle changes nothing; one that fills the map replaces all of it.
  const auto before = g.data;
  applyOccupancyGridUpdate(gridUpdate(5, 4, 0, 0, 0), &g);
  EXPECT_EQ(g.data, before);
  applyOccupancyGridUpdate(gridUpdate(0, 0, 5, 4, -1), &g);
  EXPECT_EQ(g.data[0], -1);
  EXPECT_EQ(g.data[19], 18);
}

TEST(MapUpdate, BadUpdatesAreRefusedWithAReasonAndChangeNothing) {
  using amha::lattice::LatticeError;
  auto g = grid(5, 4, 0.0);
  g.header.frame_id = "map";
  const auto before = g.data;
  auto expectRefused = [&](const map_msgs::OccupancyGridUpdate& u, const std::string& reason) {
    try {
      applyOccupancyGridUpdate(u, &g);
      ADD_FAILURE() << "accepted: " << reason;
    } catch (const LatticeError& e) {
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
    EXPECT_EQ(g.data, before) << reason;
  };
  auto u = gridUpdate(0, 0, 2, 2, 1);
  u.data.pop_back();
  expectRefused(u, "data length 3 != width x height");
  expectRefused(gridUpdate(4, 0, 2, 1, 1), "leaves the 5 x 4 map");   // one column past the edge
  expectRefused(gridUpdate(0, 3, 1, 2, 1), "leaves the 5 x 4 map");   // one row past the edge
  expectRefused(gridUpdate(-1, 0, 1, 1, 1), "leaves the 5 x 4 map");  // negative offset
  // x + width wraps to 2 in 32 bits (inside the map) but is far outside it; no rows, no data.
  u = gridUpdate(6, 0, std::numeric_limits<std::uint32_t>::max() - 3, 0, 0);
  expectRefused(u, "leaves the 5 x 4 map");
  u = gridUpdate(std::numeric_limits<std::int32_t>::max(), 0, 0, 0, 0);
  expectRefused(u, "leaves the 5 x 4 map");
  u = gridUpdate(0, 0, 1, 1, 1);
  u.header.frame_id = "odom";
  expectRefused(u, "frame 'odom' is not the map's frame 'map'");
}

TEST(MapUpdate, ConvertingOnlyTheChangedCellsGivesTheFullConversion) {
  namespace lat = amha::lattice;
  nav_msgs::OccupancyGrid before = grid(7, 5, 0.0);
  for (std::size_t i = 0; i < before.data.size(); ++i)
    before.data[i] = static_cast<std::int8_t>(i * 7 % 101);
  lat::OccupancyConversion conversion;
  conversion.lethal_threshold = 50;
  const lat::GridMap old_grid = gridMapFromOccupancy(before, conversion, 1000);
  nav_msgs::OccupancyGrid after = before;
  applyOccupancyGridUpdate(gridUpdate(2, 1, 3, 3, 45), &after);  // 45..53: across the threshold
  lat::GridMap patched = old_grid;
  convertOccupancyCells(after, lat::CellRect{2, 1, 5, 4}, conversion, &patched);
  EXPECT_EQ(patched.cost, gridMapFromOccupancy(after, conversion, 1000).cost);
  EXPECT_NE(patched.cost, old_grid.cost);
  // A rectangle outside the map or a grid of another size is refused, the grid unchanged.
  const lat::GridMap kept = patched;
  EXPECT_THROW(convertOccupancyCells(after, lat::CellRect{5, 0, 8, 2}, conversion, &patched),
               lat::LatticeError);
  EXPECT_THROW(convertOccupancyCells(after, lat::CellRect{-1, 0, 2, 2}, conversion, &patched),
               lat::LatticeError);
  lat::GridMap other = gridMapFromOccupancy(grid(6, 5, 0.0), conversion, 1000);
  EXPECT_THROW(convertOccupancyCells(after, lat::CellRect{0, 0, 1, 1}, conversion, &other),
               lat::LatticeError);
  EXPECT_EQ(patched.cost, kept.cost);
}

TEST(Conversions, CostsAreReportedInMetres) {
  amha::lattice::LatticeSolution s;
  s.search.cost = 12345;
  s.search.nominal_bound = 4.0;
  s.search.certified_bound = 1.5;
  s.search.iteration = 3;
  s.elapsed_total_s = 0.25;
  s.poses = {{0, 0, 0}, {1, 0, 0.5}};
  const auto m = planSolutionMsg(s, 7, "map", ros::Time(1, 0));
  EXPECT_DOUBLE_EQ(m.cost, 12.345);
  EXPECT_EQ(m.request_id, 7u);
  EXPECT_DOUBLE_EQ(m.bound, 4.0);
  EXPECT_DOUBLE_EQ(m.certified_bound, 1.5);
  EXPECT_DOUBLE_EQ(m.elapsed, 0.25);
  EXPECT_EQ(m.iteration, 3);
  ASSERT_EQ(m.path.poses.size(), 2u);
  EXPECT_EQ(m.path.header.frame_id, "map");
  EXPECT_EQ(m.path.poses[1].header.frame_id, "map");
  EXPECT_NEAR(m.path.poses[1].pose.orientation.z, std::sin(0.25), 1e-12);
}

TEST(SearchConfigFor, AppliesParametersThenRequestOverrides) {
  PlannerParams p;  // defaults: amha with the lattice's preset
  amha::PlannerConfig c;
  std::string error;
  ASSERT_TRUE(searchConfigFor(p, "", 0, 0, &c, &error)) << error;
  EXPECT_EQ(c.algorithm, amha::Algorithm::kAmhaStar);
  EXPECT_DOUBLE_EQ(c.w1, amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar).w1);
  EXPECT_EQ(c.weight_schedule, amha::WeightSchedule::kCertified);
  EXPECT_TRUE(c.publish_within_iterations);
  p.weight_schedule = amha::WeightSchedule::kDecrement;
  p.publish_within_iterations = false;
  ASSERT_TRUE(searchConfigFor(p, "", 0, 0, &c, &error)) << error;
  EXPECT_EQ(c.weight_schedule, amha::WeightSchedule::kDecrement);
  EXPECT_FALSE(c.publish_within_iterations);
  p.certified_ratio = 1.5;  // out of range: refused by the planner's own check
  p.weight_schedule = amha::WeightSchedule::kCertified;
  EXPECT_FALSE(searchConfigFor(p, "", 0, 0, &c, &error));
  EXPECT_NE(error.find("certified_ratio"), std::string::npos) << error;
  p.certified_ratio = 0.0;
  p.w1 = 3.0;
  p.dw2 = 0.25;
  ASSERT_TRUE(searchConfigFor(p, "", 0, 2.0, &c, &error)) << error;
  EXPECT_DOUBLE_EQ(c.w1, 3.0);
  EXPECT_DOUBLE_EQ(c.w2, 2.0) << "the request's w2";
  EXPECT_DOUBLE_EQ(c.dw2, 0.25);
  EXPECT_EQ(c.schedule, amha::QueueSchedule::kRoundRobin);
  p.queue_schedule = amha::QueueSchedule::kDts;
  ASSERT_TRUE(searchConfigFor(p, "mha", 0, 0, &c, &error)) << error;
  EXPECT_EQ(c.schedule, amha::QueueSchedule::kDts);
  // ARA*: eps is w1; the request's w1 overrides it.
  p.eps = 4.0;
  ASSERT_TRUE(searchConfigFor(p, "ara", 0, 0, &c, &error)) << error;
  EXPECT_EQ(c.algorithm, amha::Algorithm::kAraStar);
  EXPECT_DOUBLE_EQ(c.w1, 4.0);
  EXPECT_DOUBLE_EQ(c.w2, 1.0);
  ASSERT_TRUE(searchConfigFor(p, "wastar", 2.5, 0, &c, &error)) << error;
  EXPECT_DOUBLE_EQ(c.w1, 2.5);
  // Refusals.
  EXPECT_FALSE(searchConfigFor(p, "dijkstra", 0, 0, &c, &error));
  EXPECT_NE(error.find("dijkstra"), std::string::npos);
  EXPECT_FALSE(searchConfigFor(p, "", 0.5, 0, &c, &error));
  EXPECT_FALSE(searchConfigFor(p, "", 0, std::numeric_limits<double>::infinity(), &c, &error));
}

// A request's weights live in [1, amha::kMaxWeight] (issue 22, item 1: w1 = 1e308 was answered
// NO_PATH_FOUND); every algorithm that reads them refuses the rest with a message.
TEST(SearchConfigFor, RefusesRequestWeightsOutsideTheirRange) {
  PlannerParams p;
  amha::PlannerConfig c;
  std::string error;
  for (const char* algorithm : {"", "amha", "mha", "ara", "wastar"}) {
    for (double w : {amha::kMaxWeight * 1.01, 1e15, 1e308, std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN(), -1.0, 0.5}) {
      EXPECT_FALSE(searchConfigFor(p, algorithm, w, 0, &c, &error)) << algorithm << " w1 " << w;
      EXPECT_NE(error.find("is outside [1, 1e+06]"), std::string::npos) << error;
      EXPECT_FALSE(searchConfigFor(p, algorithm, 0, w, &c, &error)) << algorithm << " w2 " << w;
    }
    EXPECT_TRUE(searchConfigFor(p, algorithm, amha::kMaxWeight, 0, &c, &error)) << error;
  }
}

TEST(NormaliseFrame, StripsALeadingSlash) {
  EXPECT_EQ(normaliseFrame("/map"), "map");
  EXPECT_EQ(normaliseFrame("map"), "map");
  EXPECT_EQ(normaliseFrame(""), "");
}

}  // namespace
}  // namespace amha_planner
