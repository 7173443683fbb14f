// Fuzzes the search core: a graph, costs and arbitrary inadmissible heuristics (including
// infinite ones) from the input bytes; every algorithm's every solution must be a valid path
// within its certified bound of the Dijkstra optimum, solution costs must never increase, and
// unsolvable inputs must end cleanly. Both kinds of queue (buckets, heaps) are exercised.
// (It found ANA* reporting a costlier path after a cheaper one; fixed in SearchBase::report,
// see test/search/monotone_cost_test.cpp.) Then one run with weights from the input, hostile
// ones included: refused outside their range, and otherwise still solving the problem.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "../search/test_graphs.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace amha;
  fuzz::Bytes in{data, size};
  testing::ExplicitGraph g;
  const int n = 2 + in.u8() % 40;
  const int m = in.u8() * 2;
  g.adj.assign(n, {});
  for (int k = 0; k < m && in.n >= 3; ++k) {
    const StateId a = in.u8() % n, b = in.u8() % n;
    g.adj[a].push_back(Edge{b, 1 + static_cast<Cost>(in.u8())});
  }
  g.s_start = 0;
  g.s_goal = static_cast<StateId>(n - 1);
  g.n_heuristics = 1 + in.u8() % 6;
  const double scale = (in.u8() % 5) / 4.0;
  const auto d = testing::distancesToGoal(g);
  g.h.assign(n, std::vector<HeuristicValue>(g.n_heuristics, 0));
  for (int s = 0; s < n; ++s) {
    g.h[s][0] = d[s] >= kInfiniteCost ? kInfiniteHeuristic
                                      : static_cast<HeuristicValue>(std::floor(scale * d[s]));
    for (std::size_t i = 1; i < g.n_heuristics; ++i) {
      const std::uint8_t b = in.u8();
      g.h[s][i] = b == 255 ? kInfiniteHeuristic : static_cast<HeuristicValue>(b) * 7;
    }
  }
  g.h[g.s_goal][0] = 0;
  g.small_keys = (in.u8() & 1) != 0;  // the engine's queues as buckets or as heaps
  const Cost optimal = d[g.s_start];
  for (Algorithm a : {Algorithm::kAmhaStar, Algorithm::kMhaStar, Algorithm::kAraStar,
                      Algorithm::kAnaStar, Algorithm::kWeightedAStar, Algorithm::kAStar}) {
    PlannerConfig c = defaultConfig(a);
    c.check_invariants = true;
    const SearchResult r = makePlanner(c)->search(g, SearchLimits());
    if (optimal >= kInfiniteCost) {
      if (r.status != SearchStatus::kNoSolution || r.hasSolution()) std::abort();
      continue;
    }
    if (!r.hasSolution()) std::abort();
    Cost previous = kInfiniteCost;
    for (const Solution& s : r.solutions) {
      const std::string err = testing::validateSolution(g, s, optimal);
      if (!err.empty()) {
        std::fprintf(stderr, "%s: %s\n", algorithmName(a), err.c_str());
        std::abort();
      }
      if (s.cost > previous) {
        std::fprintf(stderr, "%s: solution cost %lld after %lld\n", algorithmName(a),
                     static_cast<long long>(s.cost), static_cast<long long>(previous));
        std::abort();
      }
      previous = s.cost;
    }
    if (r.status == SearchStatus::kProvenOptimal && r.best().cost != optimal) std::abort();
  }
  // Weights from the input, hostile ones included (issue 22, item 1: w1 = 1e15 gave a false "no
  // solution"): refused outside [1, kMaxWeight] (decrements [0, kMaxWeight]); accepted ones must
  // still find the solution, valid and within its bound.
  const Algorithm weighted[] = {Algorithm::kAmhaStar, Algorithm::kMhaStar, Algorithm::kAraStar,
                                Algorithm::kWeightedAStar};
  PlannerConfig c = defaultConfig(weighted[in.u8() % 4]);
  auto value = [&in] {
    const std::uint8_t sel = in.u8();
    return sel < 96 ? sel / 8.0 : sel < 192 ? std::ldexp(1.0, sel % 64) : in.f64();
  };
  c.w1 = 1.0 + value();
  c.w2 = 1.0 + value();
  c.dw1 = value();
  c.dw2 = value();
  auto weight = [](double w) { return w >= 1.0 && w <= kMaxWeight; };
  auto decrement = [](double d) { return d >= 0.0 && d <= kMaxWeight; };
  bool valid = weight(c.w1);
  if (c.algorithm == Algorithm::kAmhaStar || c.algorithm == Algorithm::kMhaStar)
    valid = valid && weight(c.w2);
  if (c.algorithm == Algorithm::kAmhaStar) {
    valid = valid && decrement(c.dw1) && decrement(c.dw2) && !(c.w1 > 1.0 && c.dw1 <= 0.0) &&
            !(c.w2 > 1.0 && c.dw2 <= 0.0);
  }
  if (c.algorithm == Algorithm::kAraStar)
    valid = valid && decrement(c.dw1) && !(c.w1 > 1.0 && c.dw1 <= 0.0);
  std::unique_ptr<Planner> planner;
  try {
    planner = makePlanner(c);
  } catch (const std::invalid_argument&) {
    if (valid) {
      std::fprintf(stderr, "%s: weights %g %g %g %g refused\n", algorithmName(c.algorithm), c.w1,
                   c.w2, c.dw1, c.dw2);
      std::abort();
    }
    return 0;
  }
  if (!valid) {
    std::fprintf(stderr, "%s: weights %g %g %g %g accepted\n", algorithmName(c.algorithm), c.w1,
                 c.w2, c.dw1, c.dw2);
    std::abort();
  }
  // Tiny decrements from huge weights mean millions of iterations (each reported): only the
  // verdict above is checked for those.
  const bool anytime = c.algorithm == Algorithm::kAmhaStar || c.algorithm == Algorithm::kAraStar;
  const double iterations =
      std::max(c.dw1 > 0.0 ? (c.w1 - 1.0) / c.dw1 : 0.0,
               c.algorithm == Algorithm::kAmhaStar && c.dw2 > 0.0 ? (c.w2 - 1.0) / c.dw2 : 0.0);
  if (anytime && iterations > 1000.0) return 0;
  // Bucket queues index keys g + w h directly: with weights of 10^4 and more they reserve
  // gigabytes (reported with issue 22's key arithmetic, for the engine's owner); heaps here.
  if (c.w1 * c.w2 > 1e3) g.small_keys = false;
  const SearchResult r = planner->search(g, SearchLimits());
  if ((optimal < kInfiniteCost) != r.hasSolution()) {
    std::fprintf(stderr, "%s with weights %g %g: status %s, optimum %lld\n",
                 algorithmName(c.algorithm), c.w1, c.w2, statusName(r.status),
                 static_cast<long long>(optimal));
    std::abort();
  }
  for (const Solution& s : r.solutions) {
    if (!testing::validateSolution(g, s, optimal).empty()) std::abort();
  }
  return 0;
}
