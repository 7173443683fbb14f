// gtest checks of a search's result against the exact optimum, for the search tests (the
// fuzzers share test_graphs.h without gtest).
#pragma once

#include <gtest/gtest.h>

#include "test_graphs.h"

namespace amha {
namespace testing {

/// Checks algorithm a's result on g: no solution exactly when none exists, every solution valid
/// (validateSolution) and within its nominal bound, and the algorithms that prove (all but
/// weighted A* and MHA*) proven optimal.
inline void expectValidResult(ExplicitGraph& g, const SearchResult& r, Algorithm a, Cost optimal) {
  if (optimal >= kInfiniteCost) {
    EXPECT_EQ(r.status, SearchStatus::kNoSolution);
    return;
  }
  ASSERT_FALSE(r.solutions.empty());
  for (const Solution& s : r.solutions) {
    EXPECT_EQ(validateSolution(g, s, optimal), "");
    EXPECT_LE(static_cast<double>(s.cost), s.nominal_bound * static_cast<double>(optimal) + 1e-9);
  }
  if (a != Algorithm::kWeightedAStar && a != Algorithm::kMhaStar) {
    EXPECT_EQ(r.status, SearchStatus::kProvenOptimal);
    EXPECT_EQ(r.best().cost, optimal);
  }
}

}  // namespace testing
}  // namespace amha
