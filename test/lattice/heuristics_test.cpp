// Heuristic grids against an independent Dijkstra, and the anchor's consistency and
// admissibility on the real lattice (random edges; exhaustive cost-to-go on small maps).
#include <cmath>
#include <queue>
#include <random>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/map_loaders.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

TEST(GridMovesTest, RequiredCells) {
  const auto m8 = gridMoves(8);
  const auto m16 = gridMoves(16);
  ASSERT_EQ(m8.size(), 8u);
  ASSERT_EQ(m16.size(), 16u);
  for (const GridMove& m : m16) {
    const int adx = std::abs(m.dx), ady = std::abs(m.dy);
    const std::size_t expected =
        adx + ady == 1 ? 2 : 4;  // straight: the two ends; diagonal/knight: 4 cells
    EXPECT_EQ(m.required.size(), expected) << m.dx << "," << m.dy;
  }
}

// Plain Dijkstra with a binary heap over the same rules (8-connected; a diagonal step needs one
// passable side cell and pays for the cheaper one; cost = floor(units x length x (1 + P c / 252)
// x fraction)), written independently.
std::vector<std::uint64_t> referenceGrid(const GridMap& m, int gx, int gy, double units, double pen,
                                         int max_class) {
  const int w = m.width, h = m.height;
  auto passable = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && m.at(x, y) <= max_class;
  };
  std::vector<std::uint64_t> d(static_cast<std::size_t>(w) * h, UINT64_MAX);
  using Item = std::pair<std::uint64_t, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  if (!passable(gx, gy)) return d;
  d[gy * w + gx] = 0;
  q.push({0, gy * w + gx});
  while (!q.empty()) {
    const auto [dist, i] = q.top();
    q.pop();
    if (dist != d[i]) continue;
    const int x = i % w, y = i / w;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int nx = x + dx, ny = y + dy;
        if (!passable(nx, ny)) continue;
        int c = std::max<int>(m.at(x, y), m.at(nx, ny));
        if (dx != 0 && dy != 0) {
          const bool a = passable(x + dx, y), b = passable(x, y + dy);
          if (!a && !b) continue;
          const int side = a && b ? std::min<int>(m.at(x + dx, y), m.at(x, y + dy))
                           : a    ? m.at(x + dx, y)
                                  : m.at(x, y + dy);
          c = std::max(c, side);
        }
        const double step =
            units * std::hypot(dx, dy) * (1.0 + pen * std::min(c, 252) / 252.0) * kGridFraction;
        const std::uint64_t nd = dist + static_cast<std::uint64_t>(std::floor(step));
        if (nd < d[ny * w + nx]) {
          d[ny * w + nx] = nd;
          q.push({nd, ny * w + nx});
        }
      }
    }
  }
  return d;
}

TEST(HeuristicGridTest, PointRobotGridEqualsReferenceDijkstra) {
  for (unsigned seed : {1u, 2u, 3u}) {
    auto map = test::randomMap(70, 50, 0.05, seed, 25, seed == 3 ? 0 : 200);
    const int gx = 35, gy = 25;
    map->cost[gy * map->width + gx] = 0;
    LatticeConfig c;
    c.motion.turning_radius = 0.2;
    c.robot.radius = 0.0;
    c.cost.penalty = seed == 2 ? 252.0 : 3.0;
    c.heuristics.grid_anchor = false;
    c.heuristics.num_inadmissible = 1;
    LatticeGraph g(map, c);
    HeuristicGridBuilder b(g);
    const DistanceGrid grid = b.computeOne(GridKind::kPointRobot, gx, gy);
    const auto ref =
        referenceGrid(*map, gx, gy, g.cheapestUnitsPerCell(), c.cost.penalty, kLethalCost - 1);
    for (int y = 0; y < map->height; ++y) {
      for (int x = 0; x < map->width; ++x) {
        const std::uint64_t r = ref[y * map->width + x];
        const std::uint32_t v = grid.at(x, y);
        if (r == UINT64_MAX) {
          ASSERT_EQ(v, kUnreachable) << x << "," << y;
        } else {
          ASSERT_EQ(v, r) << x << "," << y;
        }
      }
    }
  }
}

// The same with any moves (gridMoves' required cells: all of them, or for a diagonal the two
// ends and one side cell), written independently of the builder's unrolled loops.
// `units`: cost units per cell of length, per move.
std::vector<std::uint64_t> referenceGridMoves(const GridMap& m, int gx, int gy,
                                              const std::vector<double>& units, double pen,
                                              int max_class, const std::vector<GridMove>& moves) {
  const int w = m.width, h = m.height;
  auto passable = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && m.at(x, y) <= max_class;
  };
  std::vector<std::uint64_t> d(static_cast<std::size_t>(w) * h, UINT64_MAX);
  using Item = std::pair<std::uint64_t, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  if (!passable(gx, gy)) return d;
  d[gy * w + gx] = 0;
  q.push({0, gy * w + gx});
  while (!q.empty()) {
    const auto [dist, i] = q.top();
    q.pop();
    if (dist != d[i]) continue;
    const int x = i % w, y = i / w;
    for (std::size_t k = 0; k < moves.size(); ++k) {
      const GridMove& mv = moves[k];
      int c = -1, side = 256;
      bool ok = true;
      for (const CellOffset& r : mv.required) {
        const bool end = (r.dx == 0 && r.dy == 0) || (r.dx == mv.dx && r.dy == mv.dy);
        const int cx = x + r.dx, cy = y + r.dy;
        if (end || !mv.either_side) {
          if (!passable(cx, cy))
            ok = false;
          else
            c = std::max<int>(c, m.at(cx, cy));
        } else if (passable(cx, cy)) {
          side = std::min<int>(side, m.at(cx, cy));
        }
      }
      if (!ok || (mv.either_side && side == 256)) continue;
      if (mv.either_side) c = std::max(c, side);
      const double step =
          units[k] * mv.length * (1.0 + pen * std::min(c, 252) / 252.0) * kGridFraction;
      const std::uint64_t nd = dist + static_cast<std::uint64_t>(std::floor(step));
      const int j = (y + mv.dy) * w + (x + mv.dx);
      if (nd < d[j]) {
        d[j] = nd;
        q.push({nd, j});
      }
    }
  }
  return d;
}

// The anchor's grid, 8- and 16-connected (the builder's unrolled loops), against the reference.
TEST(HeuristicGridTest, AnchorGridEqualsReferenceDijkstraForBothConnectivities) {
  for (const int connectivity : {8, 16}) {
    for (unsigned seed : {4u, 5u, 6u}) {
      auto map = test::randomMap(70, 50, 0.05, seed, 25, seed == 6 ? 0 : 200);
      const int gx = 35, gy = 25;
      map->cost[gy * map->width + gx] = 0;
      for (int k = 0; k < 60; ++k)
        map->cost[(seed * 7919 + k * 104729) % map->cost.size()] = kInscribedCost;
      LatticeConfig c;
      c.motion.turning_radius = 0.2;
      if (seed == 4) {  // Smac's kind of set: the grid's diagonal steps scaled above the rest
        c.motion.turning_radius = 0.5;
        c.motion.model = MotionModel::kAckermann;
        c.motion.turn_in_place = false;
      }
      c.robot.radius = 0.0;
      c.cost.penalty = seed == 5 ? 252.0 : 3.0;
      c.heuristics.anchor_connectivity = connectivity;
      c.heuristics.coarse_anchor = false;
      c.heuristics.num_inadmissible = 0;
      LatticeGraph g(map, c);
      HeuristicGridBuilder b(g);
      const DistanceGrid grid = b.computeOne(GridKind::kAnchor, gx, gy);
      const auto ref = referenceGridMoves(*map, gx, gy, g.gridAnchorMoveUnits(), c.cost.penalty,
                                          kInscribedCost - 1, gridMoves(connectivity));
      for (int y = 0; y < map->height; ++y) {
        for (int x = 0; x < map->width; ++x) {
          const std::uint64_t r = ref[y * map->width + x];
          const std::uint32_t v = grid.at(x, y);
          ASSERT_EQ(v, r == UINT64_MAX ? kUnreachable : r)
              << connectivity << "-connected, seed " << seed << " at " << x << "," << y;
        }
      }
    }
  }
}

struct LatticeFixture {
  std::shared_ptr<GridMap> map;
  std::unique_ptr<LatticeGraph> graph;
  std::unique_ptr<HeuristicGridBuilder> builder;
};

LatticeFixture makeFixture(std::shared_ptr<GridMap> map, const LatticeConfig& c) {
  LatticeFixture f;
  f.map = std::move(map);
  f.graph.reset(new LatticeGraph(f.map, c));
  f.builder.reset(new HeuristicGridBuilder(*f.graph));
  return f;
}

// h0(p) <= cost(p, q) + h0(q) for every valid edge p -> q out of many random valid states, and
// for backward search (tables measuring the distance from `goal`, used as the search's target)
// h0(q) <= cost(p, q) + h0(p).
void checkConsistencyOnRandomEdges(const LatticeFixture& f, LatticeState goal, int samples,
                                   unsigned seed, bool backward = false) {
  auto heur = f.builder->compute(goal.x, goal.y, goal.heading, true, 0, backward);
  LatticeProblem p(*f.graph, heur, goal, goal, 3, backward);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> rx(0, f.map->width - 1), ry(0, f.map->height - 1),
      rh(0, f.graph->numHeadings() - 1);
  int edges = 0;
  EXPECT_EQ(p.anchor(goal.x, goal.y, goal.heading), 0u);
  for (int k = 0; k < samples; ++k) {
    const int x = rx(rng), y = ry(rng), h = rh(rng);
    if (!f.graph->stateValid(x, y, h)) continue;
    for (const LatticeAction* a = f.graph->actionsBegin(h); a != f.graph->actionsEnd(h); ++a) {
      const Cost c = f.graph->edgeCost(x, y, *a);
      if (c == kInvalidEdge) continue;
      // With the inflation base (the heading-blind part, LatticeProblem::hasInflationBases),
      // which must be consistent too and at most the anchor.
      HeuristicValue bp = 0, bq = 0;
      HeuristicValue hp = p.anchor(x, y, h, &bp);
      HeuristicValue hq = p.anchor(x + a->dx, y + a->dy, a->end_heading, &bq);
      if (backward) std::swap(hp, hq), std::swap(bp, bq);  // the search moves from q to p
      ++edges;
      if (hq == kInfiniteHeuristic) {
        ASSERT_EQ(hp, kInfiniteHeuristic) << "a state that reaches a dead end must be a dead end";
        continue;
      }
      ASSERT_NE(hp, kInfiniteHeuristic)
          << "infinite h at (" << x << "," << y << "," << h << ") with a finite successor";
      ASSERT_LE(static_cast<Cost>(hp), c + static_cast<Cost>(hq))
          << "(" << x << "," << y << "," << h << ") -> (" << x + a->dx << "," << y + a->dy << ","
          << a->end_heading << ") backward " << backward;
      ASSERT_LE(bp, hp);
      ASSERT_LE(static_cast<Cost>(bp), c + static_cast<Cost>(bq)) << "inflation base inconsistent";
    }
  }
  EXPECT_GT(edges, samples / 4);
}

TEST(AnchorTest, ConsistentOnRandomEdgesOfGeneratedLattices) {
  for (unsigned seed : {11u, 12u}) {
    for (int variant = 0; variant < 3; ++variant) {
      const bool grid = variant < 2;
      auto map = test::randomMap(120, 90, 0.05, seed, 30, 180);
      LatticeConfig c;
      c.heuristics.anchor_turn_term = variant != 1;
      c.motion.turning_radius = 0.3;
      c.motion.allow_reverse = seed == 12;
      c.robot.footprint = test::rectangle(0.12, 0.08);
      c.cost.penalty = seed == 11 ? 252.0 : 2.0;
      c.cost.time_to_turn_45 = seed == 11 ? 3.0 : 0.6;
      c.heuristics.grid_anchor = grid;
      map->cost[45 * 120 + 60] = 0;
      LatticeFixture f = makeFixture(map, c);
      LatticeState goal{60, 45, 3};
      checkConsistencyOnRandomEdges(f, goal, 4000, seed);
      checkConsistencyOnRandomEdges(f, goal, 4000, seed, true);
    }
  }
}

TEST(AnchorTest, ConsistentOnRandomEdgesOfTheCubicle) {
  AMHA_REQUIRE_SHARED_DATA(data);
  SbplEnvironment env;
  LatticeConfig c = test::cubicleConfig(data, &env);
  for (bool turn_term : {false, true}) {
    c.heuristics.anchor_turn_term = turn_term;
    LatticeFixture f = makeFixture(std::make_shared<GridMap>(env.map), c);
    checkConsistencyOnRandomEdges(f, LatticeState{240, 80, 0}, 20000, 5);
    checkConsistencyOnRandomEdges(f, LatticeState{160, 320, 0}, 20000, 6, true);
  }
}

// Weighted A* (epsilon = 3) on SBPL's cubicle with the PR2's primitives (turns in place):
// with the heading-aware terms inflated, its first path costs many more expansions, as turning
// early pays (LatticeConfig::Heuristics::inflate_heading_terms); both paths stay within the bound.
TEST(AnchorTest, HeadingTermsCountedOnceSaveWeightedExpansions) {
  AMHA_REQUIRE_SHARED_DATA(data);
  SbplEnvironment env;
  auto cubicle = std::make_shared<GridMap>(
      loadMapFile(data + "/sbpl/cubicle-25mm-inflated-env.cfg", 0, 1, {}, &env));
  LatticeConfig c;
  c.motion.mprim_file = data + "/sbpl/pr2.mprim";
  c.robot.footprint = test::rectangle(0.01, 0.01);
  useSbplCostModel(env, c);
  PlannerConfig wastar = defaultConfig(Algorithm::kWeightedAStar);
  wastar.w1 = 3.0;
  std::uint64_t expansions[2] = {0, 0};
  Cost costs[2] = {0, 0};
  for (int inflate = 0; inflate < 2; ++inflate) {
    c.heuristics.inflate_heading_terms = inflate == 1;
    LatticePlanner planner(cubicle, c);
    const PlanResult r = planner.plan(env.start, env.goal, wastar, SearchLimits());
    ASSERT_FALSE(r.solutions.empty());
    expansions[inflate] = r.solutions.front().search.expansions;
    costs[inflate] = r.solutions.front().search.cost;
    EXPECT_LE(r.solutions.front().search.certified_bound, 3.0);
  }
  std::printf(
      "[ weighted ] cubicle, epsilon 3: %llu expansions (cost %lld) with the heading terms once, "
      "%llu "
      "(cost %lld) inflated\n",
      static_cast<unsigned long long>(expansions[0]), static_cast<long long>(costs[0]),
      static_cast<unsigned long long>(expansions[1]), static_cast<long long>(costs[1]));
  EXPECT_LT(expansions[0] * 3, expansions[1] * 2);
}

// Without its turning term the anchor stays consistent (forward and backward), no longer
// depends on the heading at a cell, and never exceeds the anchor with the term.
TEST(AnchorTest, WithoutTurnTermConsistentAndHeadingFree) {
  for (bool coarse : {false, true}) {
    auto map = test::randomMap(120, 90, 0.05, 11, 30, 180);
    LatticeConfig c;
    c.motion.turning_radius = 0.3;
    c.robot.footprint = test::rectangle(0.12, 0.08);
    c.cost.penalty = 252.0;
    c.cost.time_to_turn_45 = 3.0;
    c.heuristics.coarse_anchor = coarse;
    map->cost[45 * 120 + 60] = 0;
    c.heuristics.anchor_turn_term = true;
    LatticeFixture with = makeFixture(map, c);
    c.heuristics.anchor_turn_term = false;
    LatticeFixture without = makeFixture(map, c);
    const LatticeState goal{60, 45, 3};
    checkConsistencyOnRandomEdges(without, goal, 4000, 11);
    checkConsistencyOnRandomEdges(without, goal, 4000, 12, true);
    auto hw = with.builder->compute(goal.x, goal.y, goal.heading);
    auto ho = without.builder->compute(goal.x, goal.y, goal.heading);
    LatticeProblem pw(*with.graph, hw, goal, goal, 3), po(*without.graph, ho, goal, goal, 3);
    int differs = 0;
    for (int y = 0; y < map->height; y += 3) {
      for (int x = 0; x < map->width; x += 3) {
        for (int h = 0; h < with.graph->numHeadings(); ++h) {
          const HeuristicValue a = pw.anchor(x, y, h), b = po.anchor(x, y, h);
          if (a == kInfiniteHeuristic) {
            EXPECT_EQ(b, kInfiniteHeuristic);
            continue;
          }
          ASSERT_LE(b, a) << x << "," << y << "," << h;
          differs += b < a;
          // Without the term and without the abstraction (which knows headings), h depends on the
          // cell only.
          if (!coarse) {
            ASSERT_EQ(b, po.anchor(x, y, 0)) << x << "," << y << "," << h;
          }
        }
      }
    }
    EXPECT_GT(differs, 0) << "the turning term changed nothing";
  }
}

// Exhaustive cost-to-go on a small lattice (reverse Dijkstra over all edges): h0 never exceeds it.
// The exact cost-to-go of every lattice state to `goal` (Dijkstra on the reversed edges),
// indexed ((y * width + x) * headings + heading).
std::vector<Cost> exactCostToGo(const LatticeGraph& g, const LatticeState& goal) {
  const int n = g.numHeadings(), w = g.width(), h = g.height();
  auto index = [&](int x, int y, int k) { return (static_cast<std::size_t>(y) * w + x) * n + k; };
  const std::size_t total = static_cast<std::size_t>(w) * h * n;
  std::vector<std::vector<std::pair<std::size_t, Cost>>> reverse(total);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < n; ++k)
        for (const LatticeAction* a = g.actionsBegin(k); a != g.actionsEnd(k); ++a) {
          const Cost cost = g.edgeCost(x, y, *a);
          if (cost != kInvalidEdge)
            reverse[index(x + a->dx, y + a->dy, a->end_heading)].push_back({index(x, y, k), cost});
        }
  std::vector<Cost> togo(total, kInfiniteCost);
  using Item = std::pair<Cost, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  togo[index(goal.x, goal.y, goal.heading)] = 0;
  q.push({0, index(goal.x, goal.y, goal.heading)});
  while (!q.empty()) {
    const auto [d, i] = q.top();
    q.pop();
    if (d != togo[i]) continue;
    for (const auto& [j, cost] : reverse[i]) {
      if (d + cost < togo[j]) {
        togo[j] = d + cost;
        q.push({togo[j], j});
      }
    }
  }
  return togo;
}

// h0 <= the exact cost-to-go at every state that reaches the goal; returns the mean of h0 / it.
double expectAdmissible(const LatticeFixture& f, const LatticeState& goal,
                        const std::vector<Cost>& togo) {
  auto heur = f.builder->compute(goal.x, goal.y, goal.heading);
  LatticeProblem p(*f.graph, heur, goal, goal, 3);
  const int n = f.graph->numHeadings();
  int reachable = 0, tight = 0;
  double ratio_sum = 0.0;
  for (int y = 0; y < f.map->height; ++y)
    for (int x = 0; x < f.map->width; ++x)
      for (int h = 0; h < n; ++h) {
        const HeuristicValue hv = p.anchor(x, y, h);
        const Cost t = togo[(static_cast<std::size_t>(y) * f.map->width + x) * n + h];
        if (t == kInfiniteCost) continue;
        ++reachable;
        EXPECT_NE(hv, kInfiniteHeuristic) << x << "," << y << "," << h;
        EXPECT_LE(static_cast<Cost>(hv), t) << x << "," << y << "," << h;
        if (hv == kInfiniteHeuristic || static_cast<Cost>(hv) > t) return 0.0;
        tight += hv * 10 >= t * 7;
        ratio_sum += static_cast<double>(hv) / std::max<Cost>(1, t);
      }
  std::printf("anchor / cost-to-go: mean %.3f, within 70%%: %d of %d\n", ratio_sum / reachable,
              tight, reachable);
  EXPECT_GT(reachable, 1000);
  return ratio_sum / reachable;
}

TEST(AnchorTest, AdmissibleAgainstExactCostToGo) {
  auto map = test::randomMap(40, 30, 0.05, 21, 10, 120);
  LatticeConfig c;
  c.motion.turning_radius = 0.25;
  c.motion.allow_reverse = true;
  c.robot.footprint = test::rectangle(0.07, 0.05);
  c.cost.penalty = 5.0;
  c.cost.time_to_turn_45 = 1.5;
  map->cost[15 * 40 + 20] = 0;
  LatticeFixture f = makeFixture(map, c);
  const LatticeState goal{20, 15, 5};
  ASSERT_TRUE(f.graph->stateValid(goal.x, goal.y, goal.heading));
  const std::vector<Cost> togo = exactCostToGo(*f.graph, goal);
  for (bool turn_term : {false, true}) {
    c.heuristics.anchor_turn_term = turn_term;
    EXPECT_GT(expectAdmissible(makeFixture(map, c), goal, togo), 0.2);  // it carries information
  }
}

// Smac's kind of set (16 headings, Ackermann, 0.5 m at 5 cm), our generator's: one scale for
// every move of the anchor's grid is held down by a turn whose knight-move walk is longer than
// its arc, and the diagonal steps then rise above it (LatticeGraph::computeAnchorScales).
LatticeConfig ackermannConfig() {
  LatticeConfig c;
  c.motion.turning_radius = 0.5;
  c.motion.model = MotionModel::kAckermann;
  c.motion.turn_in_place = false;
  c.robot.radius = 0.0;
  c.cost.penalty = 1.0;
  return c;
}

// Each class of move at the largest scale under which every action's centre cells still hold a
// walk no costlier than the action (what makes the grid a relaxation), and none below the one
// uniform scale; the mutation: any class raised by 0.2 % (below the Euclidean scale, the cap)
// breaks that for some action.
TEST(AnchorMoveScalesTest, EachClassAtTheLargestScaleTheActionsAllow) {
  auto map = test::randomMap(60, 60, 0.05, 3, 0, 0);
  LatticeConfig c = ackermannConfig();
  c.heuristics.anchor_move_scales = false;
  const LatticeGraph uniform(map, c);
  c.heuristics.anchor_move_scales = true;
  const LatticeGraph g(map, c);
  const std::vector<GridMove> moves = gridMoves(c.heuristics.anchor_connectivity);
  const std::vector<double>& units = g.gridAnchorMoveUnits();
  ASSERT_EQ(units.size(), moves.size());
  ASSERT_EQ(uniform.gridAnchorMoveUnits().size(), moves.size());
  const double u = uniform.gridAnchorMoveUnits()[0];
  bool raised = false;
  for (std::size_t m = 0; m < moves.size(); ++m) {
    EXPECT_DOUBLE_EQ(uniform.gridAnchorMoveUnits()[m], u) << "one scale for all";
    EXPECT_GE(units[m], u) << "move " << m;
    EXPECT_LE(units[m], g.cheapestUnitsPerCell()) << "move " << m;
    raised = raised || units[m] > u * 1.005;
  }
  EXPECT_TRUE(raised) << "this set lets some class of move rise";
  auto fits = [&](const std::vector<double>& sc) {
    std::vector<GridMove> scaled = moves;
    for (std::size_t m = 0; m < moves.size(); ++m) scaled[m].length *= sc[m];
    for (std::size_t i = 0; i < g.actions().size(); ++i) {
      const LatticeAction& a = g.actions()[i];
      if (a.dx == 0 && a.dy == 0) continue;
      const double w = walkLength(g.actionCells(i).centre, CellOffset{a.dx, a.dy}, scaled);
      if (std::isfinite(w) && w > static_cast<double>(a.base_cost)) return false;
    }
    return true;
  };
  EXPECT_TRUE(fits(units));
  for (const double len : {1.0, std::sqrt(2.0), std::sqrt(5.0)}) {
    std::vector<double> more = units;
    bool capped = false;
    for (std::size_t m = 0; m < moves.size(); ++m) {
      if (std::abs(moves[m].length - len) > 1e-9) continue;
      more[m] *= 1.002;
      capped = capped || more[m] > g.cheapestUnitsPerCell();
    }
    if (!capped) {
      EXPECT_FALSE(fits(more)) << "the class of length " << len << " could rise";
    }
  }
}

// The grid alone as the anchor (no block abstraction, no kinematic table), with the raised
// classes: admissible against the exact cost-to-go, consistent on random edges both ways, and
// nowhere below the uniform grid, above it on many states.
TEST(AnchorMoveScalesTest, GridAnchorAdmissibleConsistentAndAboveTheUniformOne) {
  auto map = test::randomMap(48, 40, 0.05, 8, 8, 200);
  LatticeConfig c = ackermannConfig();
  c.cost.penalty = 3.0;
  c.heuristics.coarse_anchor = false;
  c.heuristics.kinematic_radius = 0.0;
  const LatticeState goal{24, 20, 2};
  map->cost[goal.y * map->width + goal.x] = 0;
  LatticeFixture f = makeFixture(map, c);
  ASSERT_TRUE(f.graph->stateValid(goal.x, goal.y, goal.heading));
  const std::vector<Cost> togo = exactCostToGo(*f.graph, goal);
  const double mean = expectAdmissible(f, goal, togo);
  checkConsistencyOnRandomEdges(f, goal, 6000, 3);
  checkConsistencyOnRandomEdges(f, goal, 6000, 4, true);
  c.heuristics.anchor_move_scales = false;
  LatticeFixture fu = makeFixture(map, c);
  const double mean_uniform = expectAdmissible(fu, goal, togo);
  EXPECT_GT(mean, mean_uniform);
  auto heur = f.builder->compute(goal.x, goal.y, goal.heading);
  auto heur_u = fu.builder->compute(goal.x, goal.y, goal.heading);
  LatticeProblem p(*f.graph, heur, goal, goal, 3), pu(*fu.graph, heur_u, goal, goal, 3);
  int above = 0;
  for (int y = 0; y < map->height; ++y)
    for (int x = 0; x < map->width; ++x) {
      const HeuristicValue h = p.anchor(x, y, 0), hu = pu.anchor(x, y, 0);
      if (hu == kInfiniteHeuristic) continue;
      ASSERT_GE(h, hu) << x << "," << y;
      above += h > hu;
    }
  EXPECT_GT(above, map->width * map->height / 10);
}

TEST(HeuristicGridTest, GoalsCachedAndGridsShared) {
  auto map = test::randomMap(60, 60, 0.05, 4, 0, 0);  // no obstacles: the openings equal free space
  LatticeConfig c;
  c.robot.radius = 0.0;
  LatticeFixture f = makeFixture(map, c);
  auto h = f.builder->compute(10, 10, 0);
  ASSERT_TRUE(h->grids[1] && h->grids[2] && h->grids[3]);
  EXPECT_EQ(h->grids[1], h->grids[2]);  // identical levels: computed once
  EXPECT_EQ(h->grids[2], h->grids[3]);
  EXPECT_EQ(h->grids[0]->at(10, 10), 0u);
}

}  // namespace
}  // namespace lattice
}  // namespace amha
