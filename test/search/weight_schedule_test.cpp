// The anytime weight schedules (WeightSchedule): the certified schedule's solutions stay within
// their bounds and end proven optimal, every reported iteration after the first expands
// something (no copies of one solution), and weights up to kMaxWeight find the goal (a huge
// weight once made the unreached goal's sentinel pass the stop test: a false "no path").
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <string>

#include "../../src/search/mha_engine.h"
#include "test_graphs.h"

namespace amha {
namespace {

using testing::ExplicitGraph;

std::vector<ExplicitGraph> graphs() { return testing::gridsAndGraphs(28, 22, 400, 0.6, 1.0, true); }

// Every solution valid and within its bounds, costs never rising, the last proven optimal, and
// every solution after the first but the proof coming from an iteration that expanded states.
void checkStream(ExplicitGraph& g, const PlannerConfig& c, const std::string& label) {
  SCOPED_TRACE(label);
  const Cost optimal = testing::distancesToGoal(g)[g.s_start];
  const SearchResult r = makePlanner(c)->search(g, SearchLimits());
  if (optimal >= kInfiniteCost) {
    EXPECT_EQ(r.status, SearchStatus::kNoSolution);
    return;
  }
  ASSERT_TRUE(r.hasSolution());
  EXPECT_EQ(r.status, SearchStatus::kProvenOptimal);
  EXPECT_EQ(r.best().cost, optimal);
  for (std::size_t k = 0; k < r.solutions.size(); ++k) {
    const Solution& s = r.solutions[k];
    EXPECT_EQ(testing::validateSolution(g, s, optimal), "");
    if (k == 0) continue;
    EXPECT_LE(s.cost, r.solutions[k - 1].cost);
    // The last iteration (w1 = w2 = 1) always runs, and may find nothing left to expand.
    if (s.nominal_bound > 1.0) {
      EXPECT_GT(s.expansions, r.solutions[k - 1].expansions)
          << "solution " << k << " repeats the last one";
    }
    EXPECT_LT(s.nominal_bound, r.solutions[k - 1].nominal_bound);
  }
}

TEST(WeightSchedule, CertifiedSolutionsBoundedImprovingAndOptimalAtTheEnd) {
  int more_than_two = 0;
  for (ExplicitGraph& g : graphs()) {
    for (const Algorithm a : {Algorithm::kAmhaStar, Algorithm::kAraStar}) {
      for (const double split : {0.0, 0.5, 1.0}) {
        PlannerConfig c = defaultConfig(a);
        c.w1 = 3.0;
        c.weight_schedule = WeightSchedule::kCertified;
        c.certified_ratio = 0.4;
        c.certified_split = split;
        c.final_gap = 0.0;
        c.check_invariants = true;
        checkStream(g, c, std::string(algorithmName(a)) + " split " + std::to_string(split));
        more_than_two += makePlanner(c)->search(g, SearchLimits()).solutions.size() > 2;
      }
    }
  }
  EXPECT_GT(more_than_two, 10)
      << "the certified schedule should publish solutions between the first and the last";
}

// Publishing within iterations: every solution still valid and within its bounds, costs
// falling, and between the first and the proof the stream holds cheaper paths or tighter
// certified bounds even when the schedule goes straight from the first iteration to the proof.
TEST(WeightSchedule, PublishingWithinIterationsFillsTheMiddleHonestly) {
  int middles = 0, runs = 0;
  for (ExplicitGraph& g : graphs()) {
    const Cost optimal = testing::distancesToGoal(g)[g.s_start];
    if (optimal >= kInfiniteCost) continue;
    for (const Algorithm a : {Algorithm::kAmhaStar, Algorithm::kAraStar}) {
      PlannerConfig c = defaultConfig(a);
      c.w1 = 3.0;
      c.weight_schedule = WeightSchedule::kCertified;
      c.certified_ratio = 0.0;  // straight to the proof
      c.publish_within_iterations = true;
      c.check_invariants = true;
      const SearchResult r = makePlanner(c)->search(g, SearchLimits());
      ASSERT_TRUE(r.hasSolution());
      EXPECT_EQ(r.status, SearchStatus::kProvenOptimal);
      EXPECT_EQ(r.best().cost, optimal);
      for (std::size_t k = 0; k < r.solutions.size(); ++k) {
        const Solution& s = r.solutions[k];
        EXPECT_EQ(testing::validateSolution(g, s, optimal), "")
            << algorithmName(a) << " solution " << k;
        if (k == 0) continue;
        EXPECT_LE(s.cost, r.solutions[k - 1].cost);
        EXPECT_TRUE(s.cost < r.solutions[k - 1].cost ||
                    s.certified_bound < r.solutions[k - 1].certified_bound)
            << algorithmName(a) << " solution " << k << " tells nothing new";
      }
      ++runs;
      middles += r.solutions.size() > 2;
    }
  }
  EXPECT_GT(middles, runs / 4)
      << "publishing within iterations should fill the middle of many runs";
}

// The stall rule's setting of the tests below: w1 = 1 stalls after 3 expansions, then w1 = 4
// (after `mid` for 4 more expansions, with a middle rung).
PlannerConfig stallConfig(Algorithm a, double mid = 0.0) {
  PlannerConfig c = defaultConfig(a);
  c.w1 = 1.0;
  c.w2 = a == Algorithm::kAmhaStar ? 2.0 : 1.0;
  c.weight_schedule = WeightSchedule::kCertified;
  c.certified_ratio = 0.0;
  c.stall_expansions = 3;
  c.stall_w1 = 4.0;
  c.stall_mid_w1 = mid;
  c.stall_mid_expansions = mid > 0.0 ? 4 : 0;
  c.check_invariants = true;
  return c;
}

// Runs c on g: the stream ends proven optimal with every bound honest.
SearchResult expectHonestStream(ExplicitGraph& g, const PlannerConfig& c, Cost optimal) {
  SearchResult r = makePlanner(c)->search(g, SearchLimits());
  EXPECT_TRUE(r.hasSolution());
  if (!r.hasSolution()) return r;
  EXPECT_EQ(r.status, SearchStatus::kProvenOptimal);
  EXPECT_EQ(r.best().cost, optimal);
  for (const Solution& s : r.solutions) EXPECT_EQ(testing::validateSolution(g, s, optimal), "");
  return r;
}

// A first iteration that stalls gives way to a larger w1: the path it finds carries that
// iteration's bound, and the stream still ends proven optimal with every bound honest.
TEST(WeightSchedule, AStalledFirstIterationGoesOnWithALargerW1) {
  int escalated = 0;
  for (ExplicitGraph& g : graphs()) {
    const Cost optimal = testing::distancesToGoal(g)[g.s_start];
    if (optimal >= kInfiniteCost) continue;
    for (const Algorithm a : {Algorithm::kAmhaStar, Algorithm::kAraStar}) {
      const PlannerConfig c = stallConfig(a);
      const SearchResult r = expectHonestStream(g, c, optimal);
      if (r.hasSolution() && r.solutions.front().w1 == 4.0) {
        ++escalated;
        EXPECT_GE(r.solutions.front().expansions, 3u);
        EXPECT_EQ(r.solutions.front().nominal_bound, 4.0 * c.w2);
      }
    }
  }
  EXPECT_GT(escalated, 5);
}

// With a middle rung the stalled first iteration goes on at stall_mid_w1, and at stall_w1 only
// after stall_mid_expansions more without a path; each path carries its own iteration's bound.
// A middle rung outside (w1, stall_w1) is skipped.
TEST(WeightSchedule, AStalledFirstIterationClimbsTheMiddleRungFirst) {
  int at_mid = 0, at_top = 0, runs = 0;
  for (ExplicitGraph& g : graphs()) {
    const Cost optimal = testing::distancesToGoal(g)[g.s_start];
    if (optimal >= kInfiniteCost) continue;
    for (const Algorithm a : {Algorithm::kAmhaStar, Algorithm::kAraStar}) {
      for (const double mid : {2.0, 4.0, 6.0}) {
        const PlannerConfig c = stallConfig(a, mid);
        const SearchResult r = expectHonestStream(g, c, optimal);
        if (!r.hasSolution()) continue;
        const Solution& first = r.solutions.front();
        EXPECT_TRUE(first.w1 == 1.0 || first.w1 == 4.0 || (mid == 2.0 && first.w1 == 2.0))
            << "first w1 " << first.w1 << " with a middle rung at " << mid;
        EXPECT_EQ(first.nominal_bound, first.w1 * c.w2);
        if (mid != 2.0) continue;
        ++runs;
        if (first.w1 == 2.0) {
          ++at_mid;
          EXPECT_GE(first.expansions, 3u);
        } else if (first.w1 == 4.0) {
          ++at_top;
          EXPECT_GE(first.expansions, 3u + 4u) << "the middle rung had its budget first";
        }
      }
    }
  }
  EXPECT_GT(at_mid, runs / 10) << "some first paths come from the middle rung";
  EXPECT_GT(at_top, 0) << "some stall there too";
}

TEST(WeightSchedule, DecrementsReportNoIterationThatStopsAtOnce) {
  for (ExplicitGraph& g : graphs()) {
    for (const Algorithm a : {Algorithm::kAmhaStar, Algorithm::kAraStar}) {
      PlannerConfig c = defaultConfig(a);
      c.stop_when_certified_optimal = false;  // walk the whole ladder
      c.check_invariants = true;
      checkStream(g, c, std::string(algorithmName(a)) + " decrement");
    }
  }
}

TEST(WeightSchedule, HugeWeightsStillFindTheGoal) {
  for (ExplicitGraph& g : graphs()) {
    const Cost optimal = testing::distancesToGoal(g)[g.s_start];
    if (optimal >= kInfiniteCost) continue;
    for (const Algorithm a : {Algorithm::kAmhaStar, Algorithm::kMhaStar, Algorithm::kAraStar,
                              Algorithm::kWeightedAStar}) {
      PlannerConfig c = defaultConfig(a);
      c.w1 = kMaxWeight;
      if (a == Algorithm::kAmhaStar || a == Algorithm::kMhaStar) c.w2 = kMaxWeight;
      c.dw1 = 0.5;  // millions of decrements: they must not all be walked one by one
      const SearchResult r = makePlanner(c)->search(g, SearchLimits());
      ASSERT_TRUE(r.hasSolution()) << algorithmName(a) << ": " << statusName(r.status);
      EXPECT_EQ(testing::validateSolution(g, r.best(), optimal), "");
      EXPECT_LT(r.solutions.size(), 60u) << algorithmName(a);
    }
  }
}

TEST(WeightSchedule, OutOfRangeParametersAreRefused) {
  PlannerConfig c = defaultConfig(Algorithm::kAmhaStar);
  c.w1 = kMaxWeight * 2;
  EXPECT_THROW(makePlanner(c), std::invalid_argument);
  c = defaultConfig(Algorithm::kAraStar);
  c.w1 = std::numeric_limits<double>::infinity();
  EXPECT_THROW(makePlanner(c), std::invalid_argument);
  c = defaultConfig(Algorithm::kAmhaStar);
  c.dw2 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(makePlanner(c), std::invalid_argument);
  for (const double bad : {1.0, -0.5, std::numeric_limits<double>::quiet_NaN()}) {
    c = defaultConfig(Algorithm::kAmhaStar);
    c.weight_schedule = WeightSchedule::kCertified;
    c.certified_ratio = bad;
    EXPECT_THROW(makePlanner(c), std::invalid_argument) << bad;
  }
  c = defaultConfig(Algorithm::kAmhaStar);
  c.weight_schedule = WeightSchedule::kCertified;
  c.certified_split = 1.5;
  EXPECT_THROW(makePlanner(c), std::invalid_argument);
  c.certified_split = 1.0;
  c.dw1 = 0.0;  // the certified schedule does not use the decrements
  EXPECT_NO_THROW(makePlanner(c));
  for (const double bad : {0.5, kMaxWeight * 2, std::numeric_limits<double>::quiet_NaN()}) {
    c = defaultConfig(Algorithm::kAmhaStar);
    c.stall_expansions = 10;
    c.stall_mid_w1 = bad;
    EXPECT_THROW(makePlanner(c), std::invalid_argument) << bad;
  }
  c.stall_mid_w1 = 0.0;  // no middle rung
  EXPECT_NO_THROW(makePlanner(c));
}

// An explicit graph that records, per ImprovePath iteration (told by the engine's observer), the
// most heuristics the search asked for at once.
struct CountingGraph : ExplicitGraph {
  int iteration = 0;
  std::map<int, std::size_t> most_heuristics;
  void heuristics(StateId s, HeuristicValue* out, std::size_t count) override {
    std::size_t& most = most_heuristics[iteration];
    most = std::max(most, count);
    ExplicitGraph::heuristics(s, out, count);
  }
};

// proof_anchor_only: the last iteration (w1 = w2 = 1) expands from OPEN_0 alone and computes h0
// alone, every solution stays within its bounds and the last is optimal. Off, Algorithm 1's
// last iteration expands from the inadmissible queues too (on some graphs), and computes them.
TEST(WeightSchedule, TheProofWithTheAnchorAloneIsAStarOnH0) {
  int proofs = 0, inadmissible_in_proof_off = 0;
  for (ExplicitGraph& base : graphs()) {
    const Cost optimal = testing::distancesToGoal(base)[base.s_start];
    if (optimal >= kInfiniteCost || base.n_heuristics < 2) continue;
    for (const bool anchor_only : {true, false}) {
      CountingGraph g;
      static_cast<ExplicitGraph&>(g) = base;
      detail::MhaEngineOptions o;
      o.w1 = 3.0;
      o.w2 = 2.0;
      o.weight_schedule = WeightSchedule::kCertified;
      o.certified_ratio = 0.0;  // straight to the proof
      o.publish_improvements = true;
      o.max_inadmissible = 100;
      o.check_invariants = true;
      o.proof_anchor_only = anchor_only;
      detail::MhaEngine engine(o);
      std::map<int, int> inadmissible_expansions;  // per iteration
      engine.setObserver([&](StateId, std::size_t queue, int it) {
        g.iteration = it;
        if (queue > 0) ++inadmissible_expansions[it];
      });
      const SearchResult r = engine.run(g, SearchLimits(), {});
      ASSERT_TRUE(r.hasSolution());
      EXPECT_EQ(r.status, SearchStatus::kProvenOptimal);
      EXPECT_EQ(r.best().cost, optimal);
      for (const Solution& s : r.solutions) EXPECT_EQ(testing::validateSolution(g, s, optimal), "");
      const Solution& last = r.solutions.back();
      if (last.w1 > 1.0 || last.w2 > 1.0) continue;  // certified optimal before the proof
      if (anchor_only) {
        ++proofs;
        EXPECT_EQ(inadmissible_expansions[last.iteration], 0);
        EXPECT_LE(g.most_heuristics[last.iteration], 1u) << "an inadmissible heuristic computed";
      } else {
        inadmissible_in_proof_off += inadmissible_expansions[last.iteration] > 0;
        if (g.most_heuristics.count(last.iteration)) {
          EXPECT_EQ(g.most_heuristics[last.iteration], g.n_heuristics);
        }
      }
    }
  }
  EXPECT_GT(proofs, 10);
  EXPECT_GT(inadmissible_in_proof_off, 0) << "Algorithm 1's proof never used its other queues";
}

}  // namespace
}  // namespace amha
