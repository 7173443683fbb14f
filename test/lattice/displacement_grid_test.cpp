// The displacement grid (displacement_grid.h): consistent on every valid edge of generated
// lattices and of SBPL's cubicle, toward a goal and from a start; never above the exact
// cost-to-go (a Dijkstra over the lattice); its field stopped at a bound keeps both; a raised
// entry breaks the check; exact in scale on an empty map, where the 16-connected grid is not;
// and the anchor with it (LatticeProblem::upgradeHeuristics) stays consistent and plans the
// same optimal costs.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>

#include "amha_planner/lattice/detail/displacement_grid.h"
#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/map_loaders.h"
#include "anchor_checks.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

constexpr std::uint32_t kInf = DisplacementGrid::kUnreachable;
using Value = std::function<std::uint32_t(int, int)>;

// h(p) <= cost(p, q) + h(q) for every valid edge p -> q toward the goal (to_cell), or
// h(q) <= cost(p, q) + h(p) from the start; an unreachable side only where the other is.
::testing::AssertionResult consistentOnEveryEdge(const LatticeGraph& g, const Value& h,
                                                 bool to_cell, std::size_t* edges = nullptr) {
  std::size_t n = 0;
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      for (int hd = 0; hd < g.numHeadings(); ++hd) {
        if (!g.stateValid(x, y, hd)) continue;
        for (const LatticeAction* a = g.actionsBegin(hd); a != g.actionsEnd(hd); ++a) {
          const Cost c = g.edgeCost(x, y, *a);
          if (c == kInvalidEdge) continue;
          ++n;
          // The search's direction: from `from` to `to`, and h measured toward its target.
          std::uint32_t hp = h(x, y), hq = h(x + a->dx, y + a->dy);
          if (!to_cell) std::swap(hp, hq);
          if (hq == kInf) continue;  // nothing to bound
          if (hp == kInf || static_cast<Cost>(hp) > c + static_cast<Cost>(hq)) {
            return ::testing::AssertionFailure()
                   << "edge (" << x << "," << y << "," << hd << ") -> (" << x + a->dx << ","
                   << y + a->dy << "," << a->end_heading << ") cost " << c << ": " << hp << " > "
                   << c << " + " << hq << (to_cell ? " toward" : " from");
          }
        }
      }
    }
  }
  if (edges != nullptr) *edges = n;
  return ::testing::AssertionSuccess();
}

std::shared_ptr<DisplacementField> field(
    const DisplacementGrid& d, int x, int y, bool to_cell, int tx, int ty,
    std::uint64_t bound = std::numeric_limits<std::uint64_t>::max()) {
  auto f = std::make_shared<DisplacementField>();
  f->bound.store(bound);
  EXPECT_TRUE(d.compute(x, y, to_cell, tx, ty, &f->bound, f.get()));
  return f;
}

Value valueOf(const DisplacementField& f) {
  return [&f](int x, int y) { return f.at(x, y); };
}

// The cheapest cost from each of a few valid states to every state (test::dijkstraFrom), and
// the field from or toward those states' cells: never above it.
void expectAdmissible(const LatticeGraph& g, const DisplacementGrid& d, unsigned seed) {
  std::mt19937 rng(seed);
  int checked = 0;
  for (int tries = 0; tries < 400 && checked < 3; ++tries) {
    const LatticeState s{static_cast<int>(rng() % g.width()), static_cast<int>(rng() % g.height()),
                         static_cast<int>(rng() % g.numHeadings())};
    if (!g.stateValid(s.x, s.y, s.heading)) continue;
    const std::vector<Cost> exact = test::dijkstraFrom(
        g, s, [&](int x, int y, const LatticeAction& a) { return g.edgeCost(x, y, a); });
    std::vector<Cost> best(static_cast<std::size_t>(g.width()) * g.height(), kInfiniteCost);
    int finite = 0;
    for (std::size_t cell = 0; cell < best.size(); ++cell) {
      for (int h = 0; h < g.numHeadings(); ++h)
        best[cell] = std::min(best[cell], exact[cell * g.numHeadings() + h]);
      finite += best[cell] < kInfiniteCost;
    }
    if (finite < 500) continue;  // a start boxed in: too little to check
    ++checked;
    const auto from = field(d, s.x, s.y, /*to_cell=*/false, s.x, s.y);
    int k = 0;
    for (int y = 0; y < g.height(); ++y) {
      for (int x = 0; x < g.width(); ++x) {
        const Cost b = best[static_cast<std::size_t>(y) * g.width() + x];
        if (b >= kInfiniteCost) continue;
        // Reached on the lattice, so reached by the grid, no dearer.
        ASSERT_NE(from->at(x, y), kInf) << x << "," << y;
        ASSERT_LE(static_cast<Cost>(from->at(x, y)), b) << x << "," << y << " seed " << seed;
        // Toward this cell, from s's: at most the exact cost from s.
        if (++k % 97 == 0) {
          const auto toward = field(d, x, y, /*to_cell=*/true, s.x, s.y);
          ASSERT_LE(static_cast<Cost>(toward->at(s.x, s.y)), b);
        }
      }
    }
  }
  EXPECT_EQ(checked, 3);
}

TEST(DisplacementGridTest, ConsistentAndAdmissibleOnGeneratedLattices) {
  for (unsigned seed : {3u, 4u, 5u, 6u}) {
    auto map = test::randomMap(100, 80, 0.05, seed, 25, 180);
    map->cost[40 * 100 + 50] = 0;
    const LatticeConfig c = test::smallRobot(seed);
    LatticeGraph g(map, c);
    DisplacementGrid d(g);
    ASSERT_GT(d.moveCount(), 8u);
    for (bool to_cell : {true, false}) {
      const auto f = field(d, 50, 40, to_cell, 10, 10);
      EXPECT_EQ(f->stop_key, std::numeric_limits<std::uint64_t>::max());
      EXPECT_EQ(f->at(50, 40), 0u);
      std::size_t edges = 0;
      EXPECT_TRUE(consistentOnEveryEdge(g, valueOf(*f), to_cell, &edges)) << "seed " << seed;
      EXPECT_GT(edges, 10000u);
    }
    expectAdmissible(g, d, seed);
  }
}

TEST(DisplacementGridTest, ConsistentOnTheCubicle) {
  AMHA_REQUIRE_SHARED_DATA(data);
  SbplEnvironment env;
  LatticeConfig c = test::cubicleConfig(data, &env);
  LatticeGraph g(std::make_shared<GridMap>(env.map), c);
  DisplacementGrid d(g);
  EXPECT_TRUE(consistentOnEveryEdge(g, valueOf(*field(d, 240, 80, true, 160, 320)), true));
  EXPECT_TRUE(consistentOnEveryEdge(g, valueOf(*field(d, 160, 320, false, 240, 80)), false));
}

// Stopped where its keys reach a bound, the field reads min(distance, bound - e): still
// consistent, at most the complete field, equal to it where the A* went.
TEST(DisplacementGridTest, StoppedAtABoundStaysConsistentAndBelow) {
  for (unsigned seed : {7u, 8u}) {
    auto map = test::randomMap(100, 80, 0.05, seed, 25, 180);
    map->cost[40 * 100 + 50] = 0;
    map->cost[8 * 100 + 12] = 0;
    LatticeGraph g(map, test::smallRobot(seed));
    DisplacementGrid d(g);
    const auto full = field(d, 50, 40, true, 12, 8);
    ASSERT_NE(full->at(12, 8), kInf);
    const std::uint64_t bound = full->at(12, 8) + 200;
    const auto part = field(d, 50, 40, true, 12, 8, bound);
    EXPECT_LE(part->stop_key, std::numeric_limits<std::uint64_t>::max() - 1);
    EXPECT_EQ(part->at(12, 8), full->at(12, 8));  // the cell it heads for is settled
    int below = 0;
    for (int y = 0; y < 80; ++y) {
      for (int x = 0; x < 100; ++x) {
        if (full->at(x, y) == kInf) continue;
        ASSERT_LE(part->at(x, y), full->at(x, y));
        below += part->at(x, y) < full->at(x, y);
      }
    }
    EXPECT_GT(below, 0) << "the bound cut nothing short";
    EXPECT_TRUE(consistentOnEveryEdge(g, valueOf(*part), true)) << "seed " << seed;
  }
}

// A mutation the check must catch: one more unit at a cell one move from the goal.
TEST(DisplacementGridTest, ARaisedEntryIsCaught) {
  auto map = test::randomMap(100, 80, 0.05, 9, 0, 0);
  LatticeGraph g(map, test::smallRobot(9));
  DisplacementGrid d(g);
  const auto f = field(d, 50, 40, true, 10, 10);
  ASSERT_TRUE(consistentOnEveryEdge(g, valueOf(*f), true));
  const LatticeAction& a = *g.actionsBegin(0);
  const int mx = 50 - a.dx, my = 40 - a.dy;  // the start of an action that ends at the goal
  const Value raised = [&](int x, int y) { return f->at(x, y) + ((x == mx && y == my) ? 1u : 0u); };
  EXPECT_FALSE(consistentOnEveryEdge(g, raised, true));
}

// On an empty map the cost along a straight primitive's direction is its cost per cell
// exactly, where the anchor's 16-connected grid is scaled below it.
TEST(DisplacementGridTest, ExactInScaleWhereTheGridIsScaled) {
  auto map = test::randomMap(160, 60, 0.05, 1, 0, 0);
  LatticeConfig c = test::smallRobot(1);
  c.cost.penalty = 0.0;
  c.heuristics.grid_anchor = true;
  LatticeGraph g(map, c);
  DisplacementGrid d(g);
  // The cheapest straight action along the x axis per cell, k of them back to back.
  const LatticeAction* straight = nullptr;
  for (const LatticeAction* a = g.actionsBegin(0); a != g.actionsEnd(0); ++a) {
    if (a->dy != 0 || a->dx <= 0 || a->end_heading != 0) continue;
    if (straight == nullptr || a->base_cost * straight->dx < straight->base_cost * a->dx)
      straight = a;
  }
  ASSERT_NE(straight, nullptr);
  const int k = 140 / straight->dx, from_x = 150 - k * straight->dx;
  const auto f = field(d, 150, 30, true, from_x, 30);
  EXPECT_EQ(static_cast<Cost>(f->at(from_x, 30)), k * straight->base_cost);
  HeuristicGridBuilder b(g);
  const DistanceGrid anchor = b.computeOne(GridKind::kAnchor, 150, 30);
  EXPECT_LT(anchor.at(from_x, 30) / kGridFraction, f->at(from_x, 30))
      << "the 16-connected grid is no longer scaled below the lattice?";
}

// The anchor with the field taken up: consistent on every edge, and the searches it serves
// return the same optimal costs.
TEST(DisplacementGridTest, AnchorWithItConsistentAndPlansTheSameCosts) {
  for (unsigned seed : {11u, 12u}) {
    auto map = test::randomMap(100, 80, 0.05, seed, 25, 180);
    map->cost[40 * 100 + 50] = 0;
    map->cost[10 * 100 + 10] = 0;
    LatticeConfig c = test::smallRobot(seed);
    auto g = std::make_shared<LatticeGraph>(map, c);
    HeuristicGridBuilder b(*g);
    DisplacementGrid d(*g);
    for (bool backward : {false, true}) {
      const LatticeState goal{50, 40, 2};
      auto heur = b.compute(goal.x, goal.y, goal.heading, false, 1, backward);
      LatticeProblem p(*g, heur, goal, goal, 0, backward);
      auto f = field(d, goal.x, goal.y, !backward, 10, 10);
      f->ready.store(true);
      p.setDisplacementField(f);
      ASSERT_TRUE(p.upgradeHeuristics());
      ASSERT_FALSE(p.upgradeHeuristics()) << "once";
      int edges = 0;
      EXPECT_TRUE(test::anchorConsistentOnEveryEdge(*g, p, backward, &edges));
      EXPECT_GT(edges, 10000);
    }
    // Planning with and without it: equal optimal costs (A* takes it up when it is ready).
    for (Algorithm algo : {Algorithm::kAStar, Algorithm::kAmhaStar, Algorithm::kAraStar}) {
      LatticeConfig on = c, off = c;
      on.heuristics.displacement_grid = true;
      off.heuristics.displacement_grid = false;
      LatticePlanner with(map, on), without(map, off);
      const Pose2D s = g->stateToPose(10, 10, 0), t = g->stateToPose(50, 40, 2);
      PlannerConfig pc = defaultConfig(algo);
      pc.check_invariants = true;
      const PlanResult a = with.plan(s, t, pc, SearchLimits());
      const PlanResult b2 = without.plan(s, t, pc, SearchLimits());
      ASSERT_EQ(a.hasSolution(), b2.hasSolution()) << algorithmName(algo);
      if (!a.hasSolution()) continue;
      EXPECT_EQ(a.best().search.cost, b2.best().search.cost) << algorithmName(algo);
      EXPECT_EQ(a.search.status, SearchStatus::kProvenOptimal);
    }
  }
}

}  // namespace
}  // namespace lattice
}  // namespace amha
