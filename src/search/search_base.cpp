#include "search_base.h"

#include <algorithm>
#include <stdexcept>

namespace amha {
namespace detail {

void SearchBase::begin(SearchProblem& problem, const SearchLimits& limits,
                       const SolutionCallback* cb) {
  t0_ = Clock::now();
  stop_condition_ = StopCondition(limits.cancel, limits.time_limit_s, limits.clock);
  problem_ = &problem;
  limits_ = limits;
  callback_ = cb;
  result_ = SearchResult();
  stop_ = SearchStatus::kNoSolution;
  goal_unreachable_ = false;
  next_reach_check_ = 0;
  expansions_ = 0;
  generated_ = 0;
  resetArrays(std::min(used_, capacity_));
  used_ = 0;
}

bool SearchBase::grow(StateId id) {
  std::size_t cap = std::max<std::size_t>(capacity_ * 2, 1024);
  while (cap <= id) cap *= 2;
  // Refuse growth that would break the memory cap, before allocating; near the cap, grow once
  // to the largest capacity that still fits (never one state at a time: that is quadratic).
  const std::size_t per_state = capacity_ > 0 ? (engineBytes() + capacity_ - 1) / capacity_ : 64;
  const std::size_t cap_bytes = limits_.max_memory_bytes;
  if (hasMemoryCap()) {
    const std::size_t domain = problem_->memoryBytes();
    const std::size_t fit = domain < cap_bytes ? (cap_bytes - domain) / per_state : 0;
    if (fit <= id) {
      stopWith(SearchStatus::kMemoryLimit);
      return false;
    }
    cap = std::min(cap, fit);
  }
  growArrays(cap);
  capacity_ = cap;
  used_ = static_cast<std::size_t>(id) + 1;
  return true;
}

std::size_t SearchBase::memoryBytes() const { return problem_->memoryBytes() + engineBytes(); }

bool SearchBase::slowLimitCheck() {
  if (stop_condition_.cancelled()) return stopWith(SearchStatus::kCancelled);
  // A thread's CPU clock is a system call (~0.3 us, 3 % of the tiles' expansions if read
  // every 64): read it every 1024 expansions; the wall clock is cheap.
  const bool read_clock = limits_.clock == StopClock::kWall || (expansions_ & 1023u) == 0;
  if (read_clock && stop_condition_.reason() == StopReason::kDeadline)
    return stopWith(SearchStatus::kTimeLimit);
  if ((expansions_ & 4095u) == 0 && memoryBytes() > limits_.max_memory_bytes) {
    return stopWith(SearchStatus::kMemoryLimit);
  }
  return false;
}

bool SearchBase::reachabilityCheck() {
  if (expansions_ < next_reach_check_ || !result_.solutions.empty()) return false;
  const std::uint64_t budget = std::clamp(expansions_ / 16, kFirstReachBudget, kMaxReachBudget);
  next_reach_check_ = std::max(kReachCheckStart, 4 * expansions_);
  goal_unreachable_ = problem_->goalUnreachable(static_cast<std::size_t>(budget));
  return stopped();  // also if the domain's walk was cut short by the limit check (time, cancel)
}

bool SearchBase::report(double nominal_bound, Cost lower_bound, int iteration, double w1, double w2,
                        bool only_if_cheaper) {
  SearchProblem& p = *problem_;
  Solution sol;
  // Parent chains are acyclic (g strictly decreases towards the start since edge costs are
  // >= 1), but bound the walk anyway so a domain that breaks the contract cannot hang us.
  for (StateId s = p.goal(); s != kNoState; s = parentOf(s)) {
    sol.path.push_back(s);
    if (sol.path.size() > generated_ + 1) throw std::logic_error("cycle in parent pointers");
  }
  std::reverse(sol.path.begin(), sol.path.end());
  // The path's own cost can be below g(goal) when ancestors improved after their child was
  // reached; report the true sum of edges (the bound proofs hold for g(goal) >= that sum).
  // The same pass collects the edges' labels, for the domain to turn the path into its terms.
  Cost cost = 0;
  for (std::size_t k = 1; k < sol.path.size(); ++k) {
    p.successors(sol.path[k - 1], path_succ_);
    Cost best = kInfiniteCost;
    std::uint32_t label = kNoLabel;
    for (const Edge& e : path_succ_) {
      if (e.to == sol.path[k] && e.cost < best) {
        best = e.cost;
        label = e.label;
      }
    }
    if (best == kInfiniteCost) throw std::logic_error("parent chain uses a non-edge");
    cost += best;
    sol.edge_labels.push_back(label);
  }
  sol.cost = cost;
  if (only_if_cheaper && !result_.solutions.empty() && result_.solutions.back().cost <= cost)
    return false;
  // Keep the best path: a new parent chain is bounded by the new, lower g(goal), but can still
  // cost more than the previous chain's true sum (which may have been below its g(goal)).
  // Re-publishing the cheaper previous path keeps costs non-increasing; the new bounds hold for
  // it too, since they bound g(goal) and LB, and its cost is lower still.
  if (!result_.solutions.empty() && result_.solutions.back().cost < sol.cost) {
    sol.path = result_.solutions.back().path;
    sol.edge_labels = result_.solutions.back().edge_labels;
    sol.cost = result_.solutions.back().cost;
  }
  cost = sol.cost;
  sol.nominal_bound = nominal_bound;
  // certified = cost / LB, where LB <= optimal; clamp to [1, nominal]: the nominal bound is
  // proven by the algorithm's own theorem, so the smaller of the two is still a valid bound.
  double certified = nominal_bound;
  if (lower_bound >= cost) {
    certified = 1.0;
  } else if (lower_bound > 0 && lower_bound < kInfiniteCost) {
    certified =
        std::min(nominal_bound, static_cast<double>(cost) / static_cast<double>(lower_bound));
  }
  sol.certified_bound = std::max(1.0, certified);
  sol.elapsed_s = elapsed();
  sol.expansions = expansions_;
  sol.iteration = iteration;
  sol.w1 = w1;
  sol.w2 = w2;
  result_.solutions.push_back(std::move(sol));
  if (callback_ != nullptr && *callback_) (*callback_)(result_.solutions.back());
  return true;
}

void SearchBase::finish(SearchStatus status) {
  result_.status = status;
  result_.expansions = expansions_;
  result_.peak_states = generated_;
  result_.peak_memory_bytes = memoryBytes();
  result_.elapsed_s = elapsed();
  result_.goal_side_proof = status == SearchStatus::kNoSolution && goal_unreachable_;
}

}  // namespace detail
}  // namespace amha
