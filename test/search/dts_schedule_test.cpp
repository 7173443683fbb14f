// The DTS queue schedule: its bandit favours the arm that makes progress, forgets old evidence,
// is reproducible from its seed, and, inside MHA*, moves expansions to the informative queue.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "../../src/search/dts_schedule.h"
#include "test_graphs.h"

namespace amha {
namespace {

using detail::DtsSchedule;

std::vector<int> pickCounts(DtsSchedule& dts, std::size_t arms, std::size_t rewarded, int picks) {
  std::vector<int> count(arms + 1, 0);
  for (int k = 0; k < picks; ++k) {
    const std::size_t i = dts.pick();
    EXPECT_GE(i, 1u);
    EXPECT_LE(i, arms);
    ++count[i];
    dts.reward(i, i == rewarded);
  }
  return count;
}

TEST(DtsSchedule, FavoursTheArmThatMakesProgressAndFollowsAChange) {
  DtsSchedule dts;
  dts.reset(4, 1);
  const std::vector<int> first = pickCounts(dts, 4, 3, 2000);
  EXPECT_GT(first[3], 1800) << "arm 3 always pays and should get almost every pick";
  // Progress moves to arm 1: the capped window lets the schedule follow within a few dozen picks.
  pickCounts(dts, 4, 1, 100);
  const std::vector<int> second = pickCounts(dts, 4, 1, 2000);
  EXPECT_GT(second[1], 1800);
  EXPECT_LT(second[3], 100);
}

// The draws are exact Beta draws: against a uniform arm (Beta(1, 1)), an arm with one success
// (Beta(2, 1)) wins with probability E[X] = 2/3, one with one failure (Beta(1, 2)) with 1/3.
TEST(DtsSchedule, DrawsFollowTheBetaPosterior) {
  for (bool success : {true, false}) {
    DtsSchedule dts;
    dts.reset(2, 3);
    dts.reward(1, success);
    int wins = 0;
    const int n = 40000;
    for (int k = 0; k < n; ++k) wins += dts.pick() == 1;
    EXPECT_NEAR(static_cast<double>(wins) / n, success ? 2.0 / 3.0 : 1.0 / 3.0, 0.01);
  }
}

TEST(DtsSchedule, ExploresEveryArmWhenNoneMakesProgress) {
  DtsSchedule dts;
  dts.reset(4, 2);
  const std::vector<int> count = pickCounts(dts, 4, 0, 8000);  // arm 0 is never picked
  for (std::size_t i = 1; i <= 4; ++i) {
    EXPECT_GT(count[i], 1200) << "arm " << i;  // a quarter each would be 2000
  }
}

TEST(DtsSchedule, SameSeedSamePicksOtherSeedOtherPicks) {
  auto sequence = [](std::uint64_t seed) {
    DtsSchedule dts;
    dts.reset(6, seed);
    std::vector<std::size_t> picks;
    for (int k = 0; k < 500; ++k) {
      picks.push_back(dts.pick());
      dts.reward(picks.back(), k % 3 == 0);
    }
    return picks;
  };
  EXPECT_EQ(sequence(11), sequence(11));
  EXPECT_NE(sequence(11), sequence(12));
}

TEST(DtsSchedule, ProgressIsALowerSmallestHeuristicPerQueue) {
  DtsSchedule dts;
  dts.reset(2, 1);
  EXPECT_TRUE(dts.noteQueued(1, 50));
  EXPECT_FALSE(dts.noteQueued(1, 50));
  EXPECT_TRUE(dts.noteQueued(1, 49));
  EXPECT_TRUE(dts.noteQueued(2, 60));  // queues keep separate records
  dts.resetProgress();
  EXPECT_TRUE(dts.noteQueued(1, 70));
}

// One informative inadmissible heuristic (the exact distance) among seven that carry no
// information: round robin gives it an eighth of the expansions, DTS most of them, so DTS
// reaches the goal with far fewer expansions. Both stay within the bound.
TEST(DtsSchedule, MhaReachesTheGoalSoonerWhenOneQueueIsInformative) {
  std::uint64_t rr_total = 0, dts_total = 0;
  for (std::uint32_t seed = 1; seed <= 6; ++seed) {
    testing::GenOptions o;
    o.seed = seed;
    o.n_inadmissible = 8;
    testing::ExplicitGraph g = testing::randomGrid(60, 60, 0.15, o);
    const std::vector<Cost> dist = testing::distancesToGoal(g);
    if (dist[g.s_start] >= kInfiniteCost) continue;
    std::mt19937 rng(seed);
    std::uniform_int_distribution<HeuristicValue> noise(0, 2000);
    for (std::size_t s = 0; s < g.size(); ++s) {
      g.h[s][1] =
          dist[s] >= kInfiniteCost ? kInfiniteHeuristic : static_cast<HeuristicValue>(dist[s]);
      for (std::size_t i = 2; i <= 8; ++i) g.h[s][i] = noise(rng);
    }
    for (QueueSchedule schedule : {QueueSchedule::kRoundRobin, QueueSchedule::kDts}) {
      PlannerConfig config = defaultConfig(Algorithm::kMhaStar);
      config.schedule = schedule;
      const SearchResult r = makePlanner(config)->search(g, SearchLimits());
      ASSERT_TRUE(r.hasSolution());
      EXPECT_EQ(testing::validateSolution(g, r.best(), dist[g.s_start]), "");
      (schedule == QueueSchedule::kDts ? dts_total : rr_total) += r.best().expansions;
    }
  }
  ASSERT_GT(rr_total, 0u);
  EXPECT_LT(2 * dts_total, rr_total) << "DTS " << dts_total << ", round robin " << rr_total;
}

}  // namespace
}  // namespace amha
