// Goals of any heading (GoalOptions::any_heading): the search ends at whichever heading of the
// goal's cell is cheapest. Checked against an exhaustive Dijkstra over the lattice to every
// heading of the cell, forward and backward, with every algorithm's solutions validated and
// within their certified bounds; the heuristics stay consistent (the virtual goal's edges
// included); the coarse distances to any heading are the minimum over the headings.
#include <algorithm>
#include <cmath>
#include <queue>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/coarse_lattice.h"
#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "path_validator.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

// Cheapest cost from s to each state, by Dijkstra over the graph's own edges.
std::vector<Cost> costsFrom(const LatticeGraph& g, const LatticeState& s) {
  return test::dijkstraFrom(
      g, s, [&](int x, int y, const LatticeAction& a) { return g.edgeCost(x, y, a); });
}

Cost cheapestToCell(const LatticeGraph& g, const std::vector<Cost>& d, int x, int y) {
  Cost best = kInfiniteCost;
  for (int h = 0; h < g.numHeadings(); ++h)
    best = std::min(best, d[(static_cast<std::size_t>(y) * g.width() + x) * g.numHeadings() + h]);
  return best;
}

// Every algorithm, forward and backward, on the search problem itself: every solution is a
// valid lattice path from s to some heading of the goal's cell, at most certified x optimal;
// A*'s cost is the optimum.
TEST(AnyGoalHeading, SolutionsAgainstAnExhaustiveDijkstraToEveryHeading) {
  const Algorithm all[] = {Algorithm::kAStar,   Algorithm::kAmhaStar, Algorithm::kMhaStar,
                           Algorithm::kAraStar, Algorithm::kAnaStar,  Algorithm::kWeightedAStar};
  int queries = 0, cheaper_than_own_heading = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const auto map = test::randomMap(34, 34, 0.05, seed, 11, seed % 2 ? 150 : 0);
    const LatticeGraph g(map, test::smallRobot(seed));
    const HeuristicGridBuilder b(g);
    const test::ValidatorModel model = test::modelFor(g);
    std::mt19937 rng(seed * 31);
    for (int q = 0; q < 3; ++q) {
      LatticeState s{0, 0, 0}, t{0, 0, 0};
      do {
        s = {static_cast<int>(rng() % 34), static_cast<int>(rng() % 34),
             static_cast<int>(rng() % g.numHeadings())};
      } while (!g.stateValid(s.x, s.y, s.heading));
      do {
        t = {static_cast<int>(rng() % 34), static_cast<int>(rng() % 34),
             static_cast<int>(rng() % g.numHeadings())};
      } while (!g.stateValid(t.x, t.y, t.heading));
      const std::vector<Cost> d = costsFrom(g, s);
      const Cost optimal = cheapestToCell(g, d, t.x, t.y);
      const Cost own = d[(static_cast<std::size_t>(t.y) * 34 + t.x) * g.numHeadings() + t.heading];
      ++queries;
      cheaper_than_own_heading += optimal < own;
      for (const bool backward : {false, true}) {
        for (const Algorithm alg : all) {
          const LatticeState from = backward ? t : s, to = backward ? s : t;
          auto grids =
              b.compute(to.x, to.y, backward ? to.heading : kAnyHeading, true, 1, backward);
          LatticeProblem p(g, grids, from, to, 3, backward, true);
          SearchLimits limits;
          limits.time_limit_s = 10;
          const SearchResult r =
              makePlanner(defaultConfig(alg))->search(p, limits, [&](const Solution& sol) {
                std::vector<LatticeState> states;
                for (StateId id : sol.path) {
                  if (id != p.virtualGoal()) states.push_back(p.state(id));
                }
                if (backward) std::reverse(states.begin(), states.end());
                ASSERT_EQ(sol.path.size(), states.size() + 1) << "one virtual state";
                ASSERT_TRUE(states.front() == s);
                ASSERT_EQ(states.back().x, t.x);
                ASSERT_EQ(states.back().y, t.y);
                ASSERT_EQ(test::validatePath(model, states, sol.cost), "") << algorithmName(alg);
                ASSERT_GE(sol.cost, optimal);
                ASSERT_LE(static_cast<double>(sol.cost),
                          sol.certified_bound * static_cast<double>(optimal) * (1 + 1e-12))
                    << algorithmName(alg) << (backward ? " backward" : " forward");
              });
          if (optimal == kInfiniteCost) {
            EXPECT_FALSE(r.hasSolution());
          } else {
            ASSERT_TRUE(r.hasSolution()) << algorithmName(alg);
            if (alg == Algorithm::kAStar) {
              EXPECT_EQ(r.best().cost, optimal) << (backward ? "backward" : "forward");
            }
          }
          if (HasFatalFailure()) return;
        }
      }
    }
  }
  EXPECT_EQ(queries, 30);
  EXPECT_GT(cheaper_than_own_heading, 5) << "the free heading should often pay";
}

// h(s) <= c(s, t) + h(t) on every edge the searches can take, the virtual goal's included.
TEST(AnyGoalHeading, AnchorStaysConsistent) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const auto map = test::randomMap(30, 30, 0.05, seed + 50, 8, seed % 2 ? 150 : 0);
    const LatticeGraph g(map, test::smallRobot(seed));
    const HeuristicGridBuilder b(g);
    std::mt19937 rng(seed);
    LatticeState s{0, 0, 0}, t{0, 0, 0};
    do {
      s = {static_cast<int>(rng() % 30), static_cast<int>(rng() % 30), 0};
    } while (!g.stateValid(s.x, s.y, s.heading));
    do {
      t = {static_cast<int>(rng() % 30), static_cast<int>(rng() % 30),
           static_cast<int>(rng() % g.numHeadings())};
    } while (!g.stateValid(t.x, t.y, t.heading));
    LatticeProblem p(g, b.compute(t.x, t.y, kAnyHeading, false, 1), s, t, 0, false, true);
    std::vector<Edge> succ;
    int edges = 0, into_goal = 0;
    // Every state of the map (ids are created on demand).
    for (int y = 0; y < 30; ++y) {
      for (int x = 0; x < 30; ++x) {
        for (int h = 0; h < g.numHeadings(); ++h) {
          if (!g.stateValid(x, y, h)) continue;
          const StateId u = p.id(x, y, h);
          HeuristicValue hu = 0, hv = 0;
          p.heuristics(u, &hu, 1);
          p.successors(u, succ);
          for (const Edge& e : succ) {
            p.heuristics(e.to, &hv, 1);
            if (hu == kInfiniteHeuristic || hv == kInfiniteHeuristic) continue;  // holds trivially
            ASSERT_LE(static_cast<Cost>(hu), e.cost + static_cast<Cost>(hv))
                << "seed " << seed << " (" << x << ", " << y << ", " << h << ")";
            ++edges;
            into_goal += e.to == p.virtualGoal();
          }
        }
      }
    }
    EXPECT_GT(edges, 1000);
    EXPECT_GT(into_goal, 0) << "the goal cell's states lead to the virtual goal";
  }
}

TEST(AnyGoalHeading, CoarseDistancesAreTheMinimumOverHeadings) {
  const auto map = test::randomMap(60, 50, 0.05, 9, 10, 100);
  map->cost[30 * 60 + 20] = kFreeCost;  // the goal's block is passable
  LatticeConfig c = test::smallRobot(3);
  const LatticeGraph g(map, c);
  for (const int block : {2, 3}) {
    const CoarseLattice coarse(g, block);
    for (const bool forward : {false, true}) {
      const std::vector<std::uint32_t> any = coarse.distances(20, 30, kAnyHeading, forward);
      std::vector<std::uint32_t> least(any.size(), kUnreachable);
      for (int h = 0; h < g.numHeadings(); ++h) {
        const std::vector<std::uint32_t> one = coarse.distances(20, 30, h, forward);
        for (std::size_t i = 0; i < one.size(); ++i) least[i] = std::min(least[i], one[i]);
      }
      EXPECT_EQ(any, least) << "block " << block << (forward ? " forward" : " backward");
      EXPECT_GT(std::count(any.begin(), any.end(), 0u), g.numHeadings() - 1);
    }
  }
}

// A goal inside a dead end only as wide as the robot is long: facing across it, the robot
// collides; any heading takes the one that fits. And a goal behind the start: a free heading
// spares the turn.
TEST(AnyGoalHeading, PlannerTakesTheHeadingThatFitsAndTheCheapest) {
  auto map = std::make_shared<GridMap>();
  map->width = 80;
  map->height = 40;
  map->resolution = 0.05;
  map->cost.assign(80 * 40, kFreeCost);
  for (int y = 0; y < 40; ++y) {
    for (int x = 50; x < 80; ++x) {
      if (y < 17 || y > 22) map->cost[y * 80 + x] = kLethalCost;  // a corridor 6 cells wide
    }
  }
  LatticeConfig c;
  c.motion.turning_radius = 0.2;
  c.robot.footprint = test::rectangle(0.2, 0.1);  // 0.4 m x 0.2 m: fits along the corridor only
  LatticePlanner planner(map, c);
  const Pose2D start{0.5, 1.0, 0.0}, across{3.0, 1.0, M_PI / 2};
  const PlannerConfig astar = defaultConfig(Algorithm::kAStar);
  PlanResult r = planner.plan(start, across, astar, SearchLimits());
  EXPECT_EQ(r.error, QueryError::kGoalInCollision);
  GoalOptions any;
  any.any_heading = true;
  r = planner.plan(start, across, any, astar, SearchLimits());
  ASSERT_EQ(r.error, QueryError::kNone) << r.message;
  ASSERT_TRUE(r.hasSolution());
  ASSERT_TRUE(r.planned_goal.has_value());
  EXPECT_NEAR(std::abs(std::remainder(r.planned_goal->theta, M_PI)), 0.0, 1e-9)
      << "along the corridor";
  EXPECT_NEAR(r.solutions.back().poses.back().theta, r.planned_goal->theta, 1e-12);
  EXPECT_NEAR(r.solutions.back().poses.back().x, 3.025, 1e-9);

  // Behind the start, facing away: the free heading is cheaper than the one asked for.
  const Pose2D behind{0.5, 1.0, M_PI}, ahead_goal{1.5, 1.0, M_PI};
  const PlanResult fixed = planner.plan(behind, ahead_goal, astar, SearchLimits());
  const PlanResult free_heading = planner.plan(behind, ahead_goal, any, astar, SearchLimits());
  ASSERT_TRUE(fixed.hasSolution() && free_heading.hasSolution());
  EXPECT_LT(free_heading.best().search.cost, fixed.best().search.cost);
  // Every heading in collision at the goal: still refused, and said so.
  r = planner.plan(start, {3.0, 0.3, 0.0}, any, astar, SearchLimits());
  EXPECT_EQ(r.error, QueryError::kGoalInCollision);
  EXPECT_NE(r.message.find("every heading"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace lattice
}  // namespace amha
