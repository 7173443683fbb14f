// The search domain: dense ids for distinct boards, incremental heuristic terms equal to the
// from-scratch ones, successors without reallocation, heuristics as documented, memory cap.
#include <gtest/gtest.h>

#include <deque>
#include <map>

#include "amha_planner/search/planner.h"
#include "amha_planner/tiles/instances.h"
#include "amha_planner/tiles/tiles_problem.h"

namespace amha {
namespace tiles {
namespace {

// Breadth-first over the problem's own successors, checking every discovered state.
void exploreAndCheck(TilesProblem& p, std::size_t max_states) {
  std::map<std::vector<std::uint8_t>, StateId> seen;
  std::deque<StateId> queue{p.start()};
  std::vector<bool> queued(1, true);
  std::vector<Edge> out;
  std::size_t expanded = 0;
  while (!queue.empty() && p.numStates() < max_states) {
    const StateId s = queue.front();
    queue.pop_front();
    const Board b = p.board(s);
    p.successors(s, out);
    ++expanded;
    ASSERT_EQ(out.size(), blankNeighbours(b).size());
    for (const Edge& e : out) {
      ASSERT_EQ(e.cost, 1);
      ASSERT_LT(e.to, p.numStates());
      const Board c = p.board(e.to);
      ASSERT_TRUE(isOneMoveApart(b, c)) << toString(b) << " -> " << toString(c);
      const HeuristicTerms want = heuristicTerms(c);
      const HeuristicTerms got = p.terms(e.to);
      ASSERT_EQ(got.md, want.md) << toString(c);
      ASSERT_EQ(got.lc, want.lc) << toString(c);
      ASSERT_EQ(got.mt, want.mt) << toString(c);
      const auto ins = seen.emplace(c.tiles, e.to);
      ASSERT_EQ(ins.first->second, e.to) << "one board, two ids: " << toString(c);
      if (e.to >= queued.size()) queued.resize(e.to + 1, false);
      if (!queued[e.to]) {
        queued[e.to] = true;
        queue.push_back(e.to);
      }
    }
  }
  // Ids are dense: every id below numStates() is a distinct board.
  std::map<std::vector<std::uint8_t>, StateId> all;
  for (StateId id = 0; id < p.numStates(); ++id) {
    ASSERT_TRUE(all.emplace(p.board(id).tiles, id).second) << "board stored twice";
  }
  EXPECT_GT(expanded, 0u);
}

TEST(TilesProblem, IncrementalTermsMatchFromScratchOnEverySize) {
  for (int n = kMinSize; n <= kMaxSize; ++n) {
    for (std::uint64_t i = 0; i < 3; ++i) {
      const Board start = i == 0 ? randomWalkBoard(n, 30, 1, i) : randomSolvableBoard(n, 1, i);
      auto p = TilesProblem::create(start, randomTermWeights(4, 1));
      exploreAndCheck(*p, 20000);
    }
  }
}

TEST(TilesProblem, Whole3x3SpaceHasDenseDistinctIds) {
  auto p = TilesProblem::create(randomSolvableBoard(3, 8, 0), {});
  exploreAndCheck(*p, 1000000);
  EXPECT_EQ(p->numStates(), 181440u);
}

TEST(TilesProblem, StartGoalAndHeuristics) {
  const Board start = randomSolvableBoard(4, 3, 0);
  const auto w = randomTermWeights(4, 9);
  auto p = TilesProblem::create(start, w);
  EXPECT_EQ(p->numHeuristics(), 5u);
  EXPECT_EQ(p->board(p->start()), start);
  EXPECT_EQ(p->board(p->goal()), goalBoard(4));
  HeuristicValue h[5];
  p->heuristics(p->goal(), h, 5);
  for (HeuristicValue v : h) EXPECT_EQ(v, 0u);
  p->heuristics(p->start(), h, 5);
  const HeuristicTerms t = heuristicTerms(start);
  EXPECT_EQ(h[0], static_cast<HeuristicValue>(t.md + t.lc));
  for (int i = 1; i < 5; ++i) EXPECT_EQ(h[i], weightedValue(t, w[i - 1]));
  // Start equal to the goal: one state.
  auto same = TilesProblem::create(goalBoard(5), {});
  EXPECT_EQ(same->start(), same->goal());
  EXPECT_EQ(same->numStates(), 1u);
}

TEST(TilesProblem, RejectsBadStarts) {
  Board b = goalBoard(4);
  std::swap(b.tiles[1], b.tiles[2]);
  EXPECT_THROW(TilesProblem::create(b, {}), std::invalid_argument);
  b.tiles[1] = 1;  // duplicate
  EXPECT_THROW(TilesProblem::create(b, {}), std::invalid_argument);
  EXPECT_THROW(TilesProblem::create(goalBoard(4), {TermWeights{-1, 1, 1}}), std::invalid_argument);
}

TEST(TilesProblem, SuccessorsReuseTheBuffer) {
  auto p = TilesProblem::create(randomSolvableBoard(8, 2, 0), {});
  std::vector<Edge> out;
  out.reserve(4);
  const Edge* data = out.data();
  StateId s = p->start();
  for (int i = 0; i < 2000; ++i) {
    p->successors(s, out);
    ASSERT_EQ(out.data(), data);
    s = out[static_cast<std::size_t>(i) % out.size()].to;
  }
}

TEST(TilesProblem, MemoryIsCountedAndSmallPerState) {
  auto p = TilesProblem::create(randomSolvableBoard(4, 5, 0), {});
  exploreAndCheck(*p, 200000);
  const double per_state = static_cast<double>(p->memoryBytes()) / p->numStates();
  // 8 bytes of board + 4 of terms + 4-byte table slots at load 0.35..0.7, plus chunk rounding.
  EXPECT_GT(per_state, 12.0);
  EXPECT_LT(per_state, 32.0);
  EXPECT_EQ(p->memoryBytes(), p->arenaBytes() + p->tableBytes());
}

// The table's rebuild yields to the search's limits (a rebuild of tens of millions of states
// takes seconds) until the table is 90 % full, and the table stays valid either way.
TEST(TilesProblem, TableGrowthYieldsToTheSearchLimitsUntilNinetyPercentFull) {
  auto p = TilesProblem::create(randomSolvableBoard(3, 8, 0), {});
  const std::size_t first_table = p->tableBytes();  // 2^12 slots: would double at 2868 states
  int calls = 0;
  p->setInterruptCheck([&calls] {
    ++calls;
    return true;  // "the search must stop"
  });
  exploreAndCheck(*p, 3500);
  EXPECT_GT(calls, 0);
  EXPECT_EQ(p->tableBytes(), first_table) << "grew although the search had to stop";
  exploreAndCheck(*p, 1000000);  // past 90 % it grows anyway; every board keeps its id
  EXPECT_EQ(p->numStates(), 181440u);
  EXPECT_GT(p->tableBytes(), first_table);
}

// A search lends its check only while it runs: a problem searched by a planner that no longer
// exists grows its table without calling into it (ASan would catch a dangling check).
TEST(TilesProblem, OutlivesThePlannerThatSearchedIt) {
  auto p = TilesProblem::create(randomSolvableBoard(3, 8, 0), randomTermWeights(2, 1));
  {
    SearchLimits limits;
    limits.max_expansions = 100;
    makePlanner(defaultConfig(Algorithm::kAmhaStar))->search(*p, limits);
  }
  exploreAndCheck(*p, 1000000);
  EXPECT_EQ(p->numStates(), 181440u);
}

// A search that needs more than the cap ends with kMemoryLimit instead of exhausting memory.
TEST(TilesProblem, MemoryCapEndsTheSearch) {
  auto p = TilesProblem::create(randomSolvableBoard(8, 1, 0), randomTermWeights(4, 1));
  SearchLimits limits;
  limits.max_memory_bytes = 64u << 20;
  limits.time_limit_s = 60;
  const SearchResult r = makePlanner(defaultConfig(Algorithm::kAStar))->search(*p, limits);
  EXPECT_EQ(r.status, SearchStatus::kMemoryLimit);
  EXPECT_LT(r.peak_memory_bytes, 2 * limits.max_memory_bytes);
}

}  // namespace
}  // namespace tiles
}  // namespace amha
