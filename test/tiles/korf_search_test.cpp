// Searches on Korf's 100 15-puzzles: the anchor is a lower bound on every optimal length; A*
// finds the optimal length on the instances the test budget allows; every solution of the
// anytime algorithms replays move by move to the goal within its certified bound.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "amha_planner/search/planner.h"
#include "amha_planner/tiles/instances.h"
#include "amha_planner/tiles/tiles_problem.h"
#include "test_support.h"

namespace amha {
namespace tiles {
namespace {

std::vector<Instance> korf() {
  const std::string path = testing::korfFile();
  if (path.empty() || !std::ifstream(path)) return {};
  return readInstances(path, 4);
}

TEST(Korf100, AnchorNeverExceedsTheOptimalLength) {
  const auto inst = korf();
  if (inst.empty()) GTEST_SKIP() << "shared data absent";
  for (const Instance& i : inst) {
    auto p = TilesProblem::create(i.start, {});
    HeuristicValue h0 = 0;
    p->heuristics(p->start(), &h0, 1);
    EXPECT_LE(static_cast<int>(h0), *i.optimal) << "instance " << i.id;
  }
}

// The 43 instances A* (anchor MD + LC, this engine's tie-breaking: smaller h, then newest)
// solves in under 500,000 expansions (measured with the bucket queues: 11,782 for instance 12
// .. 438,983 for instance 69; 5.9 M in total; the heap's order gave the same 43). The other 57 need
// up to billions of expansions; `amha tiles --instances korf100_15puzzle.txt --algorithms astar`
// runs them as a benchmark instead.
const int kCheapForAStar[] = {6,  9,  12, 13, 16, 18, 19, 23, 28, 30, 31, 34, 36, 38, 39,
                              42, 44, 45, 46, 47, 48, 50, 55, 57, 58, 61, 65, 69, 71, 73,
                              74, 78, 79, 81, 83, 85, 86, 90, 93, 94, 95, 96, 97};

TEST(Korf100, AStarFindsTheOptimalLength) {
  const auto inst = korf();
  if (inst.empty()) GTEST_SKIP() << "shared data absent";
  for (int id : kCheapForAStar) {
    const Instance& i = inst[static_cast<std::size_t>(id - 1)];
    ASSERT_EQ(i.id, std::to_string(id));
    auto p = TilesProblem::create(i.start, {});
    SearchLimits limits;
    limits.max_expansions = 2000000;  // 4x the measured need: a safety net, not a target
    const SearchResult r = makePlanner(defaultConfig(Algorithm::kAStar))->search(*p, limits);
    ASSERT_EQ(r.status, SearchStatus::kProvenOptimal) << "instance " << id;
    EXPECT_EQ(r.best().cost, *i.optimal) << "instance " << id;
  }
}

// Replays a solution on the boards: it starts at the start, ends at the goal, and every step
// is one legal move; its length is its cost and is within certified_bound * optimal.
void checkSolution(const TilesProblem& p, const Instance& inst, const Solution& s,
                   const char* algorithm) {
  SCOPED_TRACE(std::string(algorithm) + " on instance " + inst.id);
  ASSERT_GE(s.path.size(), 1u);
  ASSERT_EQ(p.board(s.path.front()), inst.start);
  ASSERT_EQ(p.board(s.path.back()), goalBoard(4));
  Board prev = p.board(s.path.front());
  for (std::size_t k = 1; k < s.path.size(); ++k) {
    const Board next = p.board(s.path[k]);
    ASSERT_TRUE(isOneMoveApart(prev, next)) << "step " << k;
    prev = next;
  }
  EXPECT_EQ(s.cost, static_cast<Cost>(s.path.size() - 1));
  EXPECT_GE(s.cost, *inst.optimal);
  EXPECT_GE(s.certified_bound, 1.0);
  if (std::isfinite(s.nominal_bound)) {
    EXPECT_LE(s.certified_bound, s.nominal_bound + 1e-12);
  }
  EXPECT_LE(static_cast<double>(s.cost), s.certified_bound * *inst.optimal + 1e-9);
}

// Runs `config` on every instance (50 k expansions each) and replays every solution; returns
// how many solutions there were.
std::size_t replayAll(const std::vector<Instance>& inst, const PlannerConfig& config,
                      const std::string& label) {
  const auto weights = randomTermWeights(4, 1);
  auto planner = makePlanner(config);
  std::size_t solutions = 0;
  for (const Instance& i : inst) {
    auto p = TilesProblem::create(i.start, weights);
    SearchLimits limits;
    limits.max_expansions = 50000;
    const SearchResult r = planner->search(*p, limits);
    EXPECT_TRUE(r.hasSolution()) << label << " on instance " << i.id;
    Cost last = kInfiniteCost;
    for (const Solution& s : r.solutions) {
      checkSolution(*p, i, s, label.c_str());
      EXPECT_LE(s.cost, last);
      last = s.cost;
      ++solutions;
    }
  }
  return solutions;
}

TEST(Korf100, AnytimeSolutionsReplayWithinTheirCertifiedBounds) {
  const auto inst = korf();
  if (inst.empty()) GTEST_SKIP() << "shared data absent";
  std::size_t solutions = 0;
  for (Algorithm a :
       {Algorithm::kAmhaStar, Algorithm::kMhaStar, Algorithm::kAraStar, Algorithm::kAnaStar}) {
    solutions += replayAll(inst, defaultConfig(a), algorithmName(a));
  }
  EXPECT_GT(solutions, 400u);
}

// The same with the DTS queue schedule: a different order of expansions, the same guarantees.
TEST(Korf100, DtsScheduleSolutionsReplayWithinTheirCertifiedBounds) {
  const auto inst = korf();
  if (inst.empty()) GTEST_SKIP() << "shared data absent";
  std::size_t solutions = 0;
  for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kMhaStar}) {
    PlannerConfig config = defaultConfig(a);
    config.schedule = QueueSchedule::kDts;
    solutions += replayAll(inst, config, std::string(algorithmName(a)) + " (dts)");
  }
  EXPECT_GT(solutions, 200u);
}

}  // namespace
}  // namespace tiles
}  // namespace amha
