// The goal's reachability told from its side (goal_reachability.h, LatticeProblem::
// goalUnreachable): against an exhaustive Dijkstra from the start on random maps, in every
// search direction and with goals of any heading; the budget's meaning; and a planner whose
// goal lies in a dead end that says so at once instead of exhausting the map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <random>
#include <vector>

#include "amha_planner/lattice/detail/goal_reachability.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

std::size_t stateIndex(const LatticeGraph& g, int x, int y, int h) {
  return (static_cast<std::size_t>(y) * g.width() + x) * g.numHeadings() + h;
}

// smallRobot as a car (no turns on the spot): dead ends and one-way pockets, so that many goals
// have no path.
LatticeConfig car(unsigned seed) {
  LatticeConfig c = test::smallRobot(seed);
  c.motion.model = MotionModel::kAckermann;
  return c;
}

LatticeState randomValidState(const LatticeGraph& g, std::mt19937& rng) {
  for (;;) {
    const LatticeState s{static_cast<int>(rng() % g.width()), static_cast<int>(rng() % g.height()),
                         static_cast<int>(rng() % g.numHeadings())};
    if (g.stateValid(s.x, s.y, s.heading)) return s;
  }
}

TEST(GoalReachability, ProvesExactlyTheGoalsNoPathReachesOnRandomMaps) {
  int reachable = 0, unreachable = 0, any_unreachable = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const auto map = test::randomMap(40, 40, 0.05, seed, 30, seed % 2 ? 100 : 0);
    const LatticeGraph g(map, car(seed));
    std::mt19937 rng(seed);
    for (int q = 0; q < 25; ++q) {
      const LatticeState s = randomValidState(g, rng), t = randomValidState(g, rng);
      const std::vector<Cost> d = test::dijkstraFrom(
          g, s, [&](int x, int y, const LatticeAction& a) { return g.edgeCost(x, y, a); });
      const bool reaches = d[stateIndex(g, t.x, t.y, t.heading)] < kInfiniteCost;
      bool reaches_cell = false;
      for (int h = 0; h < g.numHeadings(); ++h)
        reaches_cell = reaches_cell || d[stateIndex(g, t.x, t.y, h)] < kInfiniteCost;
      (reaches ? reachable : unreachable) += 1;
      any_unreachable += reaches_cell ? 0 : 1;
      const std::size_t all = std::size_t{1} << 30;
      // Forward (the walk goes against the edges) and backward (along them), one goal heading
      // or any.
      LatticeProblem forward(g, nullptr, s, t, 0);
      EXPECT_EQ(forward.goalUnreachable(all), !reaches) << "seed " << seed << " query " << q;
      LatticeProblem backward(g, nullptr, t, s, 0, /*backward=*/true);
      EXPECT_EQ(backward.goalUnreachable(all), !reaches) << "seed " << seed << " query " << q;
      LatticeProblem forward_any(g, nullptr, s, t, 0, false, /*any_goal_heading=*/true);
      EXPECT_EQ(forward_any.goalUnreachable(all), !reaches_cell) << "seed " << seed << " q " << q;
      LatticeProblem backward_any(g, nullptr, t, s, 0, true, true);
      EXPECT_EQ(backward_any.goalUnreachable(all), !reaches_cell) << "seed " << seed << " q " << q;
    }
  }
  // Both answers were asked for often enough to mean something.
  EXPECT_GE(reachable, 40);
  EXPECT_GE(unreachable, 40);
  EXPECT_GE(any_unreachable, 20);
}

TEST(GoalReachability, TheBudgetCountsTheStatesVisited) {
  int enclosed = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const auto map = test::randomMap(40, 40, 0.05, seed, 30, 0);
    const LatticeGraph g(map, car(seed));
    std::mt19937 rng(seed + 100);
    for (int q = 0; q < 20; ++q) {
      const LatticeState s = randomValidState(g, rng), t = randomValidState(g, rng);
      auto is_s = [&](const LatticeState& v) { return v == s; };
      auto explore = [&](std::size_t budget) {
        return exploreReachable(g, {t}, true, is_s, budget);
      };
      if (explore(std::size_t{1} << 30) != Reachability::kEnclosed) continue;
      ++enclosed;
      // The smallest budget that proves it is the number of states that reach t (t included):
      // one fewer is not enough.
      std::size_t lo = 0, hi = std::size_t{1} << 30;
      while (hi - lo > 1) {
        const std::size_t mid = lo + (hi - lo) / 2;
        (explore(mid) == Reachability::kEnclosed ? hi : lo) = mid;
      }
      EXPECT_EQ(explore(hi - 1), Reachability::kOverBudget);
      EXPECT_GE(hi, 1u);
    }
  }
  EXPECT_GE(enclosed, 10);
}

// A 10 m x 6 m room with a slot 3 cells wide and 2 m deep in its east wall: a car (no turns on
// the spot, no reverse) that drives in facing east cannot turn round in it, so a goal there
// facing west has no path, though its cell is reachable.
std::shared_ptr<GridMap> roomWithSlot() {
  auto m = test::freeMap(200, 120, 0.05);
  for (int y = 0; y < m->height; ++y) {
    for (int x = 150; x < m->width; ++x) {
      const bool slot = y >= 59 && y <= 61 && x < 190;
      if (!slot) m->cost[static_cast<std::size_t>(y) * m->width + x] = kLethalCost;
    }
  }
  return m;
}

TEST(GoalReachability, APlannerSaysAtOnceThatADeadEndGoalHasNoPath) {
  LatticeConfig c;
  c.robot.footprint = test::rectangle(0.04, 0.04);
  c.motion.turning_radius = 0.3;
  c.motion.model = MotionModel::kAckermann;
  LatticePlanner planner(roomWithSlot(), c);
  const Pose2D start{1.0, 1.0, 0.0};
  const Pose2D into_slot{9.0, 3.025, 0.0}, out_of_slot{9.0, 3.025, 3.141593};
  SearchLimits limits;
  limits.time_limit_s = 20;
  // Facing in: a path.
  const PlanResult in = planner.plan(start, into_slot, defaultConfig(Algorithm::kAmhaStar), limits);
  ASSERT_EQ(in.error, QueryError::kNone) << in.message;
  EXPECT_TRUE(in.hasSolution());
  // Facing out: none, found from the goal's few states instead of the room's hundreds of
  // thousands, for every algorithm.
  const LatticeGraph& g = planner.graph();
  int sx = 0, sy = 0, sh = 0;
  ASSERT_TRUE(g.poseToState(start, &sx, &sy, &sh));
  const std::vector<Cost> d =
      test::dijkstraFrom(g, LatticeState{sx, sy, sh},
                         [&](int x, int y, const LatticeAction& a) { return g.edgeCost(x, y, a); });
  const auto from_start =
      std::count_if(d.begin(), d.end(), [](Cost v) { return v < kInfiniteCost; });
  EXPECT_GT(from_start, 200000);
  for (Algorithm a :
       {Algorithm::kAmhaStar, Algorithm::kAraStar, Algorithm::kAnaStar, Algorithm::kAStar}) {
    const PlanResult out = planner.plan(start, out_of_slot, defaultConfig(a), limits);
    ASSERT_EQ(out.error, QueryError::kNone) << out.message;
    EXPECT_FALSE(out.hasSolution()) << algorithmName(a);
    EXPECT_EQ(out.search.status, SearchStatus::kNoSolution) << algorithmName(a);
    EXPECT_LE(out.search.expansions, 32768u) << algorithmName(a);
  }
}

}  // namespace
}  // namespace lattice
}  // namespace amha
