// ANA* on the lattice before its first solution (issue 22, item 8): G is infinite, every e(s)
// is infinite, and the paper's order is greedy best-first on h; its ImproveSolution re-inserts
// every state whose g drops (there is no CLOSED list), so states reached first by a costly route
// are expanded again and again. This counts expansions and distinct expanded states up to the
// first solution on the bundled Willow Garage map and SBPL's cubicle; docs/results/lattice.md (9)
// has the table.
#include <atomic>
#include <cstdio>
#include <unordered_set>

#include <gtest/gtest.h>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/map_loaders.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

// Forwards to a LatticeProblem and counts the expansions (successors() calls) and the distinct
// states expanded until `stop` is set (at the first solution).
class CountingProblem : public SearchProblem {
 public:
  CountingProblem(LatticeProblem& p, const std::atomic<bool>& stop) : p_(p), stop_(stop) {}
  StateId start() const override { return p_.start(); }
  StateId goal() const override { return p_.goal(); }
  void successors(StateId s, std::vector<Edge>& out) override {
    if (!stop_) {
      ++calls;
      distinct.insert(s);
    }
    p_.successors(s, out);
  }
  std::size_t numHeuristics() const override { return p_.numHeuristics(); }
  void heuristics(StateId s, HeuristicValue* h, std::size_t n) override { p_.heuristics(s, h, n); }
  std::size_t memoryBytes() const override { return p_.memoryBytes(); }
  void setInterruptCheck(std::function<bool()> check) override {
    p_.setInterruptCheck(std::move(check));
  }
  std::uint64_t calls = 0;
  std::unordered_set<StateId> distinct;

 private:
  LatticeProblem& p_;
  const std::atomic<bool>& stop_;
};

struct FirstSolution {
  std::uint64_t expansions = 0, distinct = 0, astar_expansions = 0;
};

FirstSolution anaUntilFirstSolution(const std::shared_ptr<GridMap>& map, const LatticeConfig& c,
                                    Pose2D s, Pose2D t) {
  LatticeGraph g(map, c);
  HeuristicGridBuilder b(g);
  LatticeState from, to;
  EXPECT_TRUE(g.poseToState(s, &from.x, &from.y, &from.heading));
  EXPECT_TRUE(g.poseToState(t, &to.x, &to.y, &to.heading));
  const auto grids = b.compute(to.x, to.y, to.heading, false);
  FirstSolution out;
  {
    LatticeProblem p(g, grids, from, to, 0);
    std::atomic<bool> stop{false};
    CountingProblem counting(p, stop);
    SearchLimits limits;
    limits.cancel = &stop;
    const SearchResult r = makePlanner(defaultConfig(Algorithm::kAnaStar))
                               ->search(counting, limits, [&](const Solution&) { stop = true; });
    EXPECT_FALSE(r.solutions.empty());
    if (r.solutions.empty()) return out;
    // The calls also re-read the solution's path (its states were all expanded before).
    out.expansions = r.solutions.front().expansions;
    EXPECT_GE(counting.calls, out.expansions);
    out.distinct = counting.distinct.size();
  }
  LatticeProblem p(g, grids, from, to, 0);
  const SearchResult r = makePlanner(defaultConfig(Algorithm::kAStar))->search(p, SearchLimits());
  EXPECT_EQ(r.status, SearchStatus::kProvenOptimal);
  out.astar_expansions = r.expansions;
  return out;
}

void report(const char* where, const FirstSolution& f) {
  std::printf(
      "[ ANA*     ] %s: first solution after %llu expansions of %llu distinct states (%.0f %% "
      "re-expansions); "
      "A* proves the optimum in %llu\n",
      where, static_cast<unsigned long long>(f.expansions),
      static_cast<unsigned long long>(f.distinct),
      100.0 * (f.expansions - f.distinct) / f.expansions,
      static_cast<unsigned long long>(f.astar_expansions));
  // The paper's rule re-expands; if this stops holding, docs/search.md ("ANA*") is out of date.
  EXPECT_GT(f.expansions, f.distinct) << where;
}

TEST(AnaStarOnTheLattice, ItsFirstSolutionReexpandsAsThePapersRuleDoes) {
  LatticeConfig c;
  c.robot.radius = 0.2;
  c.motion.turning_radius = 0.5;
  auto willow = std::make_shared<GridMap>(loadMapServerMap(
      std::string(AMHA_SOURCE_DIR) + "/maps/willow_garage/willow-2010-02-18-0.10.yaml"));
  report("willow 17,55,0 -> 26,6,1.57",
         anaUntilFirstSolution(willow, c, {17, 55, 0}, {26, 6, 1.57}));
  AMHA_REQUIRE_SHARED_DATA(data);
  SbplEnvironment env;
  auto cubicle = std::make_shared<GridMap>(
      loadMapFile(data + "/sbpl/cubicle-25mm-inflated-env.cfg", 0, 1, {}, &env));
  c.robot.radius = 0.15;
  useSbplCostModel(env, c);
  report("cubicle (its start and end)", anaUntilFirstSolution(cubicle, c, env.start, env.goal));
}

}  // namespace
}  // namespace lattice
}  // namespace amha
