// Limits and endings: no solution, time budget, cancel from another thread, expansion and
// state/memory caps. Searches on an endless grid would run forever without them.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <thread>

#include "test_graphs.h"

namespace amha {
namespace {

const Algorithm kAll[] = {Algorithm::kAmhaStar, Algorithm::kMhaStar,       Algorithm::kAraStar,
                          Algorithm::kAnaStar,  Algorithm::kWeightedAStar, Algorithm::kAStar};

TEST(Limits, UnreachableGoalEndsWithNoSolution) {
  testing::GenOptions o;
  testing::ExplicitGraph g = testing::randomGrid(20, 20, 0.0, o);
  // Wall off the goal: remove every edge into it.
  for (auto& edges : g.adj) {
    edges.erase(
        std::remove_if(edges.begin(), edges.end(), [&](const Edge& e) { return e.to == g.s_goal; }),
        edges.end());
  }
  for (auto& hs : g.h) hs[0] = 0;  // still admissible
  g.h[g.s_goal].assign(g.n_heuristics, 0);
  for (Algorithm a : kAll) {
    const SearchResult r = makePlanner(defaultConfig(a))->search(g, SearchLimits());
    EXPECT_EQ(r.status, SearchStatus::kNoSolution) << algorithmName(a);
    EXPECT_FALSE(r.hasSolution());
    EXPECT_FALSE(r.goal_side_proof) << "the start's states ran out: " << algorithmName(a);
  }
}

TEST(Limits, InfiniteAnchorAtStartMeansNoSolution) {
  testing::GenOptions o;
  testing::ExplicitGraph g = testing::randomGrid(10, 10, 0.0, o);
  g.h[g.s_start][0] = kInfiniteHeuristic;
  for (Algorithm a : kAll) {
    const SearchResult r = makePlanner(defaultConfig(a))->search(g, SearchLimits());
    EXPECT_EQ(r.status, SearchStatus::kNoSolution) << algorithmName(a);
  }
}

TEST(Limits, TimeBudgetHonouredWithinMilliseconds) {
  for (Algorithm a : kAll) {
    testing::EndlessGrid grid(5);
    SearchLimits limits;
    limits.time_limit_s = 0.05;
    const auto t0 = std::chrono::steady_clock::now();
    const SearchResult r = makePlanner(defaultConfig(a))->search(grid, limits);
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(r.status, SearchStatus::kTimeLimit) << algorithmName(a);
    EXPECT_GE(took, 0.05);
    // Wall clock on a shared machine: a loose sanity check. The tight guarantee is the
    // deterministic check-interval test below.
    EXPECT_LT(took, 0.05 + 0.25) << algorithmName(a);
    EXPECT_GT(r.expansions, 0u);
  }
}

TEST(Limits, CancelFromAnotherThread) {
  for (Algorithm a : kAll) {
    testing::EndlessGrid grid(3);
    std::atomic<bool> cancel{false};
    SearchLimits limits;
    limits.cancel = &cancel;
    std::chrono::steady_clock::time_point cancelled_at;
    std::thread canceller([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(30));
      cancelled_at = std::chrono::steady_clock::now();
      cancel = true;
    });
    const SearchResult r = makePlanner(defaultConfig(a))->search(grid, limits);
    const auto ended = std::chrono::steady_clock::now();
    canceller.join();
    EXPECT_EQ(r.status, SearchStatus::kCancelled) << algorithmName(a);
    EXPECT_LT(std::chrono::duration<double>(ended - cancelled_at).count(), 0.25);
  }
}

// Deterministic form of the two tests above: limits are checked at least every 64 expansions,
// so a search stops within 64 expansions of the cancel flag being set (here by the problem
// itself, at a known expansion). At ~1 us an expansion that is well under a millisecond.
class CancellingGrid : public testing::EndlessGrid {
 public:
  CancellingGrid(std::atomic<bool>* flag, std::uint64_t at)
      : EndlessGrid(3), flag_(flag), at_(at) {}
  void successors(StateId s, std::vector<Edge>& out) override {
    if (++calls_ == at_) *flag_ = true;
    EndlessGrid::successors(s, out);
  }
  std::uint64_t calls_ = 0;

 private:
  std::atomic<bool>* flag_;
  std::uint64_t at_;
};

TEST(Limits, CancelObservedWithin64Expansions) {
  for (Algorithm a : kAll) {
    for (std::uint64_t at : {1u, 100u, 12345u}) {
      std::atomic<bool> cancel{false};
      CancellingGrid grid(&cancel, at);
      SearchLimits limits;
      limits.cancel = &cancel;
      const SearchResult r = makePlanner(defaultConfig(a))->search(grid, limits);
      EXPECT_EQ(r.status, SearchStatus::kCancelled) << algorithmName(a);
      EXPECT_LE(r.expansions, at + 64) << algorithmName(a) << " cancelled at " << at;
    }
  }
}

// A domain that consults the search's limit check in a long operation, as the tiles' table
// rebuild does: the check is lent only while the search runs, is false until a limit is hit,
// and once it reports the cancel the search ends right after the current expansion.
class CheckingGrid : public testing::EndlessGrid {
 public:
  CheckingGrid(std::atomic<bool>* flag, std::uint64_t at) : EndlessGrid(3), flag_(flag), at_(at) {}
  void setInterruptCheck(std::function<bool()> check) override {
    check_ = std::move(check);
    if (check_) ++lent_;
  }
  void successors(StateId s, std::vector<Edge>& out) override {
    EXPECT_TRUE(check_) << "no check lent during the search";
    if (++calls_ == at_) {
      EXPECT_FALSE(check_()) << "a limit reported before any was hit";
      *flag_ = true;
      EXPECT_TRUE(check_()) << "the cancel went unnoticed";
      cancelled_at_ = calls_;
    }
    EndlessGrid::successors(s, out);
  }
  std::function<bool()> check_;
  int lent_ = 0;
  std::uint64_t calls_ = 0, cancelled_at_ = 0;

 private:
  std::atomic<bool>* flag_;
  std::uint64_t at_;
};

TEST(Limits, DomainSeesTheLimitCheckOnlyDuringTheSearch) {
  for (Algorithm a : kAll) {
    std::atomic<bool> cancel{false};
    CheckingGrid grid(&cancel, 500);
    SearchLimits limits;
    limits.cancel = &cancel;
    const SearchResult r = makePlanner(defaultConfig(a))->search(grid, limits);
    EXPECT_EQ(r.status, SearchStatus::kCancelled) << algorithmName(a);
    EXPECT_EQ(r.expansions, grid.cancelled_at_) << algorithmName(a) << ": went on after the check";
    EXPECT_EQ(grid.lent_, 1) << algorithmName(a);
    EXPECT_FALSE(grid.check_) << algorithmName(a) << ": the check outlived the search";
  }
}

TEST(Limits, ExpansionCap) {
  for (Algorithm a : kAll) {
    testing::EndlessGrid grid(2);
    SearchLimits limits;
    limits.max_expansions = 1000;
    const SearchResult r = makePlanner(defaultConfig(a))->search(grid, limits);
    EXPECT_EQ(r.status, SearchStatus::kExpansionLimit) << algorithmName(a);
    EXPECT_EQ(r.expansions, 1000u);
  }
}

TEST(Limits, StateCap) {
  for (Algorithm a : kAll) {
    testing::EndlessGrid grid(2);
    SearchLimits limits;
    limits.max_states = 5000;
    const SearchResult r = makePlanner(defaultConfig(a))->search(grid, limits);
    EXPECT_EQ(r.status, SearchStatus::kMemoryLimit) << algorithmName(a);
    EXPECT_LE(r.peak_states, 5000u + 4);
  }
}

TEST(Limits, MemoryCap) {
  for (Algorithm a : kAll) {
    testing::EndlessGrid grid(4);
    SearchLimits limits;
    limits.max_memory_bytes = 8u << 20;
    const SearchResult r = makePlanner(defaultConfig(a))->search(grid, limits);
    EXPECT_EQ(r.status, SearchStatus::kMemoryLimit) << algorithmName(a);
    EXPECT_LE(r.peak_memory_bytes, (8u << 20) + (1u << 20)) << algorithmName(a);
  }
}

// A small-key domain (bucket queues) with a hostile weight that is a multiple of 1/64: the
// nested buckets would be indexed up to (w1 * 64) * h, some 12 million bucket headers (580 MB)
// for h below 200 (the search fuzzer's find: 3.2 GB). The search keeps the heap instead.
TEST(Limits, AHugeWeightKeepsSmallKeyQueuesSmall) {
  testing::ExplicitGraph chain;
  const int n = 20;
  chain.adj.resize(n);
  chain.h.assign(n, {0});
  for (int s = 0; s + 1 < n; ++s) chain.adj[s].push_back(Edge{static_cast<StateId>(s + 1), 10});
  for (int s = 0; s < n; ++s) chain.h[s][0] = static_cast<HeuristicValue>(10 * (n - 1 - s));
  chain.s_goal = n - 1;
  chain.small_keys = true;
  PlannerConfig c = defaultConfig(Algorithm::kWeightedAStar);
  c.w1 = 63999.0 / 64.0;
  const SearchResult r = makePlanner(c)->search(chain, SearchLimits());
  ASSERT_TRUE(r.hasSolution());
  EXPECT_EQ(r.best().cost, 10 * (n - 1));
  EXPECT_LT(r.peak_memory_bytes, 16u << 20);
}

}  // namespace
}  // namespace amha
