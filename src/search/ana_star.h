// ANA* (van den Berg, Shah, Huang and Goldberg, AAAI 2011): anytime search without parameters,
// expanding the state with the largest e(s) = (G - g(s)) / h(s), where G is the cost of the
// best solution so far. Keys are compared exactly as fractions (no truncation), and before the
// first solution (G infinite) the order is greedy on h, as the paper prescribes.
#pragma once

#include <vector>

#include "amha_planner/search/detail/indexed_heap.h"
#include "search_base.h"

namespace amha {
namespace detail {

struct AnaKey {
  Cost g;
  HeuristicValue h;
};

/// "a before b" in ANA*'s order, given the current incumbent cost *G.
struct AnaBefore {
  const Cost* G = nullptr;
  bool operator()(const AnaKey& a, const AnaKey& b) const;
};

class AnaStar : public SearchBase {
 public:
  SearchResult run(SearchProblem& problem, const SearchLimits& limits,
                   const SolutionCallback& on_solution);

 private:
  bool improveSolution();  // true: a better goal was reached; false: OPEN empty or stopped
  double eOf(const AnaKey& k) const;

  Cost gOf(StateId s) const override { return g_[s]; }
  StateId parentOf(StateId s) const override { return parent_[s]; }
  std::size_t engineBytes() const override;
  void growArrays(std::size_t cap) override;
  void resetArrays(std::size_t used) override;

  Cost G_ = kInfiniteCost;
  double E_ = 0.0;
  std::vector<Cost> g_;
  std::vector<StateId> parent_;
  std::vector<HeuristicValue> h0_;
  std::vector<std::uint8_t> generated_flag_;
  IndexedHeap<AnaKey, AnaBefore> open_{AnaBefore{&G_}};
};

}  // namespace detail
}  // namespace amha
