// AlgorithmSpecs and applyWeights: each algorithm takes exactly the weights it reads, and only
// A-MHA* and MHA* ask for inadmissible heuristics.
#include <gtest/gtest.h>

#include "amha_planner/search/planner.h"

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

}  // namespace
}  // namespace amha
