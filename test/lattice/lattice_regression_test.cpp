// Regression tests for what fuzzing found in the lattice domain (test/fuzz/*_fuzzer.cpp; each
// crashing or hanging input is also kept in test/fuzz/corpus/<target>/regression-*).
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/map_loaders.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

using Clock = std::chrono::steady_clock;

// Two headings, a straight primitive each; `middle` are `n_middle` extra intermediate poses of
// the first.
std::string twoHeadings(const std::string& middle, int n_middle = 1,
                        const std::string& res = "0.025") {
  return "resolution_m: " + res +
         "\nnumberofangles: 2\ntotalnumberofprimitives: 2\n"
         "primID: 0\nstartangle_c: 0\nendpose_c: 1 0 0\nadditionalactioncostmult: "
         "1\nintermediateposes: " +
         std::to_string(2 + n_middle) +
         "\n"
         "0 0 0\n" +
         middle + "\n" + res +
         " 0 0\n"
         "primID: 0\nstartangle_c: 1\nendpose_c: -1 0 1\nadditionalactioncostmult: "
         "1\nintermediateposes: 2\n"
         "0 0 3.14159\n-" +
         res + " 0 3.14159\n";
}

std::string mprimError(const std::string& text) {
  std::istringstream in(text);
  try {
    readMprim(in, "r.mprim");
  } catch (const LatticeError& e) {
    return e.what();
  }
  return "(no error)";
}

// mprim fuzzer, regression-long-detour: an intermediate pose 303 m (12000 cells) away from a
// one-cell primitive was accepted, and building the planner then took minutes (the anchor's
// walk over the primitive's cells was quadratic). Such primitives are now refused, and the
// walk is a heap-based Dijkstra.
TEST(MprimRegression, IntermediatePosesFarAwayAreRefused) {
  EXPECT_NE(mprimError(twoHeadings("0.0125 303.08 0"))
                .find("r.mprim:11: primID 0 (start heading 0): its intermediate poses are"),
            std::string::npos);
  EXPECT_NE(mprimError(twoHeadings("0.0125 303.08 0")).find("cells long (at most 1000)"),
            std::string::npos);
  // mprim fuzzer, regression-long-detour-2: a 180 m detour (7200 cells) was still allowed by a
  // first limit of 10000 cells, and its footprint sweep took over 10 s under the sanitizers.
  EXPECT_NE(mprimError(twoHeadings("0.0722 90.050 0")).find("cells long (at most 1000)"),
            std::string::npos);
  EXPECT_NE(mprimError(twoHeadings("1e300 -1e300 0")).find("cells long"), std::string::npos);
  EXPECT_EQ(mprimError(twoHeadings("0.0125 0 0")), "(no error)");
  // A first pose far outside int range (in cells) is refused, not undefined behaviour.
  EXPECT_NE(
      mprimError("resolution_m: 1e-300\nnumberofangles: 1\ntotalnumberofprimitives: 1\nprimID: "
                 "0\nstartangle_c: 0\n"
                 "endpose_c: 0 0 0\nadditionalactioncostmult: 1\nintermediateposes: 1\n1 0 0\n")
          .find("is not in the start cell"),
      std::string::npos);
}

TEST(MprimRegression, LongPrimitivesStillBuildQuickly) {
  // An 800-cell detour (allowed) on a small map: the planner builds in well under a second.
  const std::string dir = test::tempDir();
  const std::string path = dir + "/long.mprim";
  {
    std::ofstream f(path);
    f << twoHeadings("0.0125 5 0\n0.0125 -5 0\n0.0125 0 0", 3);
  }
  auto map = test::randomMap(24, 20, 0.025, 1, 0, 0);
  LatticeConfig c;
  c.motion.mprim_file = path;
  c.robot.radius = 0.02;
  const auto t0 = Clock::now();
  LatticePlanner planner(map, c);
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  EXPECT_LT(s, 1.0);
  // The long primitive never fits the map; the other moves still plan.
  SearchLimits limits;
  limits.max_expansions = 1000;
  const PlanResult r = planner.plan({0.2, 0.2, 3.14159}, {0.1, 0.2, 3.14159},
                                    defaultConfig(Algorithm::kAStar), limits);
  EXPECT_EQ(r.error, QueryError::kNone) << r.message;
  EXPECT_FALSE(r.solutions.empty());
}

TEST(MprimRegression, WalkLengthOnThousandsOfCells) {
  std::vector<CellOffset> cells;
  for (int x = 0; x <= 20000; ++x) cells.push_back({x, x / 3});
  for (int x = 0; x <= 20000; ++x) cells.push_back({x, x / 3 + 1});
  const auto t0 = Clock::now();
  const double w = walkLength(cells, CellOffset{20000, 6666}, gridMoves(8));
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 2.0);
  EXPECT_NEAR(w, 6666 * std::sqrt(2.0) + (20000 - 6666), 1e-6);
}

// map_server fuzzer, regression-huge-pgm-header: a PGM header claiming 70000 x 70000 pixels
// made OpenCV throw cv::Exception (its own pixel limit) out of loadMapServerMap, which
// promises LatticeError. Now PNG and PNM headers are read first, so an image with more cells
// than a map may have is refused before decoding (a small PNG can hold gigapixels), and any
// OpenCV exception becomes a LatticeError naming the file.
TEST(MapServerRegression, HugeImagesAreRefusedBeforeDecoding) {
  const std::string dir = test::tempDir();
  auto load = [&](const std::string& image_bytes) {
    std::ofstream(dir + "/m.img", std::ios::binary) << image_bytes;
    std::ofstream(dir + "/m.yaml")
        << "image: m.img\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
           "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
    try {
      loadMapServerMap(dir + "/m.yaml");
    } catch (const LatticeError& e) {
      EXPECT_EQ(e.kind(), LatticeError::Kind::kMap);
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const auto t0 = Clock::now();
  EXPECT_NE(load("P5\n70000 70000\n255\n")
                .find("m.img: the image is 70000 x 70000 pixels, more than the 67108864 cells"),
            std::string::npos);
  EXPECT_NE(load("P5 # comment\n8193\n8193 255\n").find("8193 x 8193 pixels"), std::string::npos);
  EXPECT_NE(load("P2\n99999999999999999999 2\n255\n").find("4294967296 x 2 pixels"),
            std::string::npos);
  std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\x01\x86\xa0\0\x01\x86\xa0\x08\0\0\0\0", 29);
  EXPECT_NE(load(png).find("100000 x 100000 pixels"), std::string::npos);
  // BMP: not pre-checked; OpenCV refuses it, and its exception becomes a LatticeError.
  auto le32 = [](std::uint32_t v) {
    return std::string{char(v), char(v >> 8), char(v >> 16), char(v >> 24)};
  };
  const std::string bmp = "BM" + le32(54) + le32(0) + le32(54) + le32(40) + le32(70000) +
                          le32(70000) + std::string("\x01\0\x18\0", 4) + le32(0) + le32(0) +
                          le32(2835) + le32(2835) + le32(0) + le32(0);
  EXPECT_NE(load(bmp).find("m.img: cannot read the image"), std::string::npos);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 5.0);
  // A small image still loads.
  EXPECT_EQ(load("P5\n2 1\n255\n\xff\xfe"), "(no error)");
}

// occupancy fuzzer, regression-tiny-resolution: a map with 1.8e-307 m cells was accepted; the
// primitive generator and footprint sweeps then computed in cell units that overflowed to
// infinity and NaN, cast NaN to int (undefined behaviour) and looped over billions of cells.
TEST(OccupancyRegression, ResolutionsOutsideTheSaneRangeAreRefused) {
  const std::int8_t cells[4] = {0, 0, 0, 0};
  for (double res : {1.780373142182824e-307, 1e-4, 2e3, 1e300}) {
    try {
      gridMapFromOccupancy(2, 2, res, 0, 0, 0, cells, 4, OccupancyConversion());
      ADD_FAILURE() << res;
    } catch (const LatticeError& e) {
      EXPECT_NE(std::string(e.what()).find("m is outside [0.001, 1000]"), std::string::npos)
          << e.what();
    }
    auto map = test::randomMap(7, 15, 0.05, 1, 0, 0);
    map->resolution = res;
    try {
      LatticePlanner planner(map, LatticeConfig());
      ADD_FAILURE() << res;
    } catch (const LatticeError& e) {
      EXPECT_EQ(e.kind(), LatticeError::Kind::kMap);
      EXPECT_NE(std::string(e.what()).find("is outside [0.001, 1000]"), std::string::npos)
          << e.what();
    }
  }
  for (double res : {kMinResolution, kMaxResolution}) {
    EXPECT_NO_THROW(gridMapFromOccupancy(2, 2, res, 0, 0, 0, cells, 4, OccupancyConversion()));
  }
}

// The refusals of a 2 x 2 map at this origin: gridMapFromOccupancy's message ("" if it
// accepted it), and whether LatticePlanner refused a map placed there.
struct OriginRefusal {
  std::string conversion_error;
  bool planner_refused = false;
};
OriginRefusal refusalsOfOrigin(double x, double y, double yaw) {
  OriginRefusal out;
  const std::int8_t cells[4] = {0, 0, 0, 0};
  try {
    gridMapFromOccupancy(2, 2, 0.05, x, y, yaw, cells, 4, OccupancyConversion());
  } catch (const LatticeError& e) {
    out.conversion_error = e.what();
  }
  auto map = test::randomMap(16, 4, 0.05, 1, 0, 0);
  map->origin_x = x;
  map->origin_y = y;
  map->origin_yaw = yaw;
  try {
    LatticePlanner planner(map, LatticeConfig());
  } catch (const LatticeError&) {
    out.planner_refused = true;
  }
  return out;
}

// occupancy fuzzer, regression-huge-origin: a map at origin x = 2.7e161 m was accepted; a
// double cannot place cells there (the spacing of doubles near it is ~1e145 m), so every pose
// of a path came out the same and the planner refused its own cell centres as off the map.
TEST(OccupancyRegression, OriginsTooFarAwayAreRefused) {
  for (double x : {2.68e161, -1.5e8}) {
    const OriginRefusal r = refusalsOfOrigin(x, 0, 0);
    EXPECT_NE(r.conversion_error.find("is farther than 1e+08 m"), std::string::npos)
        << x << ": " << r.conversion_error;
    EXPECT_TRUE(refusalsOfOrigin(0, x, 0).planner_refused) << x;
  }
  // UTM-sized origins are fine, and poses round-trip there.
  auto map = test::randomMap(40, 40, 0.05, 1, 0, 0);
  map->origin_x = 500000.0;
  map->origin_y = 9999000.0;
  LatticeConfig c;
  c.robot.radius = 0.05;
  LatticePlanner planner(map, c);
  const Pose2D s{500000.5, 9999000.5, 0.0}, g{500001.5, 9999001.2, 1.0};
  EXPECT_EQ(planner.checkQuery(s, g, nullptr), QueryError::kNone);
  const PlanResult r = planner.plan(s, g, defaultConfig(Algorithm::kAStar), SearchLimits());
  ASSERT_FALSE(r.solutions.empty());
  EXPECT_NEAR(r.solutions.back().poses.back().x, 500001.525, 1e-6);
}

// occupancy fuzzer, regression-huge-yaw: a map turned by 4.5e279 rad was accepted; adding a
// heading to that yaw changes nothing in a double, so every pose had the same heading, a goal
// pose came back as another heading, and the facade's optimum differed from the search's.
TEST(OccupancyRegression, OriginYawsBeyondAMillionRadiansAreRefused) {
  for (double yaw : {4.538e279, -1.1e6}) {
    const OriginRefusal r = refusalsOfOrigin(0, 0, yaw);
    EXPECT_NE(r.conversion_error.find("origin yaw"), std::string::npos)
        << yaw << ": " << r.conversion_error;
    EXPECT_TRUE(r.planner_refused) << yaw;
  }
  // A yaw many turns round is still an angle: headings round-trip through poses.
  auto map = test::randomMap(20, 20, 0.05, 1, 0, 0);
  map->origin_yaw = 2.0 * M_PI * 1000.0 + 0.3;
  LatticeConfig c;
  c.robot.radius = 0.05;
  LatticePlanner planner(map, c);
  LatticeGraph g(map, c);
  for (int h = 0; h < g.numHeadings(); ++h) {
    const Pose2D p = g.stateToPose(7, 9, h);
    int x = 0, y = 0, k = 0;
    ASSERT_TRUE(g.poseToState(p, &x, &y, &k));
    EXPECT_EQ(x, 7);
    EXPECT_EQ(y, 9);
    EXPECT_EQ(k, h);
  }
}

// occupancy fuzzer, regression-nan-pose-with-goal-options: plan() with GoalOptions turned the
// poses into states before refusing a non-finite one, and a NaN heading met a float-to-int
// conversion (undefined behaviour, reported by UBSan). Every bad pose is refused first now.
TEST(OccupancyRegression, NonFinitePosesWithGoalOptionsAreRefusedBeforeUse) {
  auto map = test::randomMap(20, 20, 0.05, 1, 0, 0);
  LatticeConfig c;
  c.robot.radius = 0.05;
  LatticePlanner planner(map, c);
  GoalOptions options;
  options.tolerance = 0.3;
  options.any_heading = true;
  const Pose2D ok{0.5, 0.5, 0.0};
  const struct {
    Pose2D start, goal;
    QueryError expected;
  } cases[] = {
      {ok, {0.6, 0.6, NAN}, QueryError::kGoalNotFinite},
      {{0.5, 0.5, NAN}, ok, QueryError::kStartNotFinite},
      {ok, {INFINITY, 0.6, 0.0}, QueryError::kGoalNotFinite},
      {{-1.0, 0.5, NAN}, ok, QueryError::kStartNotFinite},
      {ok, {5.0, 0.6, 0.0}, QueryError::kGoalOutOfMap},
  };
  for (const auto& k : cases) {
    const PlanResult r =
        planner.plan(k.start, k.goal, options, defaultConfig(Algorithm::kAStar), SearchLimits());
    EXPECT_EQ(r.error, k.expected) << r.message;
    EXPECT_FALSE(r.planned_goal.has_value());
  }
}

}  // namespace
}  // namespace lattice
}  // namespace amha
