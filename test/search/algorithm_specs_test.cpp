// AlgorithmSpecs and applyWeights: each algorithm takes exactly the weights it reads, and only
// A-MHA* and MHA* ask for inadmissible heuristics.
#include <gtest/gtest.h>

#include "amha_planner/search/planner.h"
#include "test_graphs.h"

namespace amha {
namespace {

TEST(AlgorithmSpecs, OnlyTheMultiHeuristicSearchesReadInadmissibleHeuristics) {
  EXPECT_TRUE(algorithmSpecs(Algorithm::kAmhaStar).inadmissible_heuristics);
  EXPECT_TRUE(algorithmSpecs(Algorithm::kMhaStar).inadmissible_heuristics);
  for (Algorithm a :
       {Algorithm::kAraStar, Algorithm::kAnaStar, Algorithm::kWeightedAStar, Algorithm::kAStar}) {
    EXPECT_FALSE(algorithmSpecs(a).inadmissible_heuristics) << algorithmName(a);
    EXPECT_FALSE(algorithmSpecs(a).queue_schedule) << algorithmName(a);
  }
}

TEST(AlgorithmSpecs, ChosenWeightsReachOnlyTheAlgorithmsThatReadThem) {
  const WeightChoice all{2.0, 3.0, 0.25, 0.75};
  PlannerConfig amha = defaultConfig(Algorithm::kAmhaStar);
  applyWeights(all, &amha);
  EXPECT_EQ(amha.w1, 2.0);
  EXPECT_EQ(amha.w2, 3.0);
  EXPECT_EQ(amha.dw1, 0.25);
  EXPECT_EQ(amha.dw2, 0.75);

  PlannerConfig ara = defaultConfig(Algorithm::kAraStar);
  applyWeights(all, &ara);
  EXPECT_EQ(ara.w1, 2.0);
  EXPECT_EQ(ara.dw1, 0.25);
  EXPECT_EQ(ara.w2, defaultConfig(Algorithm::kAraStar).w2);
  EXPECT_EQ(ara.dw2, defaultConfig(Algorithm::kAraStar).dw2);

  PlannerConfig wastar = defaultConfig(Algorithm::kWeightedAStar);
  applyWeights(all, &wastar);
  EXPECT_EQ(wastar.w1, 2.0);
  EXPECT_EQ(wastar.dw1, 0.0);

  for (Algorithm a : {Algorithm::kAStar, Algorithm::kAnaStar}) {
    PlannerConfig c = defaultConfig(a);
    applyWeights(all, &c);
    EXPECT_EQ(c.w1, 1.0) << algorithmName(a);
    EXPECT_EQ(c.w2, 1.0) << algorithmName(a);
  }

  PlannerConfig kept = defaultConfig(Algorithm::kAmhaStar);
  applyWeights({std::nullopt, 4.0, std::nullopt, std::nullopt}, &kept);  // unset: unchanged
  EXPECT_EQ(kept.w1, defaultConfig(Algorithm::kAmhaStar).w1);
  EXPECT_EQ(kept.w2, 4.0);
}

// Each solution names the edges its path takes (Edge::label), the cheapest of parallel edges
// (the one its cost counts), for the domain to turn the path into its own terms in one pass.
TEST(SolutionEdges, EveryAlgorithmHandsBackTheLabelsOfTheEdgesItCosted) {
  testing::ExplicitGraph g;
  g.adj.resize(4);
  g.adj[0] = {Edge{1, 5, 10}, Edge{1, 3, 11}, Edge{2, 1, 12}};  // two edges 0 -> 1: 11 is cheaper
  g.adj[1] = {Edge{3, 1, 13}};
  g.adj[2] = {Edge{3, 9, 14}};
  g.adj[3] = {};
  g.h.assign(4, {0});
  g.s_start = 0;
  g.s_goal = 3;
  for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kMhaStar, Algorithm::kAraStar,
                      Algorithm::kAnaStar, Algorithm::kWeightedAStar, Algorithm::kAStar}) {
    const SearchResult r = makePlanner(defaultConfig(a))->search(g, SearchLimits());
    ASSERT_TRUE(r.hasSolution()) << algorithmName(a);
    for (const Solution& s : r.solutions) {  // each path's labels: its cheapest edges'
      ASSERT_EQ(s.edge_labels.size() + 1, s.path.size()) << algorithmName(a);
      for (std::size_t k = 1; k < s.path.size(); ++k) {
        const Edge* cheapest = nullptr;
        for (const Edge& e : g.adj[s.path[k - 1]]) {
          if (e.to == s.path[k] && (cheapest == nullptr || e.cost < cheapest->cost)) cheapest = &e;
        }
        ASSERT_NE(cheapest, nullptr);
        EXPECT_EQ(s.edge_labels[k - 1], cheapest->label) << algorithmName(a);
      }
    }
    if (r.status != SearchStatus::kProvenOptimal) continue;  // MHA*, weighted A*: 0 2 3 will do
    EXPECT_EQ(r.best().path, (std::vector<StateId>{0, 1, 3})) << algorithmName(a);
    EXPECT_EQ(r.best().edge_labels, (std::vector<std::uint32_t>{11, 13})) << algorithmName(a);
    EXPECT_EQ(r.best().cost, 4) << algorithmName(a);
  }
}

}  // namespace
}  // namespace amha
