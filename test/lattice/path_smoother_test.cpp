// PathSmoother: Dubins paths reach their ends; the shortcut test is the lattice's own (equal to
// edgeCost on every primitive); smoothed paths of every algorithm on random maps, robots and
// motion models pass the independent validator, keep start and goal, never cost more, bend no
// tighter than the turning radius and keep headings continuous while driving.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/dubins_path.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/map_loaders.h"
#include "amha_planner/lattice/path_smoother.h"
#include "path_validator.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

double stepCurvature(const Pose2D& a, const Pose2D& b) {
  const double chord = std::hypot(b.x - a.x, b.y - a.y);
  return 2.0 * std::sin(0.5 * std::fabs(std::remainder(b.theta - a.theta, 2.0 * M_PI))) / chord;
}

TEST(DubinsPathTest, ReachesTheGoalWithinTheCurvatureBound) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-4.0, 4.0), a(-M_PI, M_PI), r(0.2, 2.0);
  std::vector<Pose2D> samples;
  int ccc = 0;
  for (int k = 0; k < 3000; ++k) {
    // Every fifth pair close together, where the CCC words win.
    const double scale = k % 5 == 0 ? 0.3 : 1.0;
    const Pose2D from{u(rng), u(rng), a(rng)},
        to{from.x + scale * u(rng), from.y + scale * u(rng), a(rng)};
    const double radius = r(rng);
    const DubinsPath p = shortestDubinsPath(from, to, radius);
    ccc += p.turn[1] != 0;
    const Pose2D end = p.at(p.totalLength());
    ASSERT_NEAR(end.x, to.x, 1e-6 * radius + 1e-9) << k;
    ASSERT_NEAR(end.y, to.y, 1e-6 * radius + 1e-9) << k;
    ASSERT_NEAR(std::remainder(end.theta - to.theta, 2.0 * M_PI), 0.0, 1e-6) << k;
    ASSERT_GE(p.totalLength() + 1e-9, std::hypot(to.x - from.x, to.y - from.y)) << k;
    // No word of the six is longer than going round: a circle plus the distance plus a circle.
    ASSERT_LE(p.totalLength(),
              std::hypot(to.x - from.x, to.y - from.y) + 4.0 * M_PI * radius + 1e-9)
        << k;
    sampleDubinsPath(p, 0.05, samples);
    ASSERT_GE(samples.size(), 2u);
    for (std::size_t i = 1; i < samples.size(); ++i) {
      ASSERT_LE(std::hypot(samples[i].x - samples[i - 1].x, samples[i].y - samples[i - 1].y),
                0.05 + 1e-9);
      ASSERT_LE(stepCurvature(samples[i - 1], samples[i]), (1.0 + 1e-9) / radius)
          << k << " step " << i;
    }
  }
  EXPECT_GT(ccc, 50) << "the random pairs should exercise the CCC words";
}

TEST(DubinsPathTest, StraightAheadIsAStraightLine) {
  // Rounding must not turn "no turn" into a full circle.
  for (double th : {0.0, 0.4636476090008061, M_PI / 4, 2.0344439357957027, -2.0344439357957027}) {
    const Pose2D from{0.1, 0.2, th}, to{0.1 + 3.0 * std::cos(th), 0.2 + 3.0 * std::sin(th), th};
    const DubinsPath p = shortestDubinsPath(from, to, 0.5);
    EXPECT_NEAR(p.totalLength(), 3.0, 1e-9) << th;
  }
}

struct Model {
  std::string name;
  LatticeConfig config;
};

std::vector<Model> models() {
  std::vector<Model> out;
  LatticeConfig c;
  c.heuristics.num_inadmissible = 2;
  c.motion.turning_radius = 0.4;
  c.robot.radius = 0.15;
  out.push_back({"round", c});
  c.robot.radius = 0.0;
  out.push_back({"point", c});
  c.robot.footprint = test::rectangle(0.3, 0.15);
  c.motion.allow_reverse = true;
  c.motion.turning_radius = 0.3;
  out.push_back({"rectangle with reverse", c});
  c.robot.footprint = {{0.35, 0.0}, {-0.2, 0.2}, {-0.1, 0.0}, {-0.2, -0.2}};  // concave arrow
  c.motion.turn_in_place = false;
  c.cost.penalty = 3.0;
  out.push_back({"arrow, no turn in place", c});
  c.robot.footprint = test::rectangle(0.2, 0.1);
  c.motion.allow_reverse = false;
  c.motion.turn_in_place = true;
  c.motion.num_headings = 8;
  c.motion.turning_radius = 0.25;
  out.push_back({"8 headings", c});
  return out;
}

/// Checks one smoothed path against its lattice path; returns "" or what is wrong.
/// Curvature and heading continuity are checked on shortcuts, and on kept motions too when
/// `kept_too` (generated primitives: exact arcs and lines; a file's poses are its own, rounded).
std::string checkSmoothed(const LatticeGraph& g, const PathSmoother& smoother,
                          const std::vector<Pose2D>& raw, Cost raw_cost, const SmoothedPath& s,
                          bool kept_too = true) {
  if (s.poses.front().x != raw.front().x || s.poses.front().y != raw.front().y ||
      s.poses.front().theta != raw.front().theta) {
    return "start pose changed";
  }
  if (s.poses.back().x != raw.back().x || s.poses.back().y != raw.back().y ||
      s.poses.back().theta != raw.back().theta) {
    return "goal pose changed";
  }
  // The same poses may be cheaper as other motions (short straight moves instead of a long one
  // whose worst cell is costlier): never costlier.
  if (s.lattice_cost > raw_cost)
    return "lattice cost " + std::to_string(s.lattice_cost) + " > the search's " +
           std::to_string(raw_cost);
  if (s.cost > s.lattice_cost) return "costs more than the lattice path";
  const std::string v = test::validateSmoothedPath(test::modelFor(g), s, longestPrimitiveLength(g));
  if (!v.empty()) return v;
  const double kmax = 1.0 / smoother.turningRadius();
  for (const SmoothedPiece& p : s.pieces) {
    if (!p.shortcut && !kept_too) continue;
    for (std::size_t k = p.first; k < p.last; ++k) {
      const Pose2D& a = s.poses[k];
      const Pose2D& b = s.poses[k + 1];
      const double chord = std::hypot(b.x - a.x, b.y - a.y);
      if (chord < 1e-12) {
        if (p.shortcut) return "a shortcut turns in place";
        continue;  // the model's own turn in place
      }
      // Kept motions bend no tighter either: the radius is the tightest of the model's.
      if (stepCurvature(a, b) > kmax * (1.0 + 1e-6)) {
        std::string d;
        for (std::size_t q = (k > 3 ? k - 3 : 0); q < std::min(s.poses.size(), k + 4); ++q) {
          char buf[200];
          std::snprintf(buf, sizeof buf, "\n  %zu: %.6f %.6f %.6f", q, s.poses[q].x, s.poses[q].y,
                        s.poses[q].theta);
          d += buf;
        }
        char buf[200];
        std::snprintf(buf, sizeof buf, "\n piece [%zu,%zu] shortcut %d backward %d", p.first,
                      p.last, p.shortcut, p.backward);
        return "curvature " + std::to_string(stepCurvature(a, b)) + " at pose " +
               std::to_string(k) + d + buf;
      }
      // Heading continuous along the motion: the direction of each step differs from the
      // heading at either end by no more than the curvature bound lets it turn within the step
      // (a step across an inflection may leave the range between its two headings).
      const double along = std::atan2(b.y - a.y, b.x - a.x) + (p.backward ? M_PI : 0.0);
      const double off_a = std::fabs(std::remainder(along - a.theta, 2.0 * M_PI));
      const double off_b = std::fabs(std::remainder(along - b.theta, 2.0 * M_PI));
      if (std::max(off_a, off_b) > 1.01 * kmax * chord + 1e-6) {
        return "step " + std::to_string(k) + " does not run along its headings (" +
               (p.shortcut ? "shortcut" : "kept") + ")";
      }
    }
  }
  return "";
}

TEST(PathSmootherTest, ShortcutTestIsTheLatticeEdgeTest) {
  // Every primitive's own poses, tested and costed as a shortcut, give edgeCost: same cells,
  // same skips by clearance, same formula.
  int compared = 0, invalid = 0;
  for (const Model& model : models()) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
      auto map = test::randomMap(50, 45, 0.05, seed, 12, seed % 2 ? 200 : 0);
      const LatticeGraph g(map, model.config);
      const PathSmoother smoother(g);
      std::mt19937 rng(seed);
      for (int k = 0; k < 60; ++k) {
        const int x = static_cast<int>(rng() % g.width()), y = static_cast<int>(rng() % g.height());
        const int h = static_cast<int>(rng() % g.numHeadings());
        if (!g.stateValid(x, y, h)) continue;
        for (const LatticeAction* a = g.actionsBegin(h); a != g.actionsEnd(h); ++a) {
          const MotionPrimitive& p = g.primitives().primitives[a->primitive];
          const Cost expected = g.edgeCost(x, y, *a);
          ASSERT_EQ(smoother.motionCost(x, y, p.poses, p.cost_multiplier), expected)
              << model.name << " seed " << seed << " state " << x << "," << y << "," << h
              << " primitive " << a->primitive;
          ++compared;
          invalid += expected == kInvalidEdge;
        }
      }
    }
  }
  EXPECT_GT(compared, 2000);
  EXPECT_GT(invalid, 100) << "the states should include collisions";
  std::printf("%d state-primitive pairs compared, %d of them colliding\n", compared, invalid);
}

TEST(PathSmootherTest, RandomMapsRobotsAndAlgorithmsKeepEveryGuarantee) {
  const Algorithm algorithms[] = {Algorithm::kAStar, Algorithm::kWeightedAStar,
                                  Algorithm::kAmhaStar, Algorithm::kAraStar};
  int paths = 0, shortened = 0, shortcuts = 0;
  for (const Model& model : models()) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
      auto map = test::randomMap(70, 60, 0.05, 100 + seed, 10, seed % 3 == 0 ? 150 : 0);
      map->origin_x = -1.3 * seed;
      map->origin_y = 0.7;
      map->origin_yaw = seed % 2 ? 0.3 : 0.0;
      LatticePlanner planner(map, model.config);
      const LatticeGraph& g = planner.graph();
      const PathSmoother smoother(g);
      std::mt19937 rng(seed);
      for (int q = 0, found = 0; q < 40 && found < 3; ++q) {
        const int sx = static_cast<int>(rng() % g.width()),
                  sy = static_cast<int>(rng() % g.height());
        const int gx = static_cast<int>(rng() % g.width()),
                  gy = static_cast<int>(rng() % g.height());
        const int sh = static_cast<int>(rng() % g.numHeadings()),
                  gh = static_cast<int>(rng() % g.numHeadings());
        if (!g.stateValid(sx, sy, sh) || !g.stateValid(gx, gy, gh) ||
            std::hypot(gx - sx, gy - sy) < 20)
          continue;
        PlannerConfig pc = defaultConfig(algorithms[(seed + q) % 4]);
        SearchLimits limits;
        limits.time_limit_s = 2.0;
        const PlanResult r =
            planner.plan(g.stateToPose(sx, sy, sh), g.stateToPose(gx, gy, gh), pc, limits);
        if (r.solutions.empty()) continue;
        ++found;
        for (const LatticeSolution& sol : r.solutions) {
          const SmoothedPath s = smoother.smooth(sol.poses);
          const std::string why = checkSmoothed(g, smoother, sol.poses, sol.search.cost, s);
          ASSERT_EQ(why, "") << model.name << " seed " << seed << " query " << q << " "
                             << algorithmName(pc.algorithm);
          ++paths;
          shortened += s.cost < s.lattice_cost;
          shortcuts += static_cast<int>(s.shortcuts);
          const LatticeSolution as_solution = smoothedSolution(sol, s);
          EXPECT_EQ(as_solution.search.cost, s.cost);
          EXPECT_GE(as_solution.search.certified_bound, 1.0);
          EXPECT_LE(as_solution.search.certified_bound, sol.search.certified_bound + 1e-12);
        }
      }
    }
  }
  EXPECT_GT(paths, 60);
  EXPECT_GT(shortened, paths / 2) << "smoothing should usually shorten a lattice path";
  EXPECT_GT(shortcuts, paths);
}

TEST(PathSmootherTest, StreamPublishesNoCostlierPathAndValidBounds) {
  // Anytime runs: the published cost and certified bound never rise, the bounds hold for the
  // published path (cost <= lattice cost of the same solution), a republished path is the
  // previous one, and a repeated lattice path is not smoothed again.
  int steps = 0, republished = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    auto map = test::randomMap(80, 70, 0.05, 300 + seed, 14, seed % 2 ? 120 : 0);
    LatticeConfig c;
    c.motion.turning_radius = 0.3;
    c.robot.radius = 0.1;
    LatticePlanner planner(map, c);
    const LatticeGraph& g = planner.graph();
    const PathSmoother smoother(g);
    std::mt19937 rng(seed);
    for (int q = 0; q < 30; ++q) {
      const int sx = static_cast<int>(rng() % g.width()), sy = static_cast<int>(rng() % g.height());
      const int gx = static_cast<int>(rng() % g.width()), gy = static_cast<int>(rng() % g.height());
      if (!g.stateValid(sx, sy, 0) || !g.stateValid(gx, gy, 4) || std::hypot(gx - sx, gy - sy) < 30)
        continue;
      SearchLimits limits;
      limits.time_limit_s = 2.0;
      const Algorithm alg = seed % 3 == 0 ? Algorithm::kAraStar : Algorithm::kAmhaStar;
      const PlanResult r = planner.plan(g.stateToPose(sx, sy, 0), g.stateToPose(gx, gy, 4),
                                        defaultConfig(alg), limits);
      SmoothedStream stream(smoother);
      const LatticeSolution* previous = nullptr;
      LatticeSolution last;
      for (const LatticeSolution& sol : r.solutions) {
        const SmoothedStream::Step& step = stream.add(sol);
        const LatticeSolution& p = step.published;
        ++steps;
        EXPECT_LE(p.search.cost, sol.search.cost);
        EXPECT_EQ(p.search.nominal_bound, sol.search.nominal_bound);
        EXPECT_GE(p.search.certified_bound, 1.0);
        EXPECT_LE(p.search.certified_bound, p.search.nominal_bound);
        EXPECT_EQ(p.poses.front().x, sol.poses.front().x);
        EXPECT_EQ(p.poses.back().y, sol.poses.back().y);
        if (step.republished) {
          ++republished;
          EXPECT_LT(p.search.cost, step.smoothed.cost);
          EXPECT_TRUE(step.same_as_previous);
        } else {
          EXPECT_EQ(p.search.cost, step.smoothed.cost);
        }
        if (previous != nullptr) {
          EXPECT_LE(p.search.cost, last.search.cost);
          EXPECT_LE(p.search.certified_bound, last.search.certified_bound);
          if (step.same_as_previous) {
            EXPECT_EQ(p.poses.size(), last.poses.size());
          }
          if (previous->search.path == sol.search.path) {
            EXPECT_TRUE(step.same_as_previous);
            EXPECT_EQ(p.search.cost, last.search.cost);
          }
        }
        previous = &sol;
        last = p;
      }
    }
  }
  EXPECT_GT(steps, 100);
  std::printf("%d streamed solutions, %d republished an earlier smoothed path\n", steps,
              republished);
}

/// The poses of the motions `primitives` (indices) driven one after the other from (x, y, h).
std::vector<Pose2D> posesOf(const LatticeGraph& g, int x, int y, int h,
                            const std::vector<int>& primitives) {
  std::vector<Pose2D> poses{g.stateToPose(x, y, h)};
  for (int i : primitives) {
    const MotionPrimitive& p = g.primitives().primitives[i];
    EXPECT_EQ(p.start_heading, h);
    for (std::size_t k = 1; k < p.poses.size(); ++k)
      poses.push_back(g.cellPoseToMap(x, y, p.poses[k]));
    x += p.end_dx;
    y += p.end_dy;
    h = p.end_heading;
  }
  return poses;
}

/// The primitive from heading h to heading e that moves (or turns in place).
int primitiveOf(const LatticeGraph& g, int h, int e, bool moves, int dx = 0) {
  const auto range = g.primitives().range(h);
  for (std::size_t i = range.first; i < range.second; ++i) {
    const MotionPrimitive& p = g.primitives().primitives[i];
    if (p.end_heading == e && (p.end_dx != 0 || p.end_dy != 0) == moves &&
        (dx == 0 || p.end_dx == dx))
      return static_cast<int>(i);
  }
  ADD_FAILURE() << "no primitive " << h << " -> " << e;
  return 0;
}

TEST(PathSmootherTest, StreamRepublishesAnEarlierSmoothedPathThatCostsLess) {
  // Solution 1 zig-zags (costly, but smooths into the straight line); solution 2 is cheaper as a
  // lattice path but turns on the spot first, which smoothing keeps: its smoothed path costs
  // more than solution 1's, so solution 1's is sent again, with solution 2's bounds.
  auto map = test::randomMap(120, 40, 0.05, 1, 0, 0);
  LatticeConfig c;
  c.motion.turning_radius = 0.3;
  c.robot.radius = 0.1;
  c.cost.time_to_turn_45 = 0.1;  // quick turns on the spot
  const LatticeGraph g(map, c);
  const PathSmoother smoother(g);
  const int n = g.numHeadings();
  std::vector<int> zigzag;
  for (int k = 0; k < 6; ++k) {
    for (int side : {1, n - 1}) {  // left and back, right and back
      zigzag.push_back(primitiveOf(g, 0, side, true));
      zigzag.push_back(primitiveOf(g, side, 0, true));
    }
  }
  std::vector<Pose2D> p1 = posesOf(g, 5, 20, 0, zigzag);
  int gx = 0, gy = 0, gh = 0;
  ASSERT_TRUE(g.poseToState(p1.back(), &gx, &gy, &gh));
  ASSERT_EQ(gy, 20);
  ASSERT_EQ(gh, 0);
  std::vector<int> tip_then_straight = {primitiveOf(g, 0, 1, false), primitiveOf(g, 1, 0, false)};
  for (int x = 5; x < gx; ++x) tip_then_straight.push_back(primitiveOf(g, 0, 0, true, 1));
  const std::vector<Pose2D> p2 = posesOf(g, 5, 20, 0, tip_then_straight);
  const SmoothedPath s1 = smoother.smooth(p1), s2 = smoother.smooth(p2);
  ASSERT_LT(s2.lattice_cost, s1.lattice_cost)
      << "the setting needs solution 2 cheaper as a lattice path";
  ASSERT_LT(s1.cost, s2.cost) << "and solution 1 cheaper smoothed";

  LatticeSolution a, b;
  a.poses = p1;
  a.search.path = {1};
  a.search.cost = s1.lattice_cost;
  a.search.nominal_bound = 3.0;
  a.search.certified_bound = 2.0;
  b.poses = p2;
  b.search.path = {2};
  b.search.cost = s2.lattice_cost;
  b.search.nominal_bound = 1.5;
  b.search.certified_bound = 1.2;
  SmoothedStream stream(smoother);
  const double first_certified = stream.add(a).published.search.certified_bound;
  const SmoothedStream::Step& step = stream.add(b);
  EXPECT_TRUE(step.republished);
  EXPECT_TRUE(step.same_as_previous);
  EXPECT_EQ(step.published.search.cost, s1.cost);
  EXPECT_EQ(step.smoothed.cost, s2.cost);
  ASSERT_EQ(step.published.poses.size(), s1.poses.size());
  EXPECT_EQ(step.published.search.nominal_bound, 1.5);
  // cost_1' <= cost_2' <= cost_2 <= 1.2 x optimum, so 1.2 x cost_1' / cost_2 bounds it.
  EXPECT_NEAR(step.published.search.certified_bound,
              std::min(first_certified, std::max(1.0, 1.2 * static_cast<double>(s1.cost) /
                                                          static_cast<double>(s2.lattice_cost))),
              1e-12);
}

TEST(PathSmootherTest, SmoothsTheBundledMapWithinTheGuarantees) {
  // Long paths on the Willow Garage map (the demo's), a round robot.
  AMHA_REQUIRE_SHARED_DATA(data);
  LatticeConfig c;
  c.robot.radius = 0.2;
  c.motion.turning_radius = 0.5;
  OccupancyConversion conv;
  auto map = std::make_shared<GridMap>(
      loadMapServerMap(data + "/maps/ros/willow_garage/willow-2010-02-18-0.10.yaml", conv));
  LatticePlanner planner(map, c);
  const PathSmoother smoother(planner.graph());
  const Pose2D queries[][2] = {{{17, 55, 0}, {26, 6, 1.57}}, {{5.2, 21.6, 1.57}, {40, 40, 0}}};
  for (const auto& q : queries) {
    SearchLimits limits;
    limits.time_limit_s = 10.0;
    const PlanResult r = planner.plan(q[0], q[1], defaultConfig(Algorithm::kWeightedAStar), limits);
    ASSERT_FALSE(r.solutions.empty());
    const LatticeSolution& sol = r.solutions.back();
    const SmoothedPath s = smoother.smooth(sol.poses);
    EXPECT_EQ(checkSmoothed(planner.graph(), smoother, sol.poses, sol.search.cost, s), "");
    EXPECT_LT(s.cost, s.lattice_cost);
  }
}

TEST(PathSmootherTest, SbplPrimitiveFilesKeepEveryGuarantee) {
  // pr2.mprim: SBPL's primitives (poses rounded to 0.1 mm, so motions end near, not at, cell
  // centres; backward motions; turns in place), a square robot, random maps with costs.
  AMHA_REQUIRE_SHARED_DATA(data);
  LatticeConfig c;
  c.motion.mprim_file = data + "/sbpl/pr2.mprim";
  c.robot.footprint = test::rectangle(0.15, 0.1);
  c.cost.penalty = 2.0;
  int paths = 0, shortened = 0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    auto map = test::randomMap(140, 120, 0.025, 500 + seed, 12, seed % 2 ? 100 : 0);
    LatticePlanner planner(map, c);
    // Before the timed queries, as `amha plan` does: a slice of these primitives' kinematic
    // table (15 m at 2.5 cm) takes about the queries' whole 2 s budget on a loaded machine.
    planner.prepareKinematicTables();
    const LatticeGraph& g = planner.graph();
    const PathSmoother smoother(g);
    std::mt19937 rng(seed);
    for (int q = 0, found = 0; q < 40 && found < 3; ++q) {
      const int sx = static_cast<int>(rng() % g.width()), sy = static_cast<int>(rng() % g.height());
      const int gx = static_cast<int>(rng() % g.width()), gy = static_cast<int>(rng() % g.height());
      const int sh = static_cast<int>(rng() % g.numHeadings()),
                gh = static_cast<int>(rng() % g.numHeadings());
      if (!g.stateValid(sx, sy, sh) || !g.stateValid(gx, gy, gh) ||
          std::hypot(gx - sx, gy - sy) < 40)
        continue;
      SearchLimits limits;
      limits.time_limit_s = 2.0;
      const PlanResult r = planner.plan(g.stateToPose(sx, sy, sh), g.stateToPose(gx, gy, gh),
                                        defaultConfig(Algorithm::kAmhaStar), limits);
      if (r.solutions.empty()) continue;
      ++found;
      for (const LatticeSolution& sol : r.solutions) {
        const SmoothedPath s = smoother.smooth(sol.poses);
        ASSERT_EQ(checkSmoothed(g, smoother, sol.poses, sol.search.cost, s, false), "")
            << "seed " << seed << " query " << q;
        ++paths;
        shortened += s.cost < s.lattice_cost;
      }
    }
  }
  EXPECT_GT(paths, 15);
  EXPECT_GT(shortened, paths / 2);
}

TEST(PathSmootherTest, RefusesWhatIsNotALatticePath) {
  auto map = test::randomMap(40, 40, 0.05, 5, 0, 0);
  LatticeConfig c;
  c.motion.turning_radius = 0.3;
  const LatticeGraph g(map, c);
  const PathSmoother smoother(g);
  std::vector<Pose2D> path = {g.stateToPose(10, 10, 0)};
  EXPECT_EQ(smoother.smooth(path).poses.size(), 1u);  // start = goal: nothing to smooth
  path.push_back(g.stateToPose(12, 10, 0));           // a jump, not a motion's poses
  EXPECT_THROW(smoother.smooth(path), std::invalid_argument);
  path = {{0.51, 0.52, 0.0}, {0.6, 0.52, 0.0}};  // not at a cell centre
  EXPECT_THROW(smoother.smooth(path), std::invalid_argument);
  SmootherOptions o;
  o.turning_radius = 0.1;  // tighter than the model's 0.3 m
  EXPECT_THROW(PathSmoother(g, o), std::invalid_argument);
}

}  // namespace
}  // namespace lattice
}  // namespace amha
