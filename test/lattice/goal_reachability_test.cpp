// The goal's reachability told from its side (goal_reachability.h, LatticeProblem::
// goalUnreachable): against an exhaustive Dijkstra from the start on random maps, in every
// search direction and with goals of any heading; the budget's meaning; and a planner whose
// goal lies in a dead end that says so at once instead of exhausting the map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <random>
#include <string>
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

// A 7.5 m x 6 m room with a slot 3 cells wide and 12 m deep in its east wall: a car (no turns
// on the spot, no reverse) that drives in facing east cannot turn round in it, so a goal there
// facing west has no path, though its cell is reachable. Deep enough that a goal or start in its
// first metres has more states in its pocket than the planner walks before its grids
// (deadEnd), and one near its end (from x = 19.2 m; the slot's last cell is at 19.475 m) fewer.
std::shared_ptr<GridMap> roomWithSlot() {
  auto m = test::freeMap(400, 120, 0.05);
  for (int y = 0; y < m->height; ++y) {
    for (int x = 150; x < m->width; ++x) {
      const bool slot = y >= 59 && y <= 61 && x < 390;
      if (!slot) m->cost[static_cast<std::size_t>(y) * m->width + x] = kLethalCost;
    }
  }
  return m;
}

// The car of the slot tests; without the block abstraction its heuristics cannot see the slot
// (the 2-D grids ignore the heading and the kinematic table the walls), so only a walk can tell.
LatticeConfig slotCar(bool coarse_anchor) {
  LatticeConfig c;
  c.robot.footprint = test::rectangle(0.04, 0.04);
  c.motion.turning_radius = 0.3;
  c.motion.model = MotionModel::kAckermann;
  c.heuristics.coarse_anchor = coarse_anchor;
  return c;
}

std::size_t countReachable(const LatticeGraph& g, const Pose2D& from) {
  int x = 0, y = 0, h = 0;
  EXPECT_TRUE(g.poseToState(from, &x, &y, &h));
  const std::vector<Cost> d = test::dijkstraFrom(
      g, LatticeState{x, y, h},
      [&](int cx, int cy, const LatticeAction& a) { return g.edgeCost(cx, cy, a); });
  return static_cast<std::size_t>(
      std::count_if(d.begin(), d.end(), [](Cost v) { return v < kInfiniteCost; }));
}

// The states from which some path leads to `to` (itself included), by an exhaustive fixed point
// over every state's every action: no walk involved.
std::size_t countLeadingTo(const LatticeGraph& g, const LatticeState& to) {
  std::vector<char> leads(static_cast<std::size_t>(g.width()) * g.height() * g.numHeadings(), 0);
  leads[stateIndex(g, to.x, to.y, to.heading)] = 1;
  std::size_t count = 1;
  for (bool grew = true; grew;) {
    grew = false;
    for (int y = 0; y < g.height(); ++y) {
      for (int x = 0; x < g.width(); ++x) {
        for (int h = 0; h < g.numHeadings(); ++h) {
          char& here = leads[stateIndex(g, x, y, h)];
          if (here) continue;
          for (const LatticeAction* a = g.actionsBegin(h); a != g.actionsEnd(h) && !here; ++a) {
            if (g.edgeCost(x, y, *a) == kInvalidEdge) continue;
            if (leads[stateIndex(g, x + a->dx, y + a->dy, a->end_heading)]) here = 1;
          }
          if (here) {
            ++count;
            grew = true;
          }
        }
      }
    }
  }
  return count;
}

TEST(GoalReachability, APlannerSaysAtOnceThatADeadEndGoalHasNoPath) {
  const Pose2D start{1.0, 1.0, 0.0};
  const Pose2D into_slot{9.0, 3.025, 0.0}, out_of_slot{9.0, 3.025, 3.141593};
  SearchLimits limits;
  limits.time_limit_s = 20;
  // The default heuristics: the block abstraction, computed from the goal, rules the start out
  // before anything is expanded.
  LatticePlanner with_blocks(roomWithSlot(), slotCar(true));
  const PlanResult in =
      with_blocks.plan(start, into_slot, defaultConfig(Algorithm::kAmhaStar), limits);
  ASSERT_EQ(in.error, QueryError::kNone) << in.message;
  EXPECT_TRUE(in.hasSolution());
  EXPECT_EQ(in.no_path, NoPathProof::kNone);
  EXPECT_EQ(in.no_path_reason, "");
  const PlanResult seen =
      with_blocks.plan(start, out_of_slot, defaultConfig(Algorithm::kAmhaStar), limits);
  EXPECT_EQ(seen.search.status, SearchStatus::kNoSolution);
  EXPECT_EQ(seen.search.expansions, 0u);
  EXPECT_EQ(seen.no_path, NoPathProof::kSearch);
  EXPECT_EQ(seen.no_path_reason,
            "proven by the heuristics, computed from the goal's side: the start cannot reach the "
            "goal");
  // Without it: no path, found from the goal's few states instead of the room's hundreds of
  // thousands, for every algorithm, and said so.
  LatticePlanner planner(roomWithSlot(), slotCar(false));
  EXPECT_GT(countReachable(planner.graph(), start), 200000u);
  for (Algorithm a :
       {Algorithm::kAmhaStar, Algorithm::kAraStar, Algorithm::kAnaStar, Algorithm::kAStar}) {
    const PlanResult out = planner.plan(start, out_of_slot, defaultConfig(a), limits);
    ASSERT_EQ(out.error, QueryError::kNone) << out.message;
    EXPECT_FALSE(out.hasSolution()) << algorithmName(a);
    EXPECT_EQ(out.search.status, SearchStatus::kNoSolution) << algorithmName(a);
    EXPECT_LE(out.search.expansions, 32768u) << algorithmName(a);
    EXPECT_TRUE(out.search.goal_side_proof) << algorithmName(a);
    EXPECT_EQ(out.no_path, NoPathProof::kGoalEnclosed) << algorithmName(a);
    EXPECT_GT(out.enclosed_states, 64u) << algorithmName(a) << ": more than deadEnd walks";
    EXPECT_LT(out.enclosed_states, 20000u) << algorithmName(a);
    EXPECT_NE(out.heuristic_source, HeuristicSource::kNone) << "found after the grids";
    EXPECT_EQ(out.no_path_reason,
              "proven from the goal's side: only " + std::to_string(out.enclosed_states) +
                  " lattice states (cell and heading; the goal's own included) lead to the goal, "
                  "and the start is none of them")
        << algorithmName(a);
  }
}

// A start in the slot facing its end: the robot reaches a few states and never the room.
// Forward, the search runs out of them; backward, the walk forward from the start counts them,
// exactly as a Dijkstra from the start does.
TEST(GoalReachability, AnEnclosedStartIsToldFromTheStartsSide) {
  const Pose2D stuck{9.0, 3.025, 0.0}, goal{1.0, 1.0, 0.0};
  SearchLimits limits;
  limits.time_limit_s = 20;
  LatticePlanner forward(roomWithSlot(), slotCar(false));
  const PlanResult f = forward.plan(stuck, goal, defaultConfig(Algorithm::kAStar), limits);
  ASSERT_EQ(f.error, QueryError::kNone) << f.message;
  EXPECT_EQ(f.search.status, SearchStatus::kNoSolution);
  EXPECT_GT(f.search.expansions, 0u);
  EXPECT_FALSE(f.search.goal_side_proof);
  EXPECT_EQ(f.no_path, NoPathProof::kSearch);
  EXPECT_EQ(f.enclosed_states, 0u) << "exhausted by the search, not walked";
  EXPECT_EQ(f.no_path_reason, "proven by the search: it ran out of states from the start after " +
                                  std::to_string(f.search.expansions) +
                                  " expansions (its heuristics, computed from the goal's side, "
                                  "rule out the others)");

  LatticeConfig c = slotCar(false);
  c.backward_search = true;
  LatticePlanner backward(roomWithSlot(), c);
  const std::size_t reached = countReachable(backward.graph(), stuck);
  ASSERT_GT(reached, 1u);
  ASSERT_LT(reached, 20000u);
  for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kAStar}) {
    const PlanResult b = backward.plan(stuck, goal, defaultConfig(a), limits);
    ASSERT_EQ(b.error, QueryError::kNone) << b.message;
    EXPECT_EQ(b.search.status, SearchStatus::kNoSolution) << algorithmName(a);
    EXPECT_TRUE(b.search.goal_side_proof) << algorithmName(a);
    EXPECT_EQ(b.no_path, NoPathProof::kStartEnclosed) << algorithmName(a);
    EXPECT_EQ(b.enclosed_states, reached) << algorithmName(a);
    EXPECT_EQ(b.no_path_reason, "proven from the start's side: only " + std::to_string(reached) +
                                    " lattice states (cell and heading; the start's own "
                                    "included) can be reached from the start, and the goal is "
                                    "none of them")
        << algorithmName(a);
  }
}

// What a refusal before the grids says: no search, no grid, a walk's proof of `proof` over
// `states` lattice states, in `reason`'s words.
void expectRefusedBeforeTheGrids(const PlanResult& r, NoPathProof proof, std::size_t states,
                                 const std::string& reason, const std::string& where) {
  ASSERT_EQ(r.error, QueryError::kNone) << where << ": " << r.message;
  EXPECT_FALSE(r.hasSolution()) << where;
  EXPECT_EQ(r.search.status, SearchStatus::kNoSolution) << where;
  EXPECT_EQ(r.search.expansions, 0u) << where;
  EXPECT_TRUE(r.search.goal_side_proof) << where;
  EXPECT_EQ(r.heuristic_seconds, 0.0) << where << ": no grid was computed";
  EXPECT_EQ(r.heuristic_source, HeuristicSource::kNone) << where;
  EXPECT_EQ(r.no_path, proof) << where;
  EXPECT_EQ(r.enclosed_states, states) << where;
  EXPECT_EQ(r.no_path_reason, reason) << where;
}

// An end that no motion enters or leaves: at the slot's end, the car facing west cannot have
// arrived (it would have come through the wall), and facing east it cannot leave. Every planner
// says so before its heuristic grids, whatever the search direction, without a search.
TEST(GoalReachability, AnEndWithoutAMotionIsToldBeforeTheGrids) {
  const Pose2D room{1.0, 1.0, 0.0};
  const Pose2D facing_out{19.425, 3.025, 3.141593}, facing_wall{19.425, 3.025, 0.0};
  SearchLimits limits;
  limits.time_limit_s = 20;
  for (bool backward : {false, true}) {
    LatticeConfig c = slotCar(true);
    c.backward_search = backward;
    LatticePlanner planner(roomWithSlot(), c);
    for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kAStar, Algorithm::kWeightedAStar}) {
      const std::string where = std::string(algorithmName(a)) + (backward ? ", backward" : "");
      expectRefusedBeforeTheGrids(
          planner.plan(room, facing_out, defaultConfig(a), limits), NoPathProof::kGoalEnclosed, 1,
          "proven from the goal's side: no valid motion ends in the goal's lattice state (cell "
          "and heading)",
          where);
      expectRefusedBeforeTheGrids(
          planner.plan(facing_wall, room, defaultConfig(a), limits), NoPathProof::kStartEnclosed, 1,
          "proven from the start's side: no valid motion leaves the start's lattice state (cell "
          "and heading)",
          where);
    }
    // With any goal heading, one heading a motion ends in is enough: the search runs.
    GoalOptions any;
    any.any_heading = true;
    const PlanResult into =
        planner.plan(room, facing_out, any, defaultConfig(Algorithm::kAmhaStar), limits);
    EXPECT_TRUE(into.hasSolution()) << into.message;
    EXPECT_EQ(into.no_path, NoPathProof::kNone);
  }
  // What the walk proves, checked by an exhaustive Dijkstra: nothing leaves the wall-facing
  // state, and the west-facing one is reached from no other state.
  LatticePlanner planner(roomWithSlot(), slotCar(false));
  EXPECT_EQ(countReachable(planner.graph(), facing_wall), 1u);
  const LatticeGraph& g = planner.graph();
  int gx = 0, gy = 0, gh = 0;
  ASSERT_TRUE(g.poseToState(facing_out, &gx, &gy, &gh));
  std::size_t into_goal = 0;
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      for (int h = 0; h < g.numHeadings(); ++h) {
        for (const LatticeAction* a = g.actionsBegin(h); a != g.actionsEnd(h); ++a) {
          if (x + a->dx == gx && y + a->dy == gy && a->end_heading == gh &&
              g.edgeCost(x, y, *a) != kInvalidEdge)
            ++into_goal;
        }
      }
    }
  }
  EXPECT_EQ(into_goal, 0u);
}

// A pocket of a few states near the slot's end: the planner walks them before its grids, in
// both search directions and for every algorithm, and counts exactly the states an exhaustive
// fixed point (the goal's) or Dijkstra (the start's) finds.
TEST(GoalReachability, APocketOfAFewStatesIsToldBeforeTheGrids) {
  const Pose2D room{1.0, 1.0, 0.0};
  const Pose2D out_of_end{19.225, 3.025, 3.141593}, into_end{19.225, 3.025, 0.0};
  LatticePlanner reference(roomWithSlot(), slotCar(false));
  const LatticeGraph& g = reference.graph();
  int x = 0, y = 0, h = 0;
  ASSERT_TRUE(g.poseToState(out_of_end, &x, &y, &h));
  const std::size_t leading = countLeadingTo(g, LatticeState{x, y, h});
  const std::size_t reached = countReachable(g, into_end);
  // More than the end's own state (a motion does enter and leave it), fewer than deadEnd's 64.
  ASSERT_GT(leading, 1u);
  ASSERT_LE(leading, 64u);
  ASSERT_GT(reached, 1u);
  ASSERT_LE(reached, 64u);
  SearchLimits limits;
  limits.time_limit_s = 20;
  for (bool backward : {false, true}) {
    LatticeConfig c = slotCar(false);
    c.backward_search = backward;
    LatticePlanner planner(roomWithSlot(), c);
    for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kAStar, Algorithm::kAraStar}) {
      const std::string where = std::string(algorithmName(a)) + (backward ? ", backward" : "");
      expectRefusedBeforeTheGrids(
          planner.plan(room, out_of_end, defaultConfig(a), limits), NoPathProof::kGoalEnclosed,
          leading,
          "proven from the goal's side: only " + std::to_string(leading) +
              " lattice states (cell and heading; the goal's own included) lead to the goal, and "
              "the start is none of them",
          where);
      expectRefusedBeforeTheGrids(
          planner.plan(into_end, room, defaultConfig(a), limits), NoPathProof::kStartEnclosed,
          reached,
          "proven from the start's side: only " + std::to_string(reached) +
              " lattice states (cell and heading; the start's own included) can be reached from "
              "the start, and the goal is none of them",
          where);
    }
  }
}

}  // namespace
}  // namespace lattice
}  // namespace amha
