// A planner built from the previous one after a local map change (a costmap update) must be
// the planner a full build gives: the same clearance and openings in every cell, the same
// heuristic grids and coarse abstraction, so the same edge costs, heuristics and plans. Checked
// after chains of random updates (so that errors cannot pile up unseen), for round and polygonal
// robots, at the map's edges and corners.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

// The first cell where two arrays differ, or "" (a readable failure instead of a huge dump).
template <class T>
std::string firstDifference(const std::vector<T>& a, const std::vector<T>& b, int width) {
  if (a.size() != b.size()) {
    return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] != b[i]) {
      return "cell (" + std::to_string(i % width) + ", " + std::to_string(i / width) +
             "): " + std::to_string(+a[i]) + " vs " + std::to_string(+b[i]);
    }
  }
  return "";
}

// The heuristics of both for a goal: every grid, scale and the coarse abstraction's distances.
void expectSameHeuristics(const HeuristicGridBuilder& updated, const HeuristicGridBuilder& full,
                          const LatticeGraph& graph, int gx, int gy, const std::string& what) {
  if (graph.map().at(gx, gy) >= kInscribedCost) return;
  const auto a = updated.compute(gx, gy, 0, true, 1);
  const auto b = full.compute(gx, gy, 0, true, 1);
  ASSERT_TRUE(a && b) << what;
  for (int k = 0; k < kNumGridKinds; ++k) {
    ASSERT_EQ(a->grids[k] == nullptr, b->grids[k] == nullptr) << what << ": grid " << k;
    if (a->grids[k]) {
      EXPECT_EQ(
          firstDifference(a->grids[k]->distances(), b->grids[k]->distances(), graph.width() + 4),
          "")
          << what << ": grid " << k << " for goal (" << gx << ", " << gy << ")";
    }
    EXPECT_EQ(a->scale[k], b->scale[k]) << what << ": grid " << k;
  }
  EXPECT_EQ(a->coarse, b->coarse) << what << ": coarse abstraction for goal (" << gx << ", " << gy
                                  << ")";
}

void expectSameGraph(const LatticeGraph& updated, const LatticeGraph& full,
                     const std::string& what) {
  const int w = full.width();
  EXPECT_EQ(firstDifference(updated.clearance(), full.clearance(), w), "") << what << ": clearance";
  for (int k = 0; k < 2; ++k) {
    const std::vector<std::uint8_t>* u = updated.openedFree(k);
    const std::vector<std::uint8_t>* f = full.openedFree(k);
    ASSERT_EQ(u == nullptr, f == nullptr) << what << ": opening " << k;
    if (u != nullptr) {
      EXPECT_EQ(firstDifference(*u, *f, w), "") << what << ": opening " << k;
    }
  }
  EXPECT_EQ(updated.openingsEqual(), full.openingsEqual()) << what;
  EXPECT_EQ(updated.actions().size(), full.actions().size()) << what;
}

struct Robot {
  const char* name;
  LatticeConfig config;
};

// A copy of `map` with the cells of `r` (clipped to the map) set to `value`.
std::shared_ptr<GridMap> withCells(const GridMap& map, const CellRect& r, std::uint8_t value) {
  auto out = std::make_shared<GridMap>(map);
  for (int y = std::max(r.y0, 0); y < std::min(r.y1, map.height); ++y) {
    for (int x = std::max(r.x0, 0); x < std::min(r.x1, map.width); ++x) {
      out->cost[static_cast<std::size_t>(y) * map.width + x] = value;
    }
  }
  return out;
}

// The cells within `half` of the pose's cell (a square).
CellRect around(const Pose2D& p, double resolution, int half) {
  const int x = static_cast<int>(p.x / resolution), y = static_cast<int>(p.y / resolution);
  return {x - half, y - half, x + half + 1, y + half + 1};
}

std::vector<Robot> robots() {
  std::vector<Robot> out;
  LatticeConfig round;
  round.robot.radius = 0.2;  // 4 cells at 0.05 m
  out.push_back({"round robot, 3 inadmissible", round});
  LatticeConfig polygon;
  polygon.robot.footprint =
      test::rectangle(0.35, 0.15);  // openings of 3 and 7.6 cells: they differ
  out.push_back({"rectangular robot", polygon});
  LatticeConfig point;
  point.robot.radius = 0.0;
  out.push_back({"point robot", point});
  LatticeConfig one;
  one.robot.radius = 0.3;
  one.heuristics.num_inadmissible = 1;  // no openings at all
  out.push_back({"round robot, 1 inadmissible", one});
  return out;
}

TEST(LatticeIncremental, ChainsOfRandomUpdatesGiveTheFullBuildsGraph) {
  // A cluttered map, and an open one where clearances reach their cap (so that a change is
  // felt as far away as the cap).
  for (int obstacles : {18, 2})
    for (const Robot& robot : robots()) {
      std::mt19937 rng(7);
      std::shared_ptr<GridMap> map = test::randomMap(150, 110, 0.05, 3, obstacles, 40);
      auto graph = std::make_unique<LatticeGraph>(map, robot.config);
      auto builder = std::make_unique<HeuristicGridBuilder>(*graph);
      const std::uint8_t values[] = {0,           0,           17,          120, kInscribedCost,
                                     kLethalCost, kLethalCost, kUnknownCost};
      for (int step = 0; step < 24; ++step) {
        // Rectangles of 1..45 cells a side anywhere, some sticking out of the map (clipped).
        std::uniform_int_distribution<int> side(1, 45), px(-10, map->width), py(-10, map->height);
        CellRect r;
        r.x0 = px(rng);
        r.y0 = py(rng);
        r.x1 = r.x0 + side(rng);
        r.y1 = r.y0 + side(rng);
        auto next = std::make_shared<GridMap>(*map);
        std::uniform_int_distribution<int> pick(0, sizeof values - 1);
        const bool one_value = step % 3 != 0;  // a blocked or cleared area, or a random mix
        const std::uint8_t v = values[pick(rng)];
        for (int y = std::max(r.y0, 0); y < std::min(r.y1, map->height); ++y) {
          for (int x = std::max(r.x0, 0); x < std::min(r.x1, map->width); ++x) {
            next->cost[static_cast<std::size_t>(y) * map->width + x] =
                one_value ? v : values[pick(rng)];
          }
        }
        auto updated = std::make_unique<LatticeGraph>(*graph, next, r);
        auto updated_builder = std::make_unique<HeuristicGridBuilder>(*builder, *updated);
        const LatticeGraph full(next, robot.config);
        const HeuristicGridBuilder full_builder(full);
        const std::string what = std::string(robot.name) + ", " + std::to_string(obstacles) +
                                 " obstacles, update " + std::to_string(step) + " (" +
                                 std::to_string(r.x0) + ", " + std::to_string(r.y0) + ") - (" +
                                 std::to_string(r.x1) + ", " + std::to_string(r.y1) + ")";
        expectSameGraph(*updated, full, what);
        // A goal at the change; now and then one far from it.
        const int gx = std::clamp(r.x0, 0, map->width - 1),
                  gy = std::clamp(r.y0, 0, map->height - 1);
        expectSameHeuristics(*updated_builder, full_builder, full, gx, gy, what);
        if (step % 6 == 5) {
          expectSameHeuristics(*updated_builder, full_builder, full, map->width / 2,
                               map->height / 2, what);
        }
        if (HasFailure()) return;
        map = next;
        graph = std::move(updated);
        builder = std::move(updated_builder);
      }
    }
}

// One obstacle appears in open space: every cell within the clearance cap of it changes, the
// farthest ones by less than a cell (so a margin one cell short would leave them stale).
TEST(LatticeIncremental, ANewObstacleIsFeltAsFarAsTheClearanceCap) {
  auto map = test::randomMap(120, 120, 0.05, 1, 0, 0);
  LatticeConfig config;
  const LatticeGraph graph(map, config);
  const int cx = 60, cy = 60;
  auto next = std::make_shared<GridMap>(*map);
  next->cost[static_cast<std::size_t>(cy) * 120 + cx] = kLethalCost;
  const LatticeGraph updated(graph, next, CellRect{cx, cy, cx + 1, cy + 1});
  const LatticeGraph full(next, config);
  expectSameGraph(updated, full, "one obstacle");
  const float cap = full.clearanceCap();
  int ring = 0;  // cells whose distance to the obstacle lies in (cap - 1, cap)
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 120; ++x) {
      const double d = std::hypot(x - cx, y - cy);
      if (d > cap - 1 && d < cap) ++ring;
    }
  }
  EXPECT_GT(ring, 0) << "the map is too small to test the cap's reach";
}

// A clearance class answers "clearance > sweep radius" for every action: with few radii exactly,
// with more than 255 conservatively (a radius is only ever rounded up).
TEST(LatticeIncremental, ClearanceClassRadiiAreAtMost255AndNeverBelowARadius) {
  const std::vector<float> few = clearanceClassRadii({3.5f, 1.25f, 3.5f, 7.0f});
  EXPECT_EQ(few, (std::vector<float>{1.25f, 3.5f, 7.0f}));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> radius(0.0f, 40.0f);
  std::vector<float> many(2000);
  for (float& r : many) r = radius(rng);
  const std::vector<float> classes = clearanceClassRadii(many);
  ASSERT_LE(classes.size(), 255u);
  ASSERT_TRUE(std::is_sorted(classes.begin(), classes.end()));
  EXPECT_EQ(classes.back(), *std::max_element(many.begin(), many.end()));
  for (const float r : many) {
    const auto c =
        std::lower_bound(classes.begin(), classes.end(), r);  // the action's class radius
    ASSERT_NE(c, classes.end()) << r;
    EXPECT_GE(*c, r);
    EXPECT_LE(*c - r, classes.back() / 255.0f * 1.001f) << "rounded up by more than one level";
  }
}

// A point robot (e.g. on a costmap already inflated by the robot's radius) sweeps no cell
// beyond its centre cells: its graph keeps no clearance (a byte a map cell), and each edge is
// valid exactly when every centre cell is inside the map and below inscribed, at the cost of
// the worst of them; a round robot keeps one.
TEST(LatticeClearance, APointRobotKeepsNoneAndItsEdgesTestTheirCentreCells) {
  std::shared_ptr<GridMap> map = test::randomMap(120, 90, 0.05, 5, 18, 40);
  std::mt19937 rng(3);
  for (std::uint8_t& c : map->cost) {  // inscribed and unknown cells too
    const unsigned r = rng() % 50;
    if (r == 0) c = kInscribedCost;
    if (r == 1) c = kUnknownCost;
  }
  LatticeConfig round;
  round.robot.radius = 0.2;
  EXPECT_EQ(LatticeGraph(map, round).clearance().size(), map->cost.size());
  LatticeConfig point;
  point.robot.radius = 0.0;
  const LatticeGraph graph(map, point);
  EXPECT_TRUE(graph.clearance().empty());
  int valid = 0, invalid = 0;
  for (std::size_t i = 0; i < graph.actions().size(); ++i) {
    const LatticeAction& a = graph.actions()[i];
    ASSERT_EQ(a.swept_begin, a.swept_end);
    for (int y = 0; y < map->height; ++y) {
      for (int x = 0; x < map->width; ++x) {
        Cost expected = kInvalidEdge;
        unsigned worst = 0;
        bool ok = true;
        for (const CellOffset& c : graph.actionCells(i).centre) {
          const int cx = x + c.dx, cy = y + c.dy;
          if (cx < 0 || cy < 0 || cx >= map->width || cy >= map->height ||
              map->at(cx, cy) >= kInscribedCost) {
            ok = false;
            break;
          }
          worst = std::max<unsigned>(worst, map->at(cx, cy));
        }
        if (ok) expected = graph.costWithPenalty(a.base_cost, worst);
        ASSERT_EQ(graph.edgeCost(x, y, a), expected)
            << "action " << i << " from (" << x << ", " << y << ")";
        ++(ok ? valid : invalid);
      }
    }
  }
  EXPECT_GT(valid, 0);
  EXPECT_GT(invalid, 0);
}

TEST(LatticeIncremental, AnEmptyChangeCopiesAndAnotherGridIsRefused) {
  auto map = test::randomMap(80, 60, 0.05, 5, 8, 0);
  LatticeConfig config;
  const LatticeGraph graph(map, config);
  const LatticeGraph same(graph, map, CellRect{});
  expectSameGraph(same, graph, "empty change");
  auto bigger = test::randomMap(81, 60, 0.05, 5, 8, 0);
  EXPECT_THROW(LatticeGraph(graph, bigger, CellRect{0, 0, 1, 1}), LatticeError);
  auto moved = std::make_shared<GridMap>(*map);
  moved->origin_x += 0.05;
  EXPECT_THROW(LatticeGraph(graph, moved, CellRect{0, 0, 1, 1}), LatticeError);
  auto finer = std::make_shared<GridMap>(*map);
  finer->resolution = 0.04;
  EXPECT_THROW(LatticePlanner(LatticePlanner(map, config), finer, CellRect{0, 0, 1, 1}),
               LatticeError);
}

TEST(LatticeIncremental, AnUpdatedPlannerPlansLikeAFreshOne) {
  auto map = test::randomMap(160, 120, 0.05, 11, 14, 30);
  LatticeConfig config;
  config.robot.footprint = test::rectangle(0.25, 0.15);
  auto planner = std::make_unique<LatticePlanner>(map, config);
  // Wall off the middle, leaving a gap, in three updates.
  const CellRect walls[] = {{78, 0, 82, 50}, {78, 60, 82, 120}, {0, 0, 3, 3}};
  for (const CellRect& r : walls) {
    auto next = withCells(*map, r, kLethalCost);
    planner = std::make_unique<LatticePlanner>(*planner, next, r);
    map = next;
  }
  LatticePlanner fresh(map, config);
  // Free start and goal on either side of the wall.
  auto freeCell = [&](int x0, int x1) {
    for (int y = 10; y < 110; ++y) {
      for (int x = x0; x < x1; ++x) {
        bool clear = true;
        for (int dy = -6; dy <= 6 && clear; ++dy) {
          for (int dx = -6; dx <= 6 && clear; ++dx)
            clear = map->at(x + dx, y + dy) < kInscribedCost;
        }
        if (clear) return Pose2D{(x + 0.5) * 0.05, (y + 0.5) * 0.05, 0.0};
      }
    }
    return Pose2D{-1, -1, 0};
  };
  const Pose2D start = freeCell(10, 60), goal = freeCell(100, 150);
  ASSERT_GE(start.x, 0.0);
  ASSERT_GE(goal.x, 0.0);
  PlannerConfig search;
  search.algorithm = Algorithm::kAStar;
  SearchLimits limits;
  limits.time_limit_s = 30.0;
  const PlanResult a = planner->plan(start, goal, search, limits);
  const PlanResult b = fresh.plan(start, goal, search, limits);
  ASSERT_EQ(a.error, QueryError::kNone) << a.message;
  EXPECT_EQ(a.search.status, b.search.status);
  EXPECT_EQ(a.search.expansions, b.search.expansions);
  ASSERT_EQ(a.solutions.size(), b.solutions.size());
  if (!a.solutions.empty()) {
    EXPECT_EQ(a.solutions.back().search.cost, b.solutions.back().search.cost);
  }
}

// The grids of the goal queried before a chain of updates are repaired, not computed again,
// and the plans are a fresh planner's; with repair_heuristics off they are computed again.
TEST(LatticeIncremental, AnUpdatedPlannerRepairsTheGridsOfItsPredecessor) {
  auto map = test::randomMap(160, 120, 0.05, 11, 14, 30);
  for (const bool repair : {true, false}) {
    LatticeConfig config;
    config.cache.repair = repair;
    config.robot.radius = 0.15;
    auto planner = std::make_unique<LatticePlanner>(map, config);
    const Pose2D start{1.0, 1.0, 0.0}, goal{6.6, 4.4, 1.57};
    // The robot's surroundings made free.
    auto base = withCells(*withCells(*map, around(start, 0.05, 8), 0), around(goal, 0.05, 8), 0);
    planner = std::make_unique<LatticePlanner>(*planner, base, CellRect{0, 0, 160, 120});
    PlannerConfig search;  // A-MHA*: every grid kind
    SearchLimits limits;
    limits.max_expansions = 200000;
    const PlanResult first = planner->plan(start, goal, search, limits);
    ASSERT_EQ(first.error, QueryError::kNone) << first.message;
    auto source = [](const PlanResult& r) {
      return std::string(heuristicSourceName(r.heuristic_source));
    };
    EXPECT_EQ(source(first), "computed") << "no planner had computed this goal's grids";
    EXPECT_EQ(source(planner->plan(start, goal, search, limits)), "cached");
    // Two updates with no query between them: a wall with a gap, then an obstacle.
    std::shared_ptr<GridMap> current = base;
    for (const CellRect& r : {CellRect{78, 0, 82, 70}, CellRect{100, 30, 112, 42}}) {
      auto next = withCells(*current, r, kLethalCost);
      planner = std::make_unique<LatticePlanner>(*planner, next, r);
      current = next;
    }
    LatticePlanner fresh(current, config);
    const PlanResult a = planner->plan(start, goal, search, limits);
    const PlanResult b = fresh.plan(start, goal, search, limits);
    ASSERT_EQ(a.error, QueryError::kNone) << a.message;
    EXPECT_EQ(source(a), repair ? "repaired" : "computed");
    EXPECT_EQ(source(b), "computed");
    EXPECT_EQ(a.search.status, b.search.status);
    EXPECT_EQ(a.search.expansions, b.search.expansions);
    ASSERT_EQ(a.solutions.size(), b.solutions.size());
    ASSERT_FALSE(a.solutions.empty()) << "the test wants a path around the wall";
    for (std::size_t k = 0; k < a.solutions.size(); ++k) {
      EXPECT_EQ(a.solutions[k].search.cost, b.solutions[k].search.cost) << "solution " << k;
    }
    // Another goal was never computed: computed now.
    EXPECT_EQ(source(planner->plan(goal, start, search, limits)), "computed");
  }
}

// Grids kept for repair count against heuristic_cache_size with the cache itself: a new goal's
// grids push out the least recently used old ones.
TEST(LatticeIncremental, KeptGridsAndCachedOnesStayWithinTheCacheSize) {
  auto map = test::randomMap(120, 90, 0.05, 2, 0, 0);  // open: every query is valid
  LatticeConfig config;
  config.robot.radius = 0.1;
  config.cache.size = 2;
  auto planner = std::make_unique<LatticePlanner>(map, config);
  const Pose2D start{0.5, 0.5, 0.0}, a{5.0, 4.0, 0.0}, b{1.0, 4.0, 0.0}, c{5.0, 0.5, 0.0};
  PlannerConfig search;
  search.algorithm = Algorithm::kWeightedAStar;
  SearchLimits limits;
  auto source = [&](const Pose2D& goal) {
    const PlanResult r = planner->plan(start, goal, search, limits);
    EXPECT_EQ(r.error, QueryError::kNone) << r.message;
    return std::string(heuristicSourceName(r.heuristic_source));
  };
  EXPECT_EQ(source(a), "computed");
  EXPECT_EQ(source(b), "computed");  // b is now the most recently used
  const CellRect obstacle{60, 45, 61, 46};
  planner =
      std::make_unique<LatticePlanner>(*planner, withCells(*map, obstacle, kLethalCost), obstacle);
  EXPECT_EQ(source(c), "computed");  // c, b and a would be three: a is dropped
  EXPECT_EQ(source(b), "repaired");
  EXPECT_EQ(source(a), "computed");
}

// Queries on a planner while the next one is built from it and queried too (the server's
// builder thread and its requests): the kept grids are copied while the old planner still
// holds them, one query repairs them while others wait, and every answer is a fresh
// planner's. Named for the TSan pass.
TEST(LatticeIncremental, ConcurrentQueriesWhileAPlannerIsBuiltFromThisOne) {
  auto map = test::randomMap(140, 100, 0.05, 4, 10, 20);
  LatticeConfig config;
  config.robot.radius = 0.1;
  auto first = std::make_shared<LatticePlanner>(map, config);
  // A start and goal clear of the random obstacles and of the update.
  const Pose2D start{0.6, 0.6, 0.0}, goal{6.3, 4.4, 0.0};
  auto cleared = withCells(*withCells(*map, around(start, 0.05, 8), 0), around(goal, 0.05, 8), 0);
  first = std::make_shared<LatticePlanner>(*first, cleared, CellRect{0, 0, 140, 100});
  PlannerConfig search;
  SearchLimits limits;
  limits.max_expansions = 50000;
  ASSERT_EQ(first->plan(start, goal, search, limits).error, QueryError::kNone);  // grids cached
  const CellRect wall{60, 20, 64, 90};
  auto next_map = withCells(*cleared, wall, kLethalCost);
  LatticePlanner fresh_first(cleared, config), fresh_next(next_map, config);
  const PlanResult want_first = fresh_first.plan(start, goal, search, limits);
  const PlanResult want_next = fresh_next.plan(start, goal, search, limits);
  ASSERT_FALSE(want_first.solutions.empty() || want_next.solutions.empty())
      << "the test wants paths";
  ASSERT_NE(want_first.search.expansions, want_next.search.expansions)
      << "the wall should change the search";
  std::shared_ptr<LatticePlanner> next;
  std::atomic<bool> built{false};
  std::vector<std::string> failures(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int k = 0; k < 6; ++k) {
        const bool on_next = t % 2 == 1 && built.load();
        const PlanResult r = (on_next ? next : first)->plan(start, goal, search, limits);
        const PlanResult& want = on_next ? want_next : want_first;
        if (r.search.expansions != want.search.expansions ||
            r.solutions.size() != want.solutions.size()) {
          failures[t] = std::string(on_next ? "next" : "first") + " planner: expansions " +
                        std::to_string(r.search.expansions) + " instead of " +
                        std::to_string(want.search.expansions);
        }
      }
    });
  }
  next = std::make_shared<LatticePlanner>(*first, next_map, wall);
  built = true;
  for (auto& th : threads) th.join();
  for (const std::string& f : failures) EXPECT_EQ(f, "");
  const PlanResult last = next->plan(start, goal, search, limits);
  EXPECT_EQ(last.search.expansions, want_next.search.expansions);
}

}  // namespace
}  // namespace lattice
}  // namespace amha
