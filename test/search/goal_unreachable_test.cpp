// SearchProblem::goalUnreachable: the engines ask it while they have no path, at expansions 0,
// 32768, 4 x 32768, ... with a budget of a sixteenth of the expansions, stop with kNoSolution on
// its proof, and never ask once a path has been reported.
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "test_graphs.h"

namespace amha {
namespace {

const Algorithm kAll[] = {Algorithm::kAmhaStar, Algorithm::kMhaStar,       Algorithm::kAraStar,
                          Algorithm::kAnaStar,  Algorithm::kWeightedAStar, Algorithm::kAStar};

// An endless grid (no path: the goal is no grid cell) whose domain proves that once it may
// look at `needed` states.
class ProvableEndlessGrid : public testing::EndlessGrid {
 public:
  explicit ProvableEndlessGrid(std::size_t needed) : EndlessGrid(3), needed_(needed) {}
  bool goalUnreachable(std::size_t budget) override {
    budgets.push_back(budget);
    return budget >= needed_;
  }
  std::vector<std::size_t> budgets;

 private:
  std::size_t needed_;
};

TEST(GoalUnreachable, AskedOnASpacedScheduleAndStopsTheSearchWithNoSolution) {
  for (Algorithm a : kAll) {
    ProvableEndlessGrid grid(2048);
    SearchLimits limits;
    limits.time_limit_s = 20;
    const SearchResult r = makePlanner(defaultConfig(a))->search(grid, limits);
    EXPECT_EQ(r.status, SearchStatus::kNoSolution) << algorithmName(a);
    EXPECT_FALSE(r.hasSolution());
    EXPECT_TRUE(r.goal_side_proof) << algorithmName(a);
    // Asked at 0 (budget 64) and at 32768 expansions (2048 states), which proves it.
    EXPECT_EQ(grid.budgets, (std::vector<std::size_t>{64, 2048})) << algorithmName(a);
    EXPECT_EQ(r.expansions, 32768u) << algorithmName(a);
  }
}

TEST(GoalUnreachable, BudgetsGrowFourfoldWhileNothingIsKnown) {
  ProvableEndlessGrid grid(1u << 30);  // never proven
  SearchLimits limits;
  limits.max_expansions = 2200000;
  const SearchResult r = makePlanner(defaultConfig(Algorithm::kAStar))->search(grid, limits);
  EXPECT_EQ(r.status, SearchStatus::kExpansionLimit);
  EXPECT_FALSE(r.goal_side_proof);
  EXPECT_EQ(grid.budgets, (std::vector<std::size_t>{64, 2048, 8192, 32768, 131072}));
}

// A solvable grid whose domain answers "unreachable" whenever asked: a search must not ask it
// once it has a path (and the answer at expansion 0 is what a domain that proves it would say,
// so the first ask must come from a search without a path).
class LyingAfterAPath : public testing::ExplicitGraph {
 public:
  explicit LyingAfterAPath(const testing::ExplicitGraph& g) : ExplicitGraph(g) {}
  bool goalUnreachable(std::size_t) override {
    ++asked;
    if (path_reported) ++asked_after_path;
    return path_reported;
  }
  int asked = 0, asked_after_path = 0;
  bool path_reported = false;
};

TEST(GoalUnreachable, NeverAskedOnceAPathIsReported) {
  testing::GenOptions o;
  o.n_inadmissible = 3;
  o.anchor_scale = 0.3;  // a weak anchor: the anytime searches go on long after the first path
  for (Algorithm a : kAll) {
    LyingAfterAPath p(testing::randomGrid(300, 300, 0.1, o));
    const SearchResult r =
        makePlanner(defaultConfig(a))->search(p, SearchLimits(), [&](const Solution&) {
          p.path_reported = true;
        });
    ASSERT_TRUE(r.hasSolution()) << algorithmName(a);
    EXPECT_TRUE(r.status == SearchStatus::kProvenOptimal ||
                r.status == SearchStatus::kBoundReached)  // MHA* and weighted A*: one bound
        << algorithmName(a);
    EXPECT_GE(p.asked, 1) << algorithmName(a);
    EXPECT_EQ(p.asked_after_path, 0) << algorithmName(a);
  }
}

}  // namespace
}  // namespace amha
