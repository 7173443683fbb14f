// Inflation bases (SearchProblem::hasInflationBases): keys g + h_i + (w - 1) b_i. Every
// algorithm keeps its bounds with a consistent anchor base b_0 <= h_0; bases equal to the
// heuristics change nothing; at weight 1 the bases change nothing.
#include <gtest/gtest.h>

#include <string>

#include "result_checks.h"
#include "test_graphs.h"

namespace amha {
namespace {

using testing::ExplicitGraph;

// b_i = floor(h_i * num / den): for the anchor a scaled consistent heuristic, so consistent
// (integer costs), and <= h_i. Infinite values keep base 0.
void setBases(ExplicitGraph& g, int num, int den) {
  g.b.assign(g.size(), std::vector<HeuristicValue>(g.n_heuristics, 0));
  for (std::size_t s = 0; s < g.size(); ++s) {
    for (std::size_t i = 0; i < g.n_heuristics; ++i) {
      const HeuristicValue h = g.h[s][i];
      g.b[s][i] =
          h == kInfiniteHeuristic ? 0 : static_cast<HeuristicValue>(std::uint64_t{h} * num / den);
    }
  }
}

std::vector<ExplicitGraph> graphs() {
  return testing::gridsAndGraphs(24, 18, 300, 1.0, 0.7, false);
}

const Algorithm kAll[] = {Algorithm::kAmhaStar, Algorithm::kMhaStar,       Algorithm::kAraStar,
                          Algorithm::kAnaStar,  Algorithm::kWeightedAStar, Algorithm::kAStar};

TEST(InflationBases, EveryAlgorithmKeepsItsBounds) {
  for (int num : {0, 1, 2}) {  // bases 0, h/3, 2h/3
    int k = 0;
    for (ExplicitGraph& g : graphs()) {
      setBases(g, num, 3);
      const Cost optimal = testing::distancesToGoal(g)[g.s_start];
      for (Algorithm a : kAll) {
        PlannerConfig c = defaultConfig(a);
        c.check_invariants = true;
        c.stop_when_certified_optimal = (k % 2) == 0;
        const SearchResult r = makePlanner(c)->search(g, SearchLimits());
        SCOPED_TRACE(std::string(algorithmName(a)) + " graph " + std::to_string(k) + " bases " +
                     std::to_string(num) + "/3");
        testing::expectValidResult(g, r, a, optimal);
      }
      ++k;
    }
  }
}

// Expansions and costs of every solution, to compare two runs.
std::string trace(ExplicitGraph& g, const PlannerConfig& c) {
  const SearchResult r = makePlanner(c)->search(g, SearchLimits());
  std::string t = std::to_string(static_cast<int>(r.status));
  for (const Solution& s : r.solutions) {
    t += " " + std::to_string(s.cost) + "@" + std::to_string(s.expansions) + "/" +
         std::to_string(s.certified_bound);
  }
  return t;
}

TEST(InflationBases, BasesEqualToTheHeuristicsChangeNothing) {
  // g + h + (w - 1) h = g + w h: the same search, queue by queue, for every weight.
  for (ExplicitGraph& g : graphs()) {
    for (Algorithm a : kAll) {
      const PlannerConfig c = defaultConfig(a);
      g.b.clear();
      const std::string without = trace(g, c);
      setBases(g, 1, 1);
      EXPECT_EQ(trace(g, c), without) << algorithmName(a);
    }
  }
}

TEST(InflationBases, AtWeightOneBasesChangeNothing) {
  for (ExplicitGraph& g : graphs()) {
    PlannerConfig c = defaultConfig(Algorithm::kAStar);
    g.b.clear();
    const std::string without = trace(g, c);
    setBases(g, 1, 2);
    EXPECT_EQ(trace(g, c), without);
  }
}

TEST(InflationBases, LowerBasesChangeWeightedSearches) {
  // Otherwise the tests above would pass with the bases ignored.
  int differ = 0;
  for (ExplicitGraph& g : graphs()) {
    const PlannerConfig c = defaultConfig(Algorithm::kWeightedAStar);
    g.b.clear();
    const std::string without = trace(g, c);
    setBases(g, 0, 1);
    differ += trace(g, c) != without;
  }
  EXPECT_GT(differ, 5);
}

}  // namespace
}  // namespace amha
