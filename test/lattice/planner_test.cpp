// LatticePlanner end to end: query errors, A* against an exhaustive Dijkstra over the lattice,
// every solution of every algorithm checked by the independent path validator, anytime bounds,
// the heuristic cache and concurrent plan() calls.
#include <algorithm>
#include <cmath>
#include <queue>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/map_loaders.h"
#include "path_validator.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

TEST(LatticePlannerTest, QueryErrors) {
  auto map = test::randomMap(30, 20, 0.1, 1, 0, 0);
  for (int y = 5; y < 10; ++y) map->cost[y * 30 + 15] = kLethalCost;
  map->origin_x = -1.0;
  map->origin_y = 2.0;
  LatticeConfig c;
  c.robot.radius = 0.15;
  LatticePlanner planner(map, c);
  const Pose2D ok{0.0, 3.0, 0.0}, ok2{1.2, 3.0, 1.0};
  std::string msg;
  EXPECT_EQ(planner.checkQuery(ok, ok2, &msg), QueryError::kNone);
  EXPECT_TRUE(msg.empty());
  EXPECT_EQ(planner.checkQuery({NAN, 3.0, 0.0}, ok2, &msg), QueryError::kStartNotFinite);
  EXPECT_EQ(planner.checkQuery(ok, {1.0, 3.0, INFINITY}, &msg), QueryError::kGoalNotFinite);
  EXPECT_EQ(planner.checkQuery({-1.5, 3.0, 0.0}, ok2, &msg), QueryError::kStartOutOfMap);
  EXPECT_NE(msg.find("outside the map"), std::string::npos);
  EXPECT_EQ(planner.checkQuery(ok, {1.0, 4.01, 0.0}, &msg), QueryError::kGoalOutOfMap);
  EXPECT_EQ(planner.checkQuery(ok, {0.55, 2.75, 0.0}, &msg),
            QueryError::kGoalInCollision);  // cell (15, 7)
  EXPECT_NE(msg.find("in collision"), std::string::npos);
  EXPECT_EQ(planner.checkQuery(ok, {0.4, 2.75, 0.0}, &msg),
            QueryError::kGoalInCollision);  // footprint touches it
  EXPECT_EQ(planner.checkQuery({-0.95, 3.0, 0.0}, ok2, &msg),
            QueryError::kStartInCollision);  // footprint leaves the map
  const PlanResult r =
      planner.plan({-1.5, 3.0, 0.0}, ok2, defaultConfig(Algorithm::kAStar), SearchLimits());
  EXPECT_EQ(r.error, QueryError::kStartOutOfMap);
  EXPECT_FALSE(r.message.empty());
  EXPECT_TRUE(r.solutions.empty());
  EXPECT_STREQ(queryErrorName(QueryError::kGoalInCollision), "goal_in_collision");
}

TEST(LatticePlannerTest, BadConfigurations) {
  auto map = test::randomMap(20, 20, 0.1, 1, 0, 0);
  LatticeConfig c;
  c.motion.num_headings = 12;
  EXPECT_THROW(LatticePlanner(map, c), LatticeError);
  c = LatticeConfig();
  c.heuristics.num_inadmissible = 4;
  EXPECT_THROW(LatticePlanner(map, c), LatticeError);
  c = LatticeConfig();
  c.motion.mprim_file = "/nonexistent.mprim";
  try {
    LatticePlanner p(map, c);
    ADD_FAILURE();
  } catch (const LatticeError& e) {
    EXPECT_EQ(e.kind(), LatticeError::Kind::kPrimitives);
  }
  auto bad = std::make_shared<GridMap>(*map);
  bad->cost.pop_back();
  EXPECT_THROW(LatticePlanner(bad, LatticeConfig()), LatticeError);
}

struct Scenario {
  std::shared_ptr<GridMap> map;
  LatticeConfig config;
};

Scenario scenario(unsigned seed, int size) {
  Scenario s;
  s.map = test::randomMap(size, size, 0.05, seed, size / 3, seed % 2 ? 150 : 0);
  s.config.motion.turning_radius = 0.2;
  s.config.motion.allow_reverse = seed % 3 == 0;
  s.config.robot.footprint = test::rectangle(0.09, 0.06);
  s.config.cost.penalty = seed % 2 ? 4.0 : 1.0;
  s.config.cost.time_to_turn_45 = 1.0;
  s.config.heuristics.grid_anchor = seed % 4 != 1;
  return s;
}

// Cost of the cheapest path by Dijkstra over the lattice (no heuristic, no search engine).
Cost exhaustiveDijkstra(LatticeProblem& p) {
  std::vector<Cost> g(1, kInfiniteCost);
  using Item = std::pair<Cost, StateId>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  g[p.start()] = 0;
  q.push({0, p.start()});
  std::vector<Edge> succ;
  while (!q.empty()) {
    const auto [d, s] = q.top();
    q.pop();
    if (d != g[s]) continue;
    if (s == p.goal()) return d;
    p.successors(s, succ);
    for (const Edge& e : succ) {
      if (e.to >= g.size()) g.resize(e.to + 1, kInfiniteCost);
      if (d + e.cost < g[e.to]) {
        g[e.to] = d + e.cost;
        q.push({g[e.to], e.to});
      }
    }
  }
  return kInfiniteCost;
}

bool randomQuery(const LatticeGraph& g, std::mt19937& rng, LatticeState* s, LatticeState* t) {
  std::uniform_int_distribution<int> rx(0, g.width() - 1), ry(0, g.height() - 1),
      rh(0, g.numHeadings() - 1);
  for (int tries = 0; tries < 1000; ++tries) {
    *s = {rx(rng), ry(rng), rh(rng)};
    *t = {rx(rng), ry(rng), rh(rng)};
    if (g.stateValid(s->x, s->y, s->heading) && g.stateValid(t->x, t->y, t->heading)) return true;
  }
  return false;
}

std::vector<LatticeState> statesOf(const LatticeProblem& p, const std::vector<StateId>& path) {
  std::vector<LatticeState> out;
  for (StateId s : path) out.push_back(p.state(s));
  return out;
}

constexpr Cost kUnknownOptimum = -1;  // a solution is expected, its optimal cost is not known

// Runs `config` on the query and checks every reported solution with the validator, and, if the
// optimum is known, that cost <= certified_bound x optimum.
void runAndValidate(const LatticeGraph& g, const HeuristicGridBuilder& b, LatticeState s,
                    LatticeState t, const PlannerConfig& config, Cost optimal, double time_limit,
                    bool backward = false) {
  // Backward search runs from t to s over reversed edges, with tables measured from s.
  const LatticeState from = backward ? t : s, to = backward ? s : t;
  LatticeProblem p(g, b.compute(to.x, to.y, to.heading, true, 1, backward), from, to, 3, backward);
  auto planner = makePlanner(config);
  SearchLimits limits;
  limits.time_limit_s = time_limit;
  const test::ValidatorModel model = test::modelFor(g);
  int count = 0;
  const SearchResult r = planner->search(p, limits, [&](const Solution& sol) {
    ++count;
    std::vector<LatticeState> states = statesOf(p, sol.path);
    if (backward) std::reverse(states.begin(), states.end());
    const std::string err = test::validatePath(model, states, sol.cost);
    ASSERT_EQ(err, "") << algorithmName(config.algorithm) << " solution " << count;
    ASSERT_EQ(sol.path.front(), p.start());
    ASSERT_EQ(sol.path.back(), p.goal());
    if (optimal != kInfiniteCost && optimal != kUnknownOptimum) {
      ASSERT_GE(sol.cost, optimal) << algorithmName(config.algorithm);
      ASSERT_LE(static_cast<double>(sol.cost),
                sol.certified_bound * static_cast<double>(optimal) * (1 + 1e-12))
          << algorithmName(config.algorithm) << " certified " << sol.certified_bound;
      ASSERT_LE(sol.certified_bound, sol.nominal_bound + 1e-12);
    }
  });
  if (optimal == kInfiniteCost) {
    EXPECT_TRUE(r.solutions.empty());
  } else if (optimal == kUnknownOptimum) {
    EXPECT_TRUE(r.hasSolution());
  } else if (r.status == SearchStatus::kProvenOptimal) {
    EXPECT_EQ(r.best().cost, optimal) << algorithmName(config.algorithm);
  }
}

TEST(LatticeSearchTest, AStarEqualsExhaustiveDijkstraAndEveryPathValidates) {
  const Algorithm all[] = {Algorithm::kAmhaStar, Algorithm::kMhaStar,       Algorithm::kAraStar,
                           Algorithm::kAnaStar,  Algorithm::kWeightedAStar, Algorithm::kAStar};
  int solved = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    Scenario sc = scenario(seed, 36);
    LatticeGraph g(sc.map, sc.config);
    HeuristicGridBuilder b(g);
    std::mt19937 rng(seed * 77);
    for (int q = 0; q < 3; ++q) {
      LatticeState s, t;
      ASSERT_TRUE(randomQuery(g, rng, &s, &t));
      LatticeProblem ref(g, b.compute(t.x, t.y, t.heading, true, 1), s, t, 3);
      const Cost optimal = exhaustiveDijkstra(ref);
      solved += optimal != kInfiniteCost;
      {
        LatticeProblem p(g, b.compute(t.x, t.y, t.heading, true, 1), s, t, 3);
        const SearchResult r =
            makePlanner(defaultConfig(Algorithm::kAStar))->search(p, SearchLimits());
        if (optimal == kInfiniteCost) {
          EXPECT_EQ(r.status, SearchStatus::kNoSolution);
        } else {
          ASSERT_TRUE(r.hasSolution());
          EXPECT_EQ(r.best().cost, optimal) << "seed " << seed << " query " << q;
        }
      }
      for (Algorithm a : all) {
        PlannerConfig pc = defaultConfig(a);
        pc.check_invariants = seed == 1;
        runAndValidate(g, b, s, t, pc, optimal, 20.0);
        if (seed % 2 == 1) runAndValidate(g, b, s, t, pc, optimal, 20.0, true);
      }
    }
  }
  EXPECT_GE(solved, 12);
}

TEST(LatticeSearchTest, AmhaWithinCertifiedBoundOnLargerMaps) {
  for (unsigned seed : {31u, 32u}) {
    Scenario sc = scenario(seed, 80);
    LatticeGraph g(sc.map, sc.config);
    HeuristicGridBuilder b(g);
    std::mt19937 rng(seed);
    LatticeState s, t;
    ASSERT_TRUE(randomQuery(g, rng, &s, &t));
    LatticeProblem ref(g, b.compute(t.x, t.y, t.heading, true, 1), s, t, 3);
    const Cost optimal = exhaustiveDijkstra(ref);
    runAndValidate(g, b, s, t, defaultConfig(Algorithm::kAmhaStar), optimal, 30.0);
  }
}

TEST(LatticePlannerTest, BackwardSearchFindsTheSameOptimum) {
  for (unsigned seed : {41u, 42u, 43u}) {
    Scenario sc = scenario(seed, 40);
    LatticeGraph g(sc.map, sc.config);
    LatticeConfig back = sc.config;
    back.backward_search = true;
    LatticePlanner forward_planner(sc.map, sc.config), backward_planner(sc.map, back);
    HeuristicGridBuilder b(g);
    std::mt19937 rng(seed);
    LatticeState s, t;
    ASSERT_TRUE(randomQuery(g, rng, &s, &t));
    LatticeProblem ref(g, b.compute(t.x, t.y, t.heading, true, 1), s, t, 3);
    const Cost optimal = exhaustiveDijkstra(ref);
    const Pose2D ps = g.stateToPose(s.x, s.y, s.heading), pt = g.stateToPose(t.x, t.y, t.heading);
    const PlanResult f =
        forward_planner.plan(ps, pt, defaultConfig(Algorithm::kAStar), SearchLimits());
    for (Algorithm a : {Algorithm::kAStar, Algorithm::kAmhaStar, Algorithm::kAraStar}) {
      const PlanResult r = backward_planner.plan(ps, pt, defaultConfig(a), SearchLimits());
      if (optimal == kInfiniteCost) {
        EXPECT_TRUE(r.solutions.empty());
        continue;
      }
      ASSERT_FALSE(r.solutions.empty());
      const LatticeSolution& last = r.solutions.back();
      if (a == Algorithm::kAStar) {
        EXPECT_EQ(last.search.cost, optimal);
        EXPECT_EQ(f.solutions.back().search.cost, optimal);
      }
      for (const LatticeSolution& sol : r.solutions) {
        EXPECT_LE(static_cast<double>(sol.search.cost),
                  sol.search.certified_bound * optimal * (1 + 1e-12));
        // Poses run from the start to the goal.
        EXPECT_NEAR(sol.poses.front().x, ps.x, 1e-9);
        EXPECT_NEAR(sol.poses.front().y, ps.y, 1e-9);
        EXPECT_NEAR(sol.poses.back().x, pt.x, 1e-6);
        EXPECT_NEAR(sol.poses.back().y, pt.y, 1e-6);
      }
    }
  }
}

TEST(LatticePlannerTest, PosesCacheAndConcurrentQueries) {
  Scenario sc = scenario(2, 60);
  LatticePlanner planner(sc.map, sc.config);
  LatticeGraph g(sc.map, sc.config);
  std::mt19937 rng(3);
  std::vector<std::pair<Pose2D, Pose2D>> queries;
  while (queries.size() < 4) {
    LatticeState s, t;
    ASSERT_TRUE(randomQuery(g, rng, &s, &t));
    queries.push_back({g.stateToPose(s.x, s.y, s.heading), g.stateToPose(t.x, t.y, t.heading)});
  }
  const PlannerConfig pc = defaultConfig(Algorithm::kAmhaStar);
  std::vector<PlanResult> sequential;
  for (const auto& q : queries)
    sequential.push_back(planner.plan(q.first, q.second, pc, SearchLimits()));
  // Poses: the path starts at the start state's pose, ends at the goal's, without jumps.
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const PlanResult& r = sequential[i];
    ASSERT_EQ(r.error, QueryError::kNone);
    if (r.solutions.empty()) continue;
    const auto& poses = r.solutions.back().poses;
    EXPECT_NEAR(poses.front().x, queries[i].first.x, 1e-9);
    EXPECT_NEAR(poses.front().y, queries[i].first.y, 1e-9);
    EXPECT_NEAR(poses.back().x, queries[i].second.x, 1e-6);
    EXPECT_NEAR(poses.back().y, queries[i].second.y, 1e-6);
    EXPECT_NEAR(angleDistance(poses.back().theta, queries[i].second.theta), 0.0, 1e-6);
    for (std::size_t k = 1; k < poses.size(); ++k) {
      EXPECT_LE(std::hypot(poses[k].x - poses[k - 1].x, poses[k].y - poses[k - 1].y), 0.05) << k;
    }
  }
  // Same goal again: the grids come from the cache.
  const PlanResult again =
      planner.plan(queries.back().first, queries.back().second, pc, SearchLimits());
  EXPECT_EQ(again.heuristic_seconds, 0.0);
  EXPECT_GT(sequential[0].heuristic_seconds, 0.0);
  // Concurrent calls give the same answers.
  std::vector<PlanResult> parallel(queries.size());
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    threads.emplace_back([&, i] {
      parallel[i] = planner.plan(queries[i].first, queries[i].second, pc, SearchLimits());
    });
  }
  for (auto& t : threads) t.join();
  for (std::size_t i = 0; i < queries.size(); ++i) {
    ASSERT_EQ(parallel[i].solutions.size(), sequential[i].solutions.size());
    for (std::size_t k = 0; k < parallel[i].solutions.size(); ++k) {
      EXPECT_EQ(parallel[i].solutions[k].search.cost, sequential[i].solutions[k].search.cost);
    }
  }
}

TEST(LatticePlannerTest, CubicleWithPr2PrimitivesValidates) {
  AMHA_REQUIRE_SHARED_DATA(data);
  SbplEnvironment env;
  const LatticeConfig c = test::cubicleConfig(data, &env);
  auto map = std::make_shared<GridMap>(env.map);
  LatticeGraph g(map, c);
  HeuristicGridBuilder b(g);
  LatticeState s, t;
  g.poseToState(env.start, &s.x, &s.y, &s.heading);
  g.poseToState(env.goal, &t.x, &t.y, &t.heading);
  PlannerConfig ara = defaultConfig(Algorithm::kAraStar);
  ara.w1 = 3.0;
  ara.dw1 = 1.0;
  runAndValidate(g, b, s, t, ara, kUnknownOptimum, 10.0);
}

}  // namespace
}  // namespace lattice
}  // namespace amha
