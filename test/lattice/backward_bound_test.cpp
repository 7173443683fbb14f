// The bidirectional proof (backward_bound.h): the backward search's expansions carry the exact
// cost to the goal (SearchProblem::expanded); the forward anchor at a snapshot of its key is
// consistent on every valid edge and 0 at the goal (so admissible) whether the backward search
// stopped early or ran on; a snapshot above the published key breaks the check; and planning
// with it returns the same optimal costs.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>

#include "amha_planner/lattice/detail/backward_bound.h"
#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/search/planner.h"
#include "anchor_checks.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

constexpr int kW = 100, kH = 80;

// A backward A* from t (its anchor measured from s) run until its key reaches `stop_at`, into a
// BackwardBound, as LatticePlanner's helper thread runs it.
std::shared_ptr<BackwardBound> runBackward(const LatticeGraph& g, const HeuristicGridBuilder& b,
                                           LatticeState s, LatticeState t, std::uint64_t stop_at) {
  auto grids = b.compute(s.x, s.y, s.heading, false, 1, /*backward=*/true);
  auto bb = std::make_shared<BackwardBound>();
  bb->width = g.width();
  bb->headings = g.numHeadings();
  bb->closed.reset(static_cast<std::size_t>(g.width()) * g.height() * g.numHeadings());
  bb->start_anchor.reset(new LatticeProblem(g, grids, t, s, 0, true));
  bb->bound.store(stop_at);
  LatticeProblem search(g, grids, t, s, 0, true);
  search.setBackwardSink(bb.get());
  SearchLimits limits;
  limits.cancel = &bb->stop;
  PlannerConfig pc = defaultConfig(Algorithm::kAStar);
  makePlanner(pc)->search(search, limits, [](const Solution&) {});
  bb->ready.store(true);
  return bb;
}

struct Case {
  std::shared_ptr<GridMap> map;
  std::unique_ptr<LatticeGraph> g;
  LatticeState s{10, 10, 0}, t{80, 60, 4};
  Cost optimum = kInfiniteCost;
};

// The case of the first seed from `seed` on whose goal the start reaches.
Case makeCase(unsigned seed) {
  for (;; ++seed) {
    Case c;
    c.map = test::randomMap(kW, kH, 0.05, seed, 25, 180);
    c.map->cost[static_cast<std::size_t>(c.s.y) * kW + c.s.x] = 0;
    c.map->cost[static_cast<std::size_t>(c.t.y) * kW + c.t.x] = 0;
    c.g.reset(new LatticeGraph(c.map, test::smallRobot(seed)));
    const std::vector<Cost> from_s = test::dijkstraFrom(
        *c.g, c.s, [&](int x, int y, const LatticeAction& a) { return c.g->edgeCost(x, y, a); });
    c.optimum =
        from_s[(static_cast<std::size_t>(c.t.y) * kW + c.t.x) * c.g->numHeadings() + c.t.heading];
    if (c.optimum < kInfiniteCost) return c;
  }
}

// Each closed entry is the exact cost to the goal (checked on a sample against Dijkstras from
// those states), and the key covers the states closed.
TEST(BackwardBoundTest, ExpansionsCarryTheExactCostToGo) {
  Case c = makeCase(21);
  ASSERT_LT(c.optimum, kInfiniteCost);
  HeuristicGridBuilder b(*c.g);
  const auto bb = runBackward(*c.g, b, c.s, c.t, UINT64_MAX);
  const int nh = c.g->numHeadings();
  std::mt19937 rng(5);
  int checked = 0, closed = 0;
  for (std::size_t i = 0; i < bb->closed.size(); ++i) closed += bb->closed[i] != 0;
  EXPECT_GT(closed, 1000);
  for (int tries = 0; tries < 20000 && checked < 12; ++tries) {
    const std::size_t i = rng() % bb->closed.size();
    if (bb->closed[i] == 0) continue;
    const LatticeState st{static_cast<int>((i / nh) % kW), static_cast<int>((i / nh) / kW),
                          static_cast<int>(i % nh)};
    const std::vector<Cost> from = test::dijkstraFrom(
        *c.g, st, [&](int x, int y, const LatticeAction& a) { return c.g->edgeCost(x, y, a); });
    const Cost exact = from[(static_cast<std::size_t>(c.t.y) * kW + c.t.x) * nh + c.t.heading];
    EXPECT_EQ(static_cast<Cost>(bb->closed[i] - 1), exact)
        << st.x << "," << st.y << "," << st.heading;
    ++checked;
  }
  EXPECT_EQ(checked, 12);
  // Run to the end, the search reached the start: its last key is at most the optimum, and
  // within the anchor's reach of it.
  EXPECT_LE(static_cast<Cost>(bb->key.load()), c.optimum);
  EXPECT_GE(static_cast<Cost>(bb->key.load()), static_cast<Cost>(0.9 * c.optimum));
}

// The anchor at a snapshot: consistent and 0 at the goal (hence admissible), with the backward
// search stopped short of the optimum or run to it; above the start's own anchor somewhere.
TEST(BackwardBoundTest, SnapshotsAreConsistentAndRaiseTheAnchor) {
  for (unsigned seed : {22u, 40u}) {
    Case c = makeCase(seed);
    ASSERT_LT(c.optimum, kInfiniteCost);
    HeuristicGridBuilder b(*c.g);
    auto forward = b.compute(c.t.x, c.t.y, c.t.heading, false, 1, false);
    for (double share : {0.98, 1.0}) {
      const auto stop_at = static_cast<std::uint64_t>(share * static_cast<double>(c.optimum));
      const auto bb = runBackward(*c.g, b, c.s, c.t, stop_at);
      LatticeProblem plain(*c.g, forward, c.s, c.t, 0, false);
      LatticeProblem p(*c.g, forward, c.s, c.t, 0, false);
      p.setBackwardBound(bb);
      ASSERT_TRUE(p.upgradeHeuristics());
      ASSERT_FALSE(p.upgradeHeuristics()) << "the key has not moved since";
      int edges = 0;
      EXPECT_TRUE(test::anchorConsistentOnEveryEdge(*c.g, p, false, &edges))
          << "seed " << seed << " share " << share;
      EXPECT_GT(edges, 10000);
      EXPECT_EQ(p.anchor(c.t.x, c.t.y, c.t.heading), 0u);
      EXPECT_LE(static_cast<Cost>(p.anchor(c.s.x, c.s.y, c.s.heading)), c.optimum);
      int raised = 0;
      for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
          for (int h = 0; h < c.g->numHeadings(); ++h) {
            if (!c.g->stateValid(x, y, h)) continue;
            ASSERT_GE(p.anchor(x, y, h), plain.anchor(x, y, h));
            raised += p.anchor(x, y, h) > plain.anchor(x, y, h);
          }
        }
      }
      EXPECT_GT(raised, 100) << "seed " << seed << " share " << share;
    }
  }
}

// A mutation the check must catch: a snapshot taken above the key the backward search
// published (as if states it had not closed were).
TEST(BackwardBoundTest, ASnapshotAboveThePublishedKeyIsCaught) {
  Case c = makeCase(22);
  HeuristicGridBuilder b(*c.g);
  auto forward = b.compute(c.t.x, c.t.y, c.t.heading, false, 1, false);
  const auto bb = runBackward(*c.g, b, c.s, c.t, static_cast<std::uint64_t>(0.9 * c.optimum));
  bb->key.store(bb->key.load() + static_cast<std::uint64_t>(0.08 * c.optimum));
  LatticeProblem p(*c.g, forward, c.s, c.t, 0, false);
  p.setBackwardBound(bb);
  ASSERT_TRUE(p.upgradeHeuristics());
  int edges = 0;
  EXPECT_FALSE(test::anchorConsistentOnEveryEdge(*c.g, p, false, &edges));
}

// Planning with it from the start of the search (0 s) and without: the same optimal costs.
TEST(BackwardBoundTest, PlansTheSameOptimalCosts) {
  for (unsigned seed : {24u, 25u}) {
    Case c = makeCase(seed);
    LatticeConfig on = c.g->config(), off = on;  // the seed makeCase settled on
    on.heuristics.bidirectional_after_s = 0.0;
    LatticePlanner with(c.map, on), without(c.map, off);
    const Pose2D s = c.g->stateToPose(c.s.x, c.s.y, c.s.heading),
                 t = c.g->stateToPose(c.t.x, c.t.y, c.t.heading);
    for (Algorithm algo : {Algorithm::kAStar, Algorithm::kAmhaStar, Algorithm::kAraStar}) {
      PlannerConfig pc = defaultConfig(algo);
      pc.check_invariants = true;
      const PlanResult a = with.plan(s, t, pc, SearchLimits());
      const PlanResult d = without.plan(s, t, pc, SearchLimits());
      ASSERT_EQ(a.hasSolution(), d.hasSolution()) << algorithmName(algo);
      if (!a.hasSolution()) continue;
      EXPECT_EQ(a.best().search.cost, d.best().search.cost) << algorithmName(algo);
      EXPECT_EQ(a.best().search.cost, c.optimum) << algorithmName(algo);
      EXPECT_EQ(a.search.status, SearchStatus::kProvenOptimal);
    }
  }
}

// On a map big enough that the backward search runs on its thread beside the forward one (A*
// takes up its snapshots every 1024 expansions): the same optimal cost, and no race (the name
// has "Thread": scripts/test runs it under ThreadSanitizer).
TEST(BackwardBoundTest, OnItsThreadBesideALongerSearchTheCostIsTheSame) {
  int planned = 0;
  for (unsigned seed = 31; seed < 45 && planned < 1; ++seed) {
    auto map = test::randomMap(320, 240, 0.05, seed, 60, 120);
    map->cost[10 * 320 + 10] = 0;
    map->cost[225 * 320 + 300] = 0;
    LatticeConfig on = test::smallRobot(seed), off = on;
    on.heuristics.bidirectional_after_s = 0.0;
    LatticePlanner with(map, on), without(map, off);
    const LatticeGraph& g = with.graph();
    const Pose2D s = g.stateToPose(10, 10, 0), t = g.stateToPose(300, 225, 4);
    const PlannerConfig pc = defaultConfig(Algorithm::kAStar);
    // The start's kinematic table ready, as the server and `amha plan` have it: the backward
    // search then starts within the forward one, whose anchor takes its snapshots (on this map
    // without fewer expansions: its key starts far below the optimum, where no term rises).
    ASSERT_TRUE(with.prepareKinematicTables(s, t, GoalOptions(), SearchLimits()));
    const PlanResult d = without.plan(s, t, pc, SearchLimits());
    if (!d.hasSolution()) continue;  // boxed in: another map
    const PlanResult a = with.plan(s, t, pc, SearchLimits());
    ASSERT_TRUE(a.hasSolution());
    EXPECT_EQ(a.best().search.cost, d.best().search.cost) << "seed " << seed;
    EXPECT_EQ(a.search.status, SearchStatus::kProvenOptimal);
    ++planned;
  }
  EXPECT_EQ(planned, 1);
}

}  // namespace
}  // namespace lattice
}  // namespace amha
