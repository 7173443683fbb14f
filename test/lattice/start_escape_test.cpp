// A start in collision (StartOptions, StartEscape): every algorithm's solutions against an
// exhaustive Dijkstra over the relaxed problem, their escapes checked by the independent
// validator on a map that encodes the rule, and LatticePlanner::plan with a start tolerance end
// to end (messages, errors, a free start unchanged, backward search refused, cancel).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/detail/start_escape.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/path_smoother.h"
#include "path_validator.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

constexpr double kTolerance = 0.3;  // metres: 6 cells of the 0.05 m test maps
constexpr double kPenalty = 2.0;

// randomMap with an inflation: free cells next to an obstacle become inscribed (253).
std::shared_ptr<GridMap> inflatedMap(unsigned seed) {
  auto m = test::randomMap(34, 34, 0.05, seed, 9, seed % 2 ? 120 : 0);
  const GridMap copy = *m;
  for (int y = 0; y < m->height; ++y) {
    for (int x = 0; x < m->width; ++x) {
      if (copy.at(x, y) >= kLethalCost) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < m->width && ny < m->height &&
              copy.at(nx, ny) >= kLethalCost) {
            m->cost[static_cast<std::size_t>(y) * m->width + x] = kInscribedCost;
          }
        }
      }
    }
  }
  return m;
}

// The lethal and unknown cells under the robot at s (the rule's "cells it already stands on").
std::vector<std::size_t> cellsUnder(const LatticeGraph& g, const LatticeState& s) {
  std::vector<std::size_t> out;
  for (const CellOffset& c :
       footprintCells(g.footprint(), Pose2D{0, 0, g.primitives().heading_angles[s.heading]},
                      g.map().resolution)) {
    const int x = s.x + c.dx, y = s.y + c.dy;
    if (x >= 0 && y >= 0 && x < g.width() && y < g.height() && g.map().at(x, y) >= kLethalCost) {
      out.push_back(static_cast<std::size_t>(y) * g.width() + x);
    }
  }
  return out;
}

// The rule written out again: an escape motion from (x, y) by action i, or -1.
Cost ruleCost(const LatticeGraph& g, const std::vector<std::size_t>& under, int x, int y,
              std::size_t i) {
  const LatticeAction& a = g.actions()[i];
  const PrimitiveCells& cells = g.actionCells(i);
  for (const auto* list : {&cells.centre, &cells.swept}) {
    for (const CellOffset& c : *list) {
      const int cx = x + c.dx, cy = y + c.dy;
      if (cx < 0 || cy < 0 || cx >= g.width() || cy >= g.height()) return -1;
      const std::size_t k = static_cast<std::size_t>(cy) * g.width() + cx;
      if (g.map().cost[k] >= kLethalCost && std::find(under.begin(), under.end(), k) == under.end())
        return -1;
    }
  }
  return static_cast<Cost>(
      std::ceil(kPenalty * static_cast<double>(g.costWithPenalty(a.base_cost, 252)) - 1e-9));
}

// The relaxed problem's optimal cost from s (in collision) to t, by Dijkstra over every state:
// escape motions out of states in collision within the tolerance, the graph's edges elsewhere.
Cost relaxedOptimum(const LatticeGraph& g, const LatticeState& s, const LatticeState& t) {
  const std::vector<std::size_t> under = cellsUnder(g, s);
  const std::vector<Cost> d =
      test::dijkstraFrom(g, s, [&](int x, int y, const LatticeAction& a) -> Cost {
        if (g.stateValid(x, y, a.start_heading)) return g.edgeCost(x, y, a);
        if (std::hypot(x + a.dx - s.x, y + a.dy - s.y) * g.map().resolution > kTolerance + 1e-9)
          return -1;
        return ruleCost(g, under, x, y, static_cast<std::size_t>(&a - g.actions().data()));
      });
  return d[(static_cast<std::size_t>(t.y) * g.width() + t.x) * g.numHeadings() + t.heading];
}

// The map the independent validator checks escape motions on: the obstacle cells under the
// start become ordinary cells, and every cell a centre may cross costs 252, so a motion it
// accepts obeys the rule and it charges what an escape motion costs before the penalty.
GridMap escapeRuleMap(const LatticeGraph& g, const LatticeState& s) {
  GridMap m = g.map();
  for (auto& c : m.cost) {
    if (c <= kInscribedCost) c = 252;
  }
  for (std::size_t k : cellsUnder(g, s)) m.cost[k] = 252;
  return m;
}

LatticeState randomState(const LatticeGraph& g, std::mt19937& rng) {
  return {static_cast<int>(rng() % g.width()), static_cast<int>(rng() % g.height()),
          static_cast<int>(rng() % g.numHeadings())};
}

TEST(StartEscape, SolutionsAgainstAnExhaustiveDijkstraOfTheRelaxedProblem) {
  const Algorithm all[] = {Algorithm::kAStar,   Algorithm::kAmhaStar, Algorithm::kMhaStar,
                           Algorithm::kAraStar, Algorithm::kAnaStar,  Algorithm::kWeightedAStar};
  int queries = 0, solved = 0, multi_step = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const auto map = inflatedMap(seed);
    const LatticeGraph g(map, test::smallRobot(seed));
    const HeuristicGridBuilder b(g);
    const test::ValidatorModel model = test::modelFor(g);
    std::mt19937 rng(seed * 7);
    for (int q = 0, tries = 0; q < 3 && tries < 2000; ++tries) {
      const LatticeState s = randomState(g, rng), t = randomState(g, rng);
      if (g.stateValid(s.x, s.y, s.heading) || !g.stateValid(t.x, t.y, t.heading)) continue;
      StopCondition no_stop;
      const StartEscape escape(g, s, kTolerance, kPenalty, &no_stop);
      if (escape.outcome() != StartEscape::Outcome::kFound) continue;
      ++q;
      ++queries;
      const Cost optimal = relaxedOptimum(g, s, t);
      const GridMap rule_map = escapeRuleMap(g, s);
      test::ValidatorModel rule_model = model;
      rule_model.map = &rule_map;
      std::vector<std::pair<LatticeState, Cost>> exits;
      for (const StartEscape::Exit& e : escape.exits()) exits.emplace_back(e.state, e.cost);
      for (const Algorithm alg : all) {
        auto grids = b.compute(t.x, t.y, t.heading, true, 1, false);
        LatticeProblem p(g, grids, s, t, 3);
        p.startAtExits(exits);
        SearchLimits limits;
        limits.time_limit_s = 10;
        const SearchResult r =
            makePlanner(defaultConfig(alg))->search(p, limits, [&](const Solution& sol) {
              ASSERT_GE(sol.path.size(), 2u);
              ASSERT_EQ(sol.path.front(), p.virtualStart());
              std::vector<LatticeState> rest;
              for (std::size_t k = 1; k < sol.path.size(); ++k)
                rest.push_back(p.state(sol.path[k]));
              const StartEscape::Exit* exit = escape.exitAt(rest.front());
              ASSERT_NE(exit, nullptr);
              // The escape: from s, each motion out of a state in collision within the tolerance,
              // valid on the rule's map, costing the penalty times its cost there.
              const std::vector<StartEscape::Step> steps = escape.path(*exit);
              ASSERT_FALSE(steps.empty());
              ASSERT_TRUE(steps.front().from == s);
              Cost escape_cost = 0;
              for (std::size_t k = 0; k < steps.size(); ++k) {
                const LatticeState& a = steps[k].from;
                const LatticeAction& act = *steps[k].action;
                const LatticeState to{a.x + act.dx, a.y + act.dy, act.end_heading};
                ASSERT_FALSE(g.stateValid(a.x, a.y, a.heading))
                    << "an escape goes on only while in collision";
                ASSERT_LE(std::hypot(to.x - s.x, to.y - s.y) * 0.05, kTolerance + 1e-9);
                ASSERT_TRUE(to == (k + 1 < steps.size() ? steps[k + 1].from : exit->state));
                std::string why;
                const Cost c = test::bruteForceEdgeCost(
                    rule_model, a, g.primitives().primitives[act.primitive], &why);
                ASSERT_GE(c, 0) << "escape motion " << k << " breaks the rule: " << why;
                escape_cost +=
                    static_cast<Cost>(std::ceil(kPenalty * static_cast<double>(c) - 1e-9));
              }
              ASSERT_EQ(escape_cost, exit->cost);
              ASSERT_TRUE(g.stateValid(exit->state.x, exit->state.y, exit->state.heading));
              // The rest: an ordinary path from the exit, validated as any other.
              ASSERT_EQ(test::validatePath(model, rest, sol.cost - exit->cost), "")
                  << algorithmName(alg);
              ASSERT_TRUE(rest.back() == t);
              ASSERT_GE(sol.cost, optimal);
              ASSERT_LE(static_cast<double>(sol.cost),
                        sol.certified_bound * static_cast<double>(optimal) * (1 + 1e-12))
                  << algorithmName(alg);
              multi_step += steps.size() > 1;
            });
        if (HasFatalFailure()) return;
        if (optimal == kInfiniteCost) {
          EXPECT_FALSE(r.hasSolution()) << algorithmName(alg);
          continue;
        }
        ASSERT_TRUE(r.hasSolution()) << algorithmName(alg);
        if (alg == Algorithm::kAStar) {
          EXPECT_EQ(r.best().cost, optimal);
          ++solved;
        }
      }
    }
  }
  EXPECT_GE(queries, 25);
  EXPECT_GE(solved, 10);
  EXPECT_GT(multi_step, 0) << "some escapes should pass through several states in collision";
}

// h(v) <= cost(v, e) + h(e) on the virtual start's edges, and h admissible there.
TEST(StartEscape, VirtualStartKeepsTheAnchorConsistent) {
  int checked = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const auto map = inflatedMap(seed + 20);
    const LatticeGraph g(map, test::smallRobot(seed));
    const HeuristicGridBuilder b(g);
    std::mt19937 rng(seed);
    for (int tries = 0; tries < 500; ++tries) {
      const LatticeState s = randomState(g, rng), t = randomState(g, rng);
      if (g.stateValid(s.x, s.y, s.heading) || !g.stateValid(t.x, t.y, t.heading)) continue;
      const StartEscape escape(g, s, kTolerance, kPenalty, nullptr);
      if (escape.exits().size() < 2) continue;
      std::vector<std::pair<LatticeState, Cost>> exits;
      for (const StartEscape::Exit& e : escape.exits()) exits.emplace_back(e.state, e.cost);
      LatticeProblem p(g, b.compute(t.x, t.y, t.heading, false, 1), s, t, 0);
      p.startAtExits(exits);
      HeuristicValue hv = 0, he = 0;
      p.heuristics(p.virtualStart(), &hv, 1);
      std::vector<Edge> out;
      p.successors(p.virtualStart(), out);
      ASSERT_EQ(out.size(), exits.size());
      for (const Edge& e : out) {
        p.heuristics(e.to, &he, 1);
        if (he == kInfiniteHeuristic) continue;
        ASSERT_NE(hv, kInfiniteHeuristic);
        EXPECT_LE(static_cast<Cost>(hv), e.cost + static_cast<Cost>(he));
        ++checked;
      }
      const Cost optimal = relaxedOptimum(g, s, t);
      if (optimal < kInfiniteCost) {
        EXPECT_LE(static_cast<Cost>(hv), optimal);
      }
      break;
    }
  }
  EXPECT_GT(checked, 10);
}

// A corridor 0.5 m wide between two walls, with inscribed cells along them: a rectangular robot
// whose rear overlaps the wall at x = 0..2 (0.05 m cells).
std::shared_ptr<GridMap> corridor() {
  auto m = test::freeMap(80, 40, 0.05);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 80; ++x) {
      std::uint8_t& c = m->cost[static_cast<std::size_t>(y) * 80 + x];
      if (y < 10 || y >= 30 || x < 3)
        c = kLethalCost;
      else if (y < 12 || y >= 28 || x < 5)
        c = kInscribedCost;
    }
  }
  return m;
}

LatticeConfig corridorRobot() {
  LatticeConfig c;
  c.robot.footprint = test::rectangle(0.15, 0.08);
  c.motion.turning_radius = 0.3;
  return c;
}

SearchLimits seconds(double s) {
  SearchLimits l;
  l.time_limit_s = s;
  return l;
}

TEST(StartEscape, PlanLeavesTheCollisionAndSaysHow) {
  LatticePlanner planner(corridor(), corridorRobot());
  // Centre at x = 0.2 m (cell 4, inscribed), facing +x: the rear reaches x = 0.05, the wall.
  const Pose2D start{0.225, 1.0, 0.0}, goal{3.5, 1.0, 0.0};
  std::string why;
  ASSERT_EQ(planner.checkQuery(start, goal, &why), QueryError::kStartInCollision);
  // Without a start tolerance: refused, as always.
  PlanResult r = planner.plan(start, goal, defaultConfig(Algorithm::kAStar), seconds(5));
  EXPECT_EQ(r.error, QueryError::kStartInCollision);
  EXPECT_FALSE(r.start_escaped);
  // With one: a path that begins at the start and leaves forward.
  StartOptions so;
  so.tolerance = 0.5;
  r = planner.plan(start, goal, so, GoalOptions(), defaultConfig(Algorithm::kAStar), seconds(5));
  ASSERT_EQ(r.error, QueryError::kNone) << r.message;
  ASSERT_TRUE(r.start_escaped);
  ASSERT_EQ(r.search.status, SearchStatus::kProvenOptimal);
  const LatticeSolution& best = r.solutions.back();
  ASSERT_GE(best.escape_poses, 2u);
  EXPECT_LE(std::hypot(best.poses.front().x - 0.225, best.poses.front().y - 1.0), 0.05);
  const Pose2D exit = best.poses[best.escape_poses - 1];
  EXPECT_EQ(planner.checkQuery(exit, goal, nullptr), QueryError::kNone)
      << "the escape ends collision-free";
  for (std::size_t k = 0; k + 1 < best.escape_poses; ++k) {
    EXPECT_GE(best.poses[k].x, 0.2) << "leaves forward, away from the wall";
  }
  EXPECT_GT(best.escape_cost, 0);
  EXPECT_LT(best.escape_cost, best.search.cost);
  EXPECT_NE(r.escape_message.find("is in collision"), std::string::npos) << r.escape_message;
  EXPECT_NE(r.escape_message.find("leaves it by"), std::string::npos) << r.escape_message;
  EXPECT_NE(r.escape_message.find("relative to the optimum"), std::string::npos)
      << r.escape_message;
  EXPECT_NEAR(best.poses.back().x, 3.525, 0.03);

  // Smoothed, as the server publishes it: the escape as it is, the rest smoothed, the cost at
  // most the search's (the smoother alone refuses the escape's motions: they collide).
  {
    const PathSmoother smoother(planner.graph());
    EXPECT_THROW(smoother.smooth(best.poses), std::invalid_argument);
    SmoothedStream stream(smoother);
    for (const LatticeSolution& raw : r.solutions) {
      const SmoothedStream::Step& step = stream.add(raw);
      const std::vector<Pose2D>& p = step.published.poses;
      ASSERT_GE(p.size(), raw.escape_poses);
      for (std::size_t k = 0; k < raw.escape_poses; ++k) {
        EXPECT_TRUE(p[k].x == raw.poses[k].x && p[k].y == raw.poses[k].y &&
                    p[k].theta == raw.poses[k].theta)
            << k;
      }
      EXPECT_NEAR(p.back().x, raw.poses.back().x, 1e-9);
      EXPECT_NEAR(p.back().y, raw.poses.back().y, 1e-9);
      EXPECT_LE(step.published.search.cost, raw.search.cost);
      EXPECT_GE(step.published.search.cost, raw.escape_cost);
      EXPECT_LE(step.published.search.certified_bound, raw.search.nominal_bound);
    }
  }

  // Too small a tolerance: only the start's own (inscribed) cell, where no heading is free; the
  // message says so. (One cell more is enough: a quarter turn there frees the rear.)
  so.tolerance = 0.01;
  r = planner.plan(start, goal, so, GoalOptions(), defaultConfig(Algorithm::kAStar), seconds(5));
  EXPECT_EQ(r.error, QueryError::kStartInCollision);
  EXPECT_NE(r.message.find("start tolerance of 0.010 m"), std::string::npos) << r.message;
  so.tolerance = 0.05;
  r = planner.plan(start, goal, so, GoalOptions(), defaultConfig(Algorithm::kAStar), seconds(5));
  EXPECT_EQ(r.error, QueryError::kNone) << r.message;
  EXPECT_TRUE(r.start_escaped);

  // A collision-free start is planned from as it is: the same result with a tolerance or not.
  const Pose2D free_start{1.0, 1.0, 0.0};
  so.tolerance = 0.5;
  const PlanResult plain =
      planner.plan(free_start, goal, defaultConfig(Algorithm::kAStar), seconds(5));
  const PlanResult tolerant = planner.plan(free_start, goal, so, GoalOptions(),
                                           defaultConfig(Algorithm::kAStar), seconds(5));
  ASSERT_TRUE(plain.hasSolution() && tolerant.hasSolution());
  EXPECT_FALSE(tolerant.start_escaped);
  EXPECT_EQ(tolerant.best().search.cost, plain.best().search.cost);
  EXPECT_EQ(tolerant.solutions.back().escape_poses, 0u);
  EXPECT_TRUE(tolerant.escape_message.empty());

  // Goal errors still come first when the start could be left.
  EXPECT_EQ(planner
                .plan(start, Pose2D{0.1, 0.1, 0.0}, so, GoalOptions(),
                      defaultConfig(Algorithm::kAStar), seconds(5))
                .error,
            QueryError::kGoalInCollision);
  EXPECT_EQ(planner
                .plan(start, Pose2D{9.0, 1.0, 0.0}, so, GoalOptions(),
                      defaultConfig(Algorithm::kAStar), seconds(5))
                .error,
            QueryError::kGoalOutOfMap);
  // With a goal tolerance and any heading as well: the obstructed goal is replaced.
  GoalOptions go;
  go.tolerance = 0.5;
  go.any_heading = true;
  r = planner.plan(start, Pose2D{3.5, 0.45, 0.0}, so, go, defaultConfig(Algorithm::kAmhaStar),
                   seconds(5));
  ASSERT_EQ(r.error, QueryError::kNone) << r.message;
  EXPECT_TRUE(r.start_escaped && r.goal_substituted);
  ASSERT_FALSE(r.solutions.empty());

  // Bad options.
  so.tolerance = -1.0;
  EXPECT_THROW(
      planner.plan(start, goal, so, GoalOptions(), defaultConfig(Algorithm::kAStar), seconds(5)),
      std::invalid_argument);
  so.tolerance = 0.5;
  so.penalty = 0.5;
  EXPECT_THROW(
      planner.plan(start, goal, so, GoalOptions(), defaultConfig(Algorithm::kAStar), seconds(5)),
      std::invalid_argument);
}

TEST(StartEscape, NeverCrossesAnObstacleTheRobotIsNotOn) {
  // The same corridor closed by a wall just ahead of the robot (x = 0.40 .. 0.45 m): the only
  // way out would cross it, so there is none, even with a large tolerance.
  auto m = corridor();
  for (int y = 0; y < 40; ++y) {
    for (int x = 8; x < 9; ++x) m->cost[static_cast<std::size_t>(y) * 80 + x] = kLethalCost;
  }
  LatticePlanner planner(m, corridorRobot());
  StartOptions so;
  so.tolerance = 2.0;
  const PlanResult r = planner.plan(Pose2D{0.225, 1.0, 0.0}, Pose2D{3.5, 1.0, 0.0}, so,
                                    GoalOptions(), defaultConfig(Algorithm::kAStar), seconds(5));
  EXPECT_EQ(r.error, QueryError::kStartInCollision) << r.message;
  EXPECT_NE(r.message.find("no collision-free pose"), std::string::npos) << r.message;
}

TEST(StartEscape, BackwardSearchRefusesAnEscapeAndSaysWhy) {
  LatticeConfig c = corridorRobot();
  c.backward_search = true;
  LatticePlanner planner(corridor(), c);
  StartOptions so;
  so.tolerance = 0.5;
  const PlanResult r = planner.plan(Pose2D{0.225, 1.0, 0.0}, Pose2D{3.5, 1.0, 0.0}, so,
                                    GoalOptions(), defaultConfig(Algorithm::kAStar), seconds(5));
  EXPECT_EQ(r.error, QueryError::kStartInCollision);
  EXPECT_NE(r.message.find("backward_search"), std::string::npos) << r.message;
}

TEST(StartEscape, ACancelledRequestStopsBeforeSearching) {
  LatticePlanner planner(corridor(), corridorRobot());
  std::atomic<bool> cancel{true};
  SearchLimits l = seconds(5);
  l.cancel = &cancel;
  StartOptions so;
  so.tolerance = 0.5;
  const PlanResult r = planner.plan(Pose2D{0.225, 1.0, 0.0}, Pose2D{3.5, 1.0, 0.0}, so,
                                    GoalOptions(), defaultConfig(Algorithm::kAStar), l);
  EXPECT_EQ(r.error, QueryError::kNone);
  EXPECT_EQ(r.search.status, SearchStatus::kCancelled);
  EXPECT_TRUE(r.solutions.empty());
}

}  // namespace
}  // namespace lattice
}  // namespace amha
