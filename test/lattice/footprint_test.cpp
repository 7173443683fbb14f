// Footprint rasterisation and primitive sweeps against brute force.
#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/footprint.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "path_validator.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

using Poly = std::vector<std::array<double, 2>>;

std::set<std::pair<int, int>> bruteForce(const Poly& poly, double grow) {
  std::set<std::pair<int, int>> out;
  double minx = 1e18, maxx = -1e18, miny = 1e18, maxy = -1e18;
  for (const auto& v : poly) {
    minx = std::min(minx, v[0]);
    maxx = std::max(maxx, v[0]);
    miny = std::min(miny, v[1]);
    maxy = std::max(maxy, v[1]);
  }
  for (int j = static_cast<int>(std::floor(miny)) - 2; j <= static_cast<int>(std::floor(maxy)) + 2;
       ++j) {
    for (int i = static_cast<int>(std::floor(minx)) - 2;
         i <= static_cast<int>(std::floor(maxx)) + 2; ++i) {
      if (test::polygonMeetsSquare(poly, i, j, grow)) out.insert({i, j});
    }
  }
  return out;
}

std::set<std::pair<int, int>> asSet(const std::vector<CellOffset>& cells) {
  std::set<std::pair<int, int>> s;
  for (const auto& c : cells) s.insert({c.dx, c.dy});
  return s;
}

Poly randomPolygon(std::mt19937& rng, bool convex) {
  // A star-shaped polygon around a random centre (convex if the radii are equal).
  std::uniform_real_distribution<double> u(-5.0, 5.0), r(0.3, 6.0), a(0.0, 2 * M_PI);
  const double cx = u(rng), cy = u(rng);
  const int n = 3 + static_cast<int>(rng() % 8);
  std::vector<double> angles;
  for (int k = 0; k < n; ++k) angles.push_back(a(rng));
  std::sort(angles.begin(), angles.end());
  const double r0 = r(rng);
  Poly p;
  for (double t : angles) {
    const double rr = convex ? r0 : r(rng);
    p.push_back({cx + rr * std::cos(t), cy + rr * std::sin(t)});
  }
  return p;
}

TEST(FootprintTest, PolygonRasterisationMatchesBruteForce) {
  std::mt19937 rng(7);
  for (int k = 0; k < 400; ++k) {
    const Poly p = randomPolygon(rng, k % 2 == 0);
    std::vector<CellPoint> cp;
    for (const auto& v : p) cp.push_back({v[0], v[1]});
    std::vector<CellOffset> cells;
    rasterizePolygon(cp, cells);
    uniqueCells(cells);
    ASSERT_EQ(asSet(cells), bruteForce(p, kRasterEpsilon)) << "polygon " << k;
  }
}

TEST(FootprintTest, SegmentTouchingCornersMarksAllNeighbours) {
  std::vector<CellOffset> cells;
  rasterizeSegment({0.5, 0.5}, {1.5, 1.5}, cells);  // through the corner (1, 1)
  uniqueCells(cells);
  EXPECT_EQ(asSet(cells), (std::set<std::pair<int, int>>{{0, 0}, {0, 1}, {1, 0}, {1, 1}}));
  cells.clear();
  rasterizeSegment({0.5, 0.5}, {2.5, 1.5}, cells);  // a knight move: through (1.5, 1.0)
  uniqueCells(cells);
  EXPECT_EQ(asSet(cells), (std::set<std::pair<int, int>>{{0, 0}, {1, 0}, {1, 1}, {2, 1}}));
}

TEST(FootprintTest, RobotFromConfig) {
  LatticeConfig c;
  c.robot.footprint = test::rectangle(0.3, 0.2);
  const RobotFootprint r = RobotFootprint::fromConfig(c);
  EXPECT_NEAR(r.inscribed_radius, 0.2, 1e-12);
  EXPECT_NEAR(r.circumscribed_radius, std::hypot(0.3, 0.2), 1e-12);
  c.robot.footprint.clear();
  c.robot.radius = 0.25;
  const RobotFootprint round = RobotFootprint::fromConfig(c);
  EXPECT_EQ(round.polygon.size(), 16u);
  for (std::size_t k = 0; k < round.polygon.size(); ++k) {  // the 16-gon contains the circle
    const auto& a = round.polygon[k];
    const auto& b = round.polygon[(k + 1) % round.polygon.size()];
    const double dist = std::fabs(a[0] * b[1] - a[1] * b[0]) / std::hypot(b[0] - a[0], b[1] - a[1]);
    EXPECT_GE(dist, 0.25 * (1 - 1e-12));
  }
  EXPECT_NEAR(round.inscribed_radius, 0.25, 1e-12);
  c.robot.radius = 0.0;
  EXPECT_TRUE(RobotFootprint::fromConfig(c).polygon.empty());
  c.robot.radius = -1.0;
  EXPECT_THROW(RobotFootprint::fromConfig(c), LatticeError);
  c.robot.footprint = {{0, 0}, {1, 0}};
  EXPECT_THROW(RobotFootprint::fromConfig(c), LatticeError);
  c.robot.footprint = {{0, 0}, {2, 1}, {2, 0}, {0, 2}};  // a bow tie
  try {
    RobotFootprint::fromConfig(c);
    ADD_FAILURE();
  } catch (const LatticeError& e) {
    EXPECT_EQ(e.kind(), LatticeError::Kind::kRobot);
    EXPECT_NE(std::string(e.what()).find("self-intersecting"), std::string::npos);
  }
  c.robot.footprint = {{0, 0}, {1, 0}, {2, 0}};
  EXPECT_THROW(RobotFootprint::fromConfig(c), LatticeError);  // zero area
}

// For every heading, the cells under the footprint at rest equal a brute-force rasterisation;
// along every primitive the swept cells contain every cell the footprint touches at very dense
// poses, and stay within the footprint grown by a third of a cell.
void checkSweeps(const PrimitiveSet& set, const Poly& footprint) {
  LatticeConfig c;
  c.robot.footprint = footprint;
  const RobotFootprint f = RobotFootprint::fromConfig(c);
  const double res = set.resolution;
  for (int h = 0; h < set.num_headings; ++h) {
    const Pose2D rest{0.0, 0.0, set.heading_angles[h]};
    Poly poly;
    for (const auto& v : f.at(rest)) poly.push_back({v[0] / res + 0.5, v[1] / res + 0.5});
    auto expected = bruteForce(poly, kRasterEpsilon);
    expected.insert({0, 0});
    ASSERT_EQ(asSet(footprintCells(f, rest, res)), expected) << "heading " << h;
  }
  for (const MotionPrimitive& p : set.primitives) {
    const PrimitiveCells cells = primitiveCells(f, p.poses, res);
    const auto swept = asSet(cells.swept);
    std::set<std::pair<int, int>> dense, grown;
    for (std::size_t k = 0; k + 1 < std::max<std::size_t>(p.poses.size(), 2); ++k) {
      const Pose2D& a = p.poses[k];
      const Pose2D& b = p.poses[std::min(k + 1, p.poses.size() - 1)];
      const double dth = std::remainder(b.theta - a.theta, 2 * M_PI);
      for (int s = 0; s <= 60; ++s) {
        const double t = s / 60.0;
        const Pose2D q{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.theta + t * dth};
        Poly poly;
        for (const auto& v : f.at(q)) poly.push_back({v[0] / res + 0.5, v[1] / res + 0.5});
        for (const auto& c2 : bruteForce(poly, 0.0)) dense.insert(c2);
        for (const auto& c2 : bruteForce(poly, 0.34)) grown.insert(c2);
      }
    }
    for (const auto& c2 : dense) {
      ASSERT_TRUE(swept.count(c2)) << "heading " << p.start_heading << " prim " << p.id
                                   << " misses (" << c2.first << ", " << c2.second << ")";
    }
    for (const auto& c2 : swept) {
      ASSERT_TRUE(grown.count(c2)) << "heading " << p.start_heading << " prim " << p.id
                                   << " sweeps (" << c2.first << ", " << c2.second << ") too far";
    }
  }
}

TEST(FootprintTest, SweepsOfSharedPrimitives) {
  AMHA_REQUIRE_SHARED_DATA(data);
  checkSweeps(readMprimFile(data + "/sbpl/pr2.mprim"), test::rectangle(0.11, 0.07));
  checkSweeps(readMprimFile(data + "/sbpl/pr2_10cm.mprim"),
              {{-0.32, -0.33}, {0.35, -0.3}, {0.36, 0.31}, {-0.3, 0.33}, {-0.4, 0.0}});
}

TEST(FootprintTest, SweepsOfGeneratedPrimitives) {
  PrimitiveGeneratorOptions o;
  o.resolution = 0.1;
  o.num_headings = 16;
  o.turning_radius = 0.35;
  o.allow_reverse = true;
  checkSweeps(generatePrimitives(o), test::rectangle(0.27, 0.18));
}

}  // namespace
}  // namespace lattice
}  // namespace amha
