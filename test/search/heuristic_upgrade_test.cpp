// SearchProblem::upgradeHeuristics: an anchor that becomes better informed during the search
// (here once the search has asked for a number of successors) leaves every algorithm's paths
// valid and bounded, and the optimal ones optimal; A* takes it up within its iteration and
// expands fewer states than with the weak anchor alone.
#include <gtest/gtest.h>

#include <string>

#include "result_checks.h"
#include "test_graphs.h"

namespace amha {
namespace {

using testing::ExplicitGraph;

// The anchor: floor(weak * d) until the upgrade, floor(strong * d) after (d the exact
// cost-to-go; both consistent, and the second no lower).
class UpgradingGraph : public ExplicitGraph {
 public:
  std::vector<HeuristicValue> strong;
  std::uint64_t upgrade_after = 0;  // successor calls before the upgrade
  bool upgraded = false;
  int upgrades = 0;

  void heuristics(StateId s, HeuristicValue* out, std::size_t count) override {
    ExplicitGraph::heuristics(s, out, count);
    if (upgraded) out[0] = strong[s];
  }
  bool upgradeHeuristics() override {
    if (upgraded || successor_calls < upgrade_after) return false;
    upgraded = true;
    ++upgrades;
    return true;
  }
};

UpgradingGraph upgrading(const ExplicitGraph& base, double weak, double strong,
                         std::uint64_t after) {
  UpgradingGraph g;
  static_cast<ExplicitGraph&>(g) = base;
  const std::vector<Cost> d = testing::distancesToGoal(base);
  g.strong.resize(g.size());
  for (std::size_t s = 0; s < g.size(); ++s) {
    const bool finite = d[s] < kInfiniteCost;
    g.h[s][0] =
        finite ? static_cast<HeuristicValue>(weak * static_cast<double>(d[s])) : kInfiniteHeuristic;
    g.strong[s] = finite ? static_cast<HeuristicValue>(strong * static_cast<double>(d[s]))
                         : kInfiniteHeuristic;
  }
  g.upgrade_after = after;
  return g;
}

const Algorithm kAll[] = {Algorithm::kAmhaStar, Algorithm::kMhaStar,       Algorithm::kAraStar,
                          Algorithm::kAnaStar,  Algorithm::kWeightedAStar, Algorithm::kAStar};

// Graphs big enough for A*'s poll (every 1024 expansions) to come before the goal.
std::vector<ExplicitGraph> graphs() {
  return testing::gridsAndGraphs(120, 90, 12000, 1.0, 1.0, true);
}

TEST(HeuristicUpgrade, EveryAlgorithmKeepsItsBoundsAndOptimality) {
  int k = 0;
  for (const ExplicitGraph& base : graphs()) {
    const Cost optimal = testing::distancesToGoal(base)[base.s_start];
    for (std::uint64_t after : {std::uint64_t{0}, std::uint64_t{1500}, std::uint64_t{4000}}) {
      for (Algorithm a : kAll) {
        UpgradingGraph g = upgrading(base, 0.3, 0.95, after);
        PlannerConfig c = defaultConfig(a);
        c.check_invariants = true;
        const SearchResult r = makePlanner(c)->search(g, SearchLimits());
        SCOPED_TRACE(std::string(algorithmName(a)) + " graph " + std::to_string(k) +
                     " upgrade after " + std::to_string(after));
        testing::expectValidResult(g, r, a, optimal);
      }
    }
    ++k;
  }
}

TEST(HeuristicUpgrade, AStarTakesItUpWithinItsIteration) {
  int upgraded_runs = 0;
  for (const ExplicitGraph& base : graphs()) {
    const Cost optimal = testing::distancesToGoal(base)[base.s_start];
    if (optimal >= kInfiniteCost) continue;
    PlannerConfig c = defaultConfig(Algorithm::kAStar);
    c.check_invariants = true;
    UpgradingGraph weak = upgrading(base, 0.3, 0.3, 0);
    const SearchResult rw = makePlanner(c)->search(weak, SearchLimits());
    if (rw.expansions < 3000) continue;  // too small for the poll to matter
    UpgradingGraph g = upgrading(base, 0.3, 0.95, 1500);
    const SearchResult r = makePlanner(c)->search(g, SearchLimits());
    ASSERT_EQ(r.best().cost, optimal);
    EXPECT_EQ(g.upgrades, 1);
    EXPECT_LT(r.expansions, rw.expansions) << "the upgrade changed nothing";
    ++upgraded_runs;
  }
  EXPECT_GE(upgraded_runs, 5);
}

}  // namespace
}  // namespace amha
