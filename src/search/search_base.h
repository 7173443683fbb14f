// State shared by the engines: growth of the per-state data with the dense ids, the limit checks
// (time, expansions, states, memory, cancel), and turning a parent chain into a reported Solution
// with its certified bound.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "amha_planner/search/planner.h"

namespace amha {
namespace detail {

class SearchBase {
 protected:
  using Clock = std::chrono::steady_clock;

  /// Starts a search: remembers problem and limits and resets per-state data of the last one.
  void begin(SearchProblem& problem, const SearchLimits& limits, const SolutionCallback* cb);

  /// Grows the per-state arrays so that `id` is addressable (geometric growth: no per-expansion
  /// allocation once warmed up). Returns false if the memory cap would be exceeded.
  bool ensure(StateId id) {
    if (id < capacity_) {
      if (id >= used_) used_ = id + 1;
      return true;
    }
    return grow(id);
  }

  /// Checks time, cancel, expansion, state and memory limits. Cheap checks every call,
  /// the clock and the domain's memory every 64 expansions.
  /// Also asks the domain, while no path is known, whether the goal is unreachable
  /// (reachabilityCheck): a proof of that stops the search with kNoSolution.
  bool limitHit() {
    if (stopped()) return true;
    if (expansions_ >= limits_.max_expansions) return stopWith(SearchStatus::kExpansionLimit);
    if (generated_ > limits_.max_states) return stopWith(SearchStatus::kMemoryLimit);
    if ((expansions_ & 63u) == 0) return slowLimitCheck() || reachabilityCheck();
    return false;
  }
  bool slowLimitCheck();
  /// SearchProblem::goalUnreachable at expansions 0, 32768, 4 x 32768, ..., with a budget of a
  /// sixteenth of the expansions so far (at least kFirstReachBudget, at most kMaxReachBudget
  /// states); never once a path has been reported. A state of the lattice's walk costs about as
  /// much as an expansion, so the asks add at most 1/16 x 4/3 (8 %) to a search without a path,
  /// and nothing but the first 64 states to the many first paths that come within 32768
  /// expansions (measured: docs/results/smac.md, "Queries without a path").
  bool reachabilityCheck();
  static constexpr std::uint64_t kFirstReachBudget = 64, kReachCheckStart = 32768;
  static constexpr std::uint64_t kMaxReachBudget = std::uint64_t{1} << 20;

  /// Lends the problem this search's limit check (SearchProblem::setInterruptCheck) while it
  /// lives: every run() holds one from begin() on, so that no exit leaves the problem holding
  /// a check into a search that has returned.
  class InterruptScope {
   public:
    explicit InterruptScope(SearchBase& search) : problem_(*search.problem_) {
      problem_.setInterruptCheck([&search] { return search.slowLimitCheck(); });
    }
    ~InterruptScope() { problem_.setInterruptCheck({}); }
    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;

   private:
    SearchProblem& problem_;
  };
  bool stopWith(SearchStatus s) {
    stop_ = s;
    return true;
  }
  bool stopped() const { return stop_ != SearchStatus::kNoSolution || goal_unreachable_; }
  /// Whether `extra` more bytes stay within the memory cap (queues check before they double;
  /// the cap's own check runs every 4096 expansions, too late for a doubling of a big queue).
  bool roomFor(std::size_t extra) const {
    return !hasMemoryCap() || memoryBytes() + extra <= limits_.max_memory_bytes;
  }
  bool hasMemoryCap() const { return limits_.max_memory_bytes != SearchLimits().max_memory_bytes; }

  double elapsed() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }

  /// Builds the path start..goal from parent pointers, recomputes its cost from the domain's
  /// edges, and reports it (with the given bounds) through the callback and into result_.
  /// `lower_bound` is a proven lower bound on the optimal cost (kInfiniteCost if none).
  /// only_if_cheaper: report nothing (and return false) unless the path costs less than the
  /// last reported one.
  bool report(double nominal_bound, Cost lower_bound, int iteration, double w1, double w2,
              bool only_if_cheaper = false);

  /// g-value and parent of a state (the engines store them in their own layouts).
  virtual Cost gOf(StateId s) const = 0;
  virtual StateId parentOf(StateId s) const = 0;
  /// Bytes of the subclass's own arrays, for the memory cap.
  virtual std::size_t engineBytes() const = 0;
  /// Called when the arrays grow to `new_capacity` ids; subclasses grow theirs.
  virtual void growArrays(std::size_t new_capacity) = 0;
  /// Resets the subclass's per-state data for ids [0, used) at the start of a search
  /// (g = infinity, no parent, nothing closed or queued).
  virtual void resetArrays(std::size_t used) = 0;

  std::size_t memoryBytes() const;
  void finish(SearchStatus status);

  SearchProblem* problem_ = nullptr;
  SearchLimits limits_;
  StopCondition stop_condition_;  // limits_' cancel flag and time budget, from begin()
  const SolutionCallback* callback_ = nullptr;
  Clock::time_point t0_;
  SearchResult result_;
  SearchStatus stop_ = SearchStatus::kNoSolution;  // kNoSolution means "not stopped"
  bool goal_unreachable_ = false;  // stopped: the domain proved that no path exists (stop_ stays)
  std::uint64_t next_reach_check_ = 0;  // reachabilityCheck's next expansion count

  std::uint64_t expansions_ = 0;
  std::size_t generated_ = 0;  // states that received search data (g < infinity)
  std::size_t capacity_ = 0;   // ids addressable in the arrays
  std::size_t used_ = 0;       // 1 + the largest id touched in this search

  std::vector<Edge> succ_;  // successor buffer, reused across expansions

 private:
  bool grow(StateId id);
  std::vector<Edge> path_succ_;  // separate buffer for path cost recomputation
};

}  // namespace detail
}  // namespace amha
