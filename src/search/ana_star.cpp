#include "ana_star.h"

#include <algorithm>
#include <limits>

namespace amha {
namespace detail {

bool AnaBefore::operator()(const AnaKey& a, const AnaKey& b) const {
  if (*G >= kInfiniteCost) {
    // No solution yet: every e(s) is infinite; expand greedily on h (then on g).
    return a.h < b.h || (a.h == b.h && a.g < b.g);
  }
  // e = (G - g) / h, with h = 0 meaning e = infinity. Larger e comes first.
  if (a.h == 0 || b.h == 0) {
    if (a.h != 0) return false;
    if (b.h != 0) return true;
    return a.g < b.g;
  }
  // (G - ga) / ha > (G - gb) / hb  <=>  (G - ga) * hb > (G - gb) * ha, exactly in 128 bits.
  const __int128 lhs = static_cast<__int128>(*G - a.g) * b.h;
  const __int128 rhs = static_cast<__int128>(*G - b.g) * a.h;
  if (lhs != rhs) return lhs > rhs;
  return a.h < b.h;
}

double AnaStar::eOf(const AnaKey& k) const {
  if (G_ >= kInfiniteCost || k.h == 0) return std::numeric_limits<double>::infinity();
  return static_cast<double>(G_ - k.g) / static_cast<double>(k.h);
}

std::size_t AnaStar::engineBytes() const {
  return g_.capacity() * sizeof(Cost) + parent_.capacity() * sizeof(StateId) +
         h0_.capacity() * sizeof(HeuristicValue) + generated_flag_.capacity() + open_.memoryBytes();
}

void AnaStar::growArrays(std::size_t cap) {
  g_.resize(cap, kInfiniteCost);
  parent_.resize(cap, kNoState);
  h0_.resize(cap, 0);
  generated_flag_.resize(cap, 0);
  open_.reserveIds(cap);
}

void AnaStar::resetArrays(std::size_t used) {
  std::fill(g_.begin(), g_.begin() + std::min(used, g_.size()), kInfiniteCost);
  std::fill(parent_.begin(), parent_.begin() + std::min(used, parent_.size()), kNoState);
  std::fill(generated_flag_.begin(),
            generated_flag_.begin() + std::min(used, generated_flag_.size()), 0);
  open_.clear();
}

SearchResult AnaStar::run(SearchProblem& problem, const SearchLimits& limits,
                          const SolutionCallback& on_solution) {
  begin(problem, limits, &on_solution);
  const InterruptScope interrupt_scope(*this);
  G_ = kInfiniteCost;
  E_ = std::numeric_limits<double>::infinity();
  auto gen = [&](StateId s) {
    if (!ensure(s)) return false;
    if (!generated_flag_[s]) {
      problem.heuristics(s, &h0_[s], 1);
      generated_flag_[s] = 1;
      ++generated_;
    }
    return true;
  };
  const StateId start = problem.start();
  if (!gen(start) || !gen(problem.goal())) {
    finish(SearchStatus::kMemoryLimit);
    return std::move(result_);
  }
  g_[start] = 0;
  if (h0_[start] != kInfiniteHeuristic) open_.push(start, AnaKey{0, h0_[start]});

  int iteration = 0;
  SearchStatus status = SearchStatus::kNoSolution;
  for (;;) {
    const bool improved = improveSolution();
    if (stopped()) {
      status = stop_;
      break;
    }
    if (!improved) {  // OPEN empty: G is optimal (or there is no solution)
      if (G_ < kInfiniteCost) {
        // Publish the proof: the incumbent again, now with bound 1.
        if (result_.solutions.back().certified_bound > 1.0) report(1.0, G_, iteration, 1.0, 1.0);
        status = SearchStatus::kProvenOptimal;
      }
      break;
    }
    // Prune the states that cannot lead to a better solution and re-order OPEN for the new G:
    // one sequential pass over the entries, then a heapify, which checks the clock (OPEN can
    // hold tens of millions). An entry's key holds its state's current g: every state whose g
    // falls while g + h < G is pushed again, and G only falls.
    // Lower bound for the certificate: every state that could still improve on G is in OPEN
    // (ANA* re-opens any state whose g drops while g + h < G), so min over OPEN of g + h is at
    // most the optimal cost unless G is already optimal.
    Cost lb = kInfiniteCost;
    open_.removeIf([&](const auto& e) {
      const Cost f = e.key.g + static_cast<Cost>(e.key.h);
      if (f >= G_) return true;
      lb = std::min(lb, f);
      return false;
    });
    const bool ordered = open_.rebuild([this](std::size_t) { return slowLimitCheck(); });
    report(E_, lb, iteration++, 1.0, 1.0);  // lb is complete even if the heapify stopped
    if (!ordered) {
      status = stop_;
      break;
    }
    if (open_.empty()) {
      status = SearchStatus::kProvenOptimal;
      break;
    }
    if (slowLimitCheck()) {
      status = stop_;
      break;
    }
  }
  finish(status);
  return std::move(result_);
}

bool AnaStar::improveSolution() {
  const StateId goal = problem_->goal();
  while (!open_.empty()) {
    if (limitHit()) return false;
    const auto top = open_.top();
    open_.remove(top.id);
    const StateId s = top.id;
    E_ = std::min(E_, eOf(top.key));
    if (s == goal) {
      G_ = g_[s];
      return true;
    }
    ++expansions_;
    problem_->successors(s, succ_);
    const Cost gs = g_[s];
    for (const Edge& e : succ_) {
      const StateId t = e.to;
      if (t >= capacity_ || !generated_flag_[t]) {
        if (!ensure(t)) return false;
        problem_->heuristics(t, &h0_[t], 1);
        generated_flag_[t] = 1;
        ++generated_;
      }
      const Cost ng = gs + e.cost;
      if (ng >= g_[t]) continue;
      g_[t] = ng;
      parent_[t] = s;
      const HeuristicValue ht = h0_[t];
      if (ht != kInfiniteHeuristic && ng + static_cast<Cost>(ht) < G_) {
        open_.push(t, AnaKey{ng, ht});
      }
    }
  }
  return false;
}

}  // namespace detail
}  // namespace amha
