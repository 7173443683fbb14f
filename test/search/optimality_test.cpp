// Every algorithm against an exact solver on generated problems: valid paths, costs equal to
// the sum of edges, cost <= certified * optimal <= nominal * optimal, non-increasing costs,
// proven-optimal endings that really are optimal, and at most two expansions per state within
// one ImprovePath for A-MHA* and MHA*.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "../../src/search/mha_engine.h"
#include "test_graphs.h"

namespace amha {
namespace {

using testing::ExplicitGraph;
using testing::GenOptions;

struct Case {
  std::string name;
  ExplicitGraph graph;
};

std::vector<Case> makeCases(std::size_t n_inadmissible) {
  std::vector<Case> cases;
  for (std::uint32_t seed = 1; seed <= 12; ++seed) {
    GenOptions o;
    o.seed = seed;
    o.n_inadmissible = n_inadmissible;
    o.anchor_scale = (seed % 3 == 0) ? 0.0 : (seed % 3 == 1 ? 0.6 : 1.0);
    cases.push_back({"grid" + std::to_string(seed), testing::randomGrid(24, 18, 0.25, o)});
    cases.push_back({"graph" + std::to_string(seed), testing::randomGraph(300, 3, o)});
    // Half of the cases let the engine keep its queues as buckets, half as heaps.
    for (std::size_t k = cases.size() - 2; k < cases.size(); ++k) {
      cases[k].graph.small_keys = (seed + k) % 2 == 0;
      cases[k].name += cases[k].graph.small_keys ? "-buckets" : "-heaps";
    }
  }
  return cases;
}

void checkRun(ExplicitGraph& g, const PlannerConfig& config, const std::string& label) {
  const Cost optimal = testing::distancesToGoal(g)[g.s_start];
  auto planner = makePlanner(config);
  std::vector<Solution> streamed;
  const SearchResult r =
      planner->search(g, SearchLimits(), [&](const Solution& s) { streamed.push_back(s); });
  SCOPED_TRACE(label + " " + algorithmName(config.algorithm));
  ASSERT_EQ(streamed.size(), r.solutions.size());
  if (optimal >= kInfiniteCost) {
    EXPECT_EQ(r.status, SearchStatus::kNoSolution);
    EXPECT_TRUE(r.solutions.empty());
    return;
  }
  ASSERT_FALSE(r.solutions.empty());
  Cost last = kInfiniteCost;
  for (const Solution& s : r.solutions) {
    EXPECT_EQ(testing::validateSolution(g, s, optimal), "");
    EXPECT_LE(s.cost, last) << "solution cost increased";
    last = s.cost;
  }
  if (r.status == SearchStatus::kProvenOptimal) {
    EXPECT_EQ(r.best().cost, optimal);
    EXPECT_EQ(r.best().certified_bound, 1.0);
  }
  const bool anytime_to_one =
      config.algorithm == Algorithm::kAmhaStar || config.algorithm == Algorithm::kAraStar ||
      config.algorithm == Algorithm::kAnaStar || config.algorithm == Algorithm::kAStar;
  if (anytime_to_one) {
    EXPECT_EQ(r.status, SearchStatus::kProvenOptimal);
  } else {
    EXPECT_TRUE(r.status == SearchStatus::kBoundReached ||
                r.status == SearchStatus::kProvenOptimal);
  }
}

class AllAlgorithms : public ::testing::TestWithParam<Algorithm> {};

TEST_P(AllAlgorithms, SolutionsValidBoundedAndImproving) {
  for (auto& c : makeCases(4)) {
    PlannerConfig config = defaultConfig(GetParam());
    config.check_invariants = true;
    checkRun(c.graph, config, c.name);
  }
}

TEST_P(AllAlgorithms, RunsToOptimalWithoutCertifiedShortcut) {
  // Without the early stop, A-MHA* must walk its schedule down to w1 = w2 = 1.
  for (auto& c : makeCases(3)) {
    PlannerConfig config = defaultConfig(GetParam());
    config.stop_when_certified_optimal = false;
    config.check_invariants = true;
    checkRun(c.graph, config, c.name);
  }
}

// The bound cannot depend on which inadmissible queue goes next: the same checks with DTS.
TEST(DtsSchedule, SolutionsValidBoundedAndImproving) {
  for (bool shortcut : {true, false}) {
    for (auto& c : makeCases(shortcut ? 4 : 7)) {
      for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kMhaStar}) {
        PlannerConfig config = defaultConfig(a);
        config.schedule = QueueSchedule::kDts;
        config.schedule_seed = 7;
        config.stop_when_certified_optimal = shortcut;
        config.check_invariants = true;
        checkRun(c.graph, config, c.name + " dts");
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Search, AllAlgorithms,
                         ::testing::Values(Algorithm::kAmhaStar, Algorithm::kMhaStar,
                                           Algorithm::kAraStar, Algorithm::kAnaStar,
                                           Algorithm::kWeightedAStar, Algorithm::kAStar),
                         [](const auto& info) { return std::string(algorithmName(info.param)); });

TEST(AmhaStar, FinalIterationHasUnitWeightsAndIsOptimal) {
  GenOptions o;
  o.seed = 5;
  ExplicitGraph g = testing::randomGrid(30, 30, 0.2, o);
  PlannerConfig config = defaultConfig(Algorithm::kAmhaStar);
  config.stop_when_certified_optimal = false;
  const SearchResult r = makePlanner(config)->search(g, SearchLimits());
  ASSERT_EQ(r.status, SearchStatus::kProvenOptimal);
  EXPECT_EQ(r.best().w1, 1.0);
  EXPECT_EQ(r.best().w2, 1.0);
  EXPECT_EQ(r.best().nominal_bound, 1.0);
  EXPECT_EQ(r.best().cost, testing::distancesToGoal(g)[g.s_start]);
  // The schedule 25, 20.25, 16, ... : nominal bounds strictly decrease.
  for (std::size_t k = 1; k < r.solutions.size(); ++k) {
    EXPECT_LT(r.solutions[k].nominal_bound, r.solutions[k - 1].nominal_bound);
  }
}

TEST(AmhaStar, NominalBoundHoldsWithMisleadingHeuristics) {
  // With the anchor at 0 (Dijkstra-like) and wild inadmissible heuristics, every iteration's
  // solution must still be within w1*w2 of optimal.
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    GenOptions o;
    o.seed = seed;
    o.anchor_scale = 0.3;
    o.n_inadmissible = 8;
    ExplicitGraph g = testing::randomGraph(400, 3, o);
    const Cost optimal = testing::distancesToGoal(g)[g.s_start];
    if (optimal >= kInfiniteCost) continue;
    PlannerConfig config = defaultConfig(Algorithm::kAmhaStar);
    config.stop_when_certified_optimal = false;
    config.w1 = 1.5;
    config.w2 = 3.0;
    config.dw1 = 0.25;
    config.dw2 = 1.0;
    config.schedule = seed % 2 ? QueueSchedule::kDts : QueueSchedule::kRoundRobin;
    const SearchResult r = makePlanner(config)->search(g, SearchLimits());
    for (const Solution& s : r.solutions) {
      EXPECT_LE(static_cast<double>(s.cost), s.w1 * s.w2 * static_cast<double>(optimal));
    }
  }
}

// Theorem 2: within one ImprovePath a state is expanded at most twice.
TEST(AmhaStar, AtMostTwoExpansionsPerStatePerImprovePath) {
  for (Algorithm algorithm : {Algorithm::kAmhaStar, Algorithm::kMhaStar}) {
    for (std::uint32_t seed = 1; seed <= 15; ++seed) {
      GenOptions o;
      o.seed = seed;
      o.anchor_scale = 0.5;
      o.n_inadmissible = 1 + seed % 8;
      ExplicitGraph g =
          (seed % 2) ? testing::randomGrid(30, 25, 0.2, o) : testing::randomGraph(500, 3, o);
      const PlannerConfig config = defaultConfig(algorithm);
      detail::MhaEngineOptions eo;
      eo.w1 = config.w1;
      eo.w2 = config.w2;
      eo.dw1 = config.dw1;
      eo.dw2 = config.dw2;
      eo.anytime = algorithm == Algorithm::kAmhaStar;
      eo.max_inadmissible = 100;
      eo.stop_when_certified_optimal = false;
      eo.schedule = seed % 3 == 0 ? QueueSchedule::kDts : QueueSchedule::kRoundRobin;
      detail::MhaEngine engine(eo);
      std::map<std::pair<int, StateId>, int> count;
      std::map<std::pair<int, StateId>, int> anchor_count;
      int max_count = 0;
      engine.setObserver([&](StateId s, std::size_t q, int it) {
        max_count = std::max(max_count, ++count[std::make_pair(it, s)]);
        if (q == 0) {
          const int n = ++anchor_count[std::make_pair(it, s)];
          EXPECT_EQ(n, 1) << "anchor re-expanded a state";
        }
      });
      engine.run(g, SearchLimits(), {});
      EXPECT_LE(max_count, 2) << "seed " << seed;
    }
  }
}

TEST(Search, HeuristicCountsFromZeroToEight) {
  // And beyond 27 inadmissible ones (28 queues), where the queue membership bits leave the
  // flags word for words of their own, and at the boundary.
  for (std::size_t n : {0, 1, 2, 3, 4, 5, 6, 7, 8, 27, 28, 40}) {
    GenOptions o;
    o.seed = 100 + static_cast<std::uint32_t>(n);
    o.n_inadmissible = n;
    ExplicitGraph g = testing::randomGrid(20, 20, 0.2, o);
    for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kMhaStar}) {
      PlannerConfig config = defaultConfig(a);
      config.check_invariants = true;
      checkRun(g, config, "n=" + std::to_string(n));
    }
  }
}

TEST(Search, StartEqualsGoal) {
  GenOptions o;
  ExplicitGraph g = testing::randomGrid(5, 5, 0.0, o);
  g.s_goal = g.s_start;
  g.h[g.s_goal].assign(g.n_heuristics, 0);
  for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kAraStar, Algorithm::kAnaStar}) {
    const SearchResult r = makePlanner(defaultConfig(a))->search(g, SearchLimits());
    ASSERT_TRUE(r.hasSolution()) << algorithmName(a);
    EXPECT_EQ(r.best().cost, 0);
    EXPECT_EQ(r.best().path.size(), 1u);
    EXPECT_EQ(r.status, SearchStatus::kProvenOptimal);
  }
}

TEST(Search, PlannerIsReusableAcrossProblems) {
  auto planner = makePlanner(defaultConfig(Algorithm::kAmhaStar));
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    GenOptions o;
    o.seed = seed;
    o.n_inadmissible = seed % 3;  // a changing heuristic count re-lays the arrays
    ExplicitGraph g = testing::randomGrid(15 + static_cast<int>(seed), 15, 0.2, o);
    const Cost optimal = testing::distancesToGoal(g)[g.s_start];
    const SearchResult r = planner->search(g, SearchLimits());
    if (optimal >= kInfiniteCost) {
      EXPECT_EQ(r.status, SearchStatus::kNoSolution);
    } else {
      ASSERT_TRUE(r.hasSolution());
      EXPECT_EQ(r.best().cost, optimal);
    }
  }
}

TEST(Search, RejectsBadWeights) {
  PlannerConfig c = defaultConfig(Algorithm::kAmhaStar);
  c.w1 = 0.5;
  EXPECT_THROW(makePlanner(c), std::invalid_argument);
  c = defaultConfig(Algorithm::kAmhaStar);
  c.w2 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(makePlanner(c), std::invalid_argument);
  c = defaultConfig(Algorithm::kAmhaStar);
  c.dw1 = 0.0;
  EXPECT_THROW(makePlanner(c), std::invalid_argument);
  c = defaultConfig(Algorithm::kAraStar);
  c.dw1 = -1.0;
  EXPECT_THROW(makePlanner(c), std::invalid_argument);
}

// Weights and decrements live in [1, kMaxWeight] and [0, kMaxWeight] (issue 22, item 1: w1 =
// 1e15 gave a false "no path"); the refusal names the parameter and the range.
TEST(Search, RejectsWeightsAndDecrementsOutsideTheirRange) {
  const double inf = std::numeric_limits<double>::infinity(),
               nan = std::numeric_limits<double>::quiet_NaN();
  for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kMhaStar, Algorithm::kAraStar,
                      Algorithm::kWeightedAStar}) {
    for (double w : {kMaxWeight * 1.000001, 1e15, 1e308, inf, nan, 0.999}) {
      PlannerConfig c = defaultConfig(a);
      c.w1 = w;
      try {
        makePlanner(c);
        ADD_FAILURE() << algorithmName(a) << " accepted w1 = " << w;
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("must be a finite number in [1, 1e+06]"),
                  std::string::npos)
            << e.what();
      }
      if (a == Algorithm::kAmhaStar || a == Algorithm::kMhaStar) {
        c = defaultConfig(a);
        c.w2 = w;
        EXPECT_THROW(makePlanner(c), std::invalid_argument) << algorithmName(a) << " w2 = " << w;
      }
    }
    PlannerConfig c = defaultConfig(a);
    c.w1 = kMaxWeight;
    c.w2 = a == Algorithm::kAmhaStar || a == Algorithm::kMhaStar ? kMaxWeight : c.w2;
    EXPECT_NO_THROW(makePlanner(c)) << algorithmName(a);
  }
  for (double d : {-1.0, 2e6, inf, nan}) {
    PlannerConfig c = defaultConfig(Algorithm::kAmhaStar);
    c.dw2 = d;
    EXPECT_THROW(makePlanner(c), std::invalid_argument) << "dw2 = " << d;
    c = defaultConfig(Algorithm::kAraStar);
    c.dw1 = d;
    EXPECT_THROW(makePlanner(c), std::invalid_argument) << "ARA* dw1 = " << d;
  }
}

}  // namespace
}  // namespace amha
