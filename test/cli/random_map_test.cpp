// Benchmark inputs: random maps are seeded, as dense as asked, one free region, and load as
// map_server maps; random queries are valid, connected and far enough apart.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/map_loaders.h"
#include "random_map.h"
#include "random_queries.h"
#include "test_support.h"

namespace amha {
namespace cli {
namespace {

RandomMapOptions small(unsigned seed) {
  RandomMapOptions o;
  o.width = 400;
  o.height = 300;
  o.seed = seed;
  return o;
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && cv::countNonZero(a != b) == 0;
}

TEST(RandomMap, SeededDenseAndOneFreeRegion) {
  const RandomMap a = randomObstacleMap(small(1)), b = randomObstacleMap(small(1)),
                  c = randomObstacleMap(small(2));
  EXPECT_TRUE(same(a.occupied, b.occupied));
  EXPECT_FALSE(same(a.occupied, c.occupied));
  for (const RandomMap* m : {&a, &c}) {
    // At least the fraction asked for; the last shape and the filled pockets add a little.
    EXPECT_GE(m->occupied_fraction, 0.15);
    EXPECT_LE(m->occupied_fraction, 0.19);
    EXPECT_GT(m->obstacles, 20);
    cv::Mat labels;
    EXPECT_EQ(cv::connectedComponents(m->occupied == 0, labels, 4),
              2);  // background + one free region
  }
  RandomMapOptions bad = small(1);
  bad.obstacle_fraction = NAN;
  EXPECT_THROW(randomObstacleMap(bad), std::invalid_argument);
  bad = small(1);
  bad.resolution = -0.05;
  EXPECT_THROW(randomObstacleMap(bad), std::invalid_argument);
  bad = small(1);
  bad.width = 0;
  EXPECT_THROW(randomObstacleMap(bad), std::invalid_argument);
}

TEST(RandomMap, LoadsAsMapServerMap) {
  const RandomMap m = randomObstacleMap(small(5));
  const std::string base = lattice::test::tempDir() + "/random";
  writeMapServerFiles(base, m.occupied, 0.05);
  const lattice::GridMap g = lattice::loadMapServerMap(base + ".yaml");
  ASSERT_EQ(g.width, 400);
  ASSERT_EQ(g.height, 300);
  EXPECT_DOUBLE_EQ(g.resolution, 0.05);
  // map_server puts the image's top row at the top of the map (largest y).
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const bool occupied = m.occupied.at<std::uint8_t>(g.height - 1 - y, x) != 0;
      ASSERT_EQ(g.at(x, y), occupied ? lattice::kLethalCost : lattice::kFreeCost) << x << " " << y;
    }
  }
}

TEST(RandomQueries, ValidConnectedFarApartAndSeeded) {
  const RandomMap rm = randomObstacleMap(small(7));
  const std::string base = lattice::test::tempDir() + "/random";
  writeMapServerFiles(base, rm.occupied, 0.05);
  auto map = std::make_shared<lattice::GridMap>(lattice::loadMapServerMap(base + ".yaml"));
  // Mark a band of cells inscribed: queries must not start or end with the centre in it.
  for (int y = 0; y < map->height; ++y) map->cost[y * map->width + 200] = lattice::kInscribedCost;
  lattice::LatticeConfig config;
  config.robot.radius = 0.25;
  const lattice::LatticeGraph graph(map, config);
  const std::vector<Query> qs = randomQueries(graph, 15, 3, 8.0);
  ASSERT_EQ(qs.size(), 15u);
  int crossing = 0;
  for (const Query& q : qs) {
    int sx, sy, sh, gx, gy, gh;
    ASSERT_TRUE(graph.poseToState(q.start, &sx, &sy, &sh));
    ASSERT_TRUE(graph.poseToState(q.goal, &gx, &gy, &gh));
    EXPECT_TRUE(graph.stateValid(sx, sy, sh));
    EXPECT_TRUE(graph.stateValid(gx, gy, gh));
    EXPECT_GE(std::hypot(q.goal.x - q.start.x, q.goal.y - q.start.y), 8.0);
    EXPECT_TRUE(lattice::test::floodFill(*map, sx, sy)[gy * map->width + gx])
        << "start and goal are not connected";
    crossing += (sx < 200) != (gx < 200);
  }
  EXPECT_EQ(crossing, 0);  // the inscribed band splits the map in two
  const std::vector<Query> again = randomQueries(graph, 15, 3, 8.0),
                           other = randomQueries(graph, 15, 4, 8.0);
  for (std::size_t i = 0; i < qs.size(); ++i) {
    EXPECT_EQ(again[i].start.x, qs[i].start.x);
    EXPECT_EQ(again[i].goal.theta, qs[i].goal.theta);
  }
  EXPECT_NE(other[0].start.x, qs[0].start.x);
}

}  // namespace
}  // namespace cli
}  // namespace amha
