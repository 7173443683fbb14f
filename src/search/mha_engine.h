// A-MHA* (Algorithm 1 of the paper) and the algorithms that are special cases of it:
// MHA* (one ImprovePath), ARA* (no inadmissible heuristics, w2 = 1), weighted A* (ARA* with one
// iteration) and A* (weight 1). One engine, so comparisons between them are fair.
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <vector>

#include "amha_planner/search/detail/realloc_vector.h"
#include "dts_schedule.h"
#include "open_queue.h"
#include "search_base.h"
#include "state_records.h"

namespace amha {
namespace detail {

struct MhaEngineOptions {
  double w1 = 5.0, w2 = 5.0;    // initial weights
  double dw1 = 0.5, dw2 = 0.5;  // decrements per iteration
  WeightSchedule weight_schedule = WeightSchedule::kDecrement;
  double certified_ratio = 0.5, certified_split = 1.0, final_gap = 0.002;
  bool publish_improvements = false;   // PlannerConfig::publish_within_iterations
  std::uint64_t stall_expansions = 0;  // PlannerConfig::stall_expansions, stall_w1, stall_mid_*
  double stall_w1 = 5.0;
  double stall_mid_w1 = 0.0;
  std::uint64_t stall_mid_expansions = 0;
  bool proof_anchor_only = false;  // PlannerConfig::proof_anchor_only
  bool anytime = true;             // false: one ImprovePath (MHA*, weighted A*, A*)
  std::size_t max_inadmissible = 0;
  bool stop_when_certified_optimal = true;
  bool check_invariants = false;
  QueueSchedule schedule = QueueSchedule::kRoundRobin;
  std::uint64_t schedule_seed = 1;
};

/// Hook for tests: called for every expansion with the state, the queue (0 = anchor) and the
/// ImprovePath iteration.
using ExpansionObserver = std::function<void(StateId, std::size_t queue, int iteration)>;

class MhaEngine : public SearchBase {
 public:
  explicit MhaEngine(const MhaEngineOptions& options) : opt_(options) {}
  SearchResult run(SearchProblem& problem, const SearchLimits& limits,
                   const SolutionCallback& on_solution);
  void setObserver(ExpansionObserver obs) { observer_ = std::move(obs); }

 private:
  /// The anchor's queue and heuristic (h_0, admissible and consistent): OPEN_0 of Algorithm 1.
  static constexpr std::size_t kAnchor = 0;
  static constexpr std::uint32_t kGenerated = StateRecords::kGenerated,
                                 kClosedAnch = StateRecords::kClosedAnch,
                                 kClosedInad = StateRecords::kClosedInad,
                                 kIncons = StateRecords::kIncons, kStaleH = StateRecords::kStaleH;

  bool improvePath();  // false if a limit stopped it
  void expand(StateId s, std::size_t queue);
  void generate(StateId s);  // computes and caches the heuristics of a new state
  bool prepareNextIteration(double next_w1, double next_w2);  // false if a limit stopped it
  // The next iteration's weights (WeightSchedule), given the last solution's certified bound.
  void nextWeights(double certified, double* next_w1, double* next_w2);
  // Empties every queue and picks buckets or heaps for the current w1; a bucket per key only if
  // the keys are dense (denseKeys()).
  void resetQueues(bool dense_keys = false);
  // Whether members_ (the next iteration's OPEN_0), whose keys at the current w1 lie in
  // [lo, hi], hold at least kMinKeyDensity states per key value.
  bool denseKeys(double lo, double hi) const;
  static constexpr double kMinKeyDensity = 0.1;
  static constexpr std::size_t kMinDensityMembers = 256;
  // SearchProblem::upgradeHeuristics: marks every generated state's cached heuristics stale
  // (kStaleH), for generate() to recompute when the state is next generated or popped.
  void markHeuristicsStale();
  // Whether s, just popped, goes back into OPEN_0 with its renewed key instead of being
  // expanded (it was stale and its key rose).
  bool requeuedWithNewKey(StateId s);
  // Some state may hold stale heuristics (kStaleH). A stale state in OPEN_0 (a key computed
  // with them) arises only within an A* iteration: generate() renews a state before any push,
  // and prepareNextIteration renews every member.
  bool stale_states_ = false;
  void clearClosed();  // also empties INCONS
  // Collects OPEN_0 u INCONS (finite h0) into members_, in id order, and returns the minimum
  // of g + h0 over them: a lower bound on the optimal cost.
  Cost collectOpen0AndIncons();
  void checkInvariants() const;

  // Per-state data (g, parent, flags, h_i, b_i, queue membership) lives in records_
  // (state_records.h). The queues hold entries lazily (see lazy_queue.h): an entry describes a
  // member iff its state's bit is set and its key is the state's current key; anything else is
  // stale and skipped.
  std::size_t nh() const { return records_.heuristics(); }  // in use, anchor included
  // The queues the current iteration keeps, anchor included: nh(), or 1 at a proof with the
  // anchor alone (anchorOnlyAt).
  std::size_t queuesInUse() const { return anchorOnlyAt(w1_, w2_) ? 1 : nh(); }
  // Whether an iteration at these weights is a proof with the anchor alone: at w1 = w2 = 1 an
  // inadmissible queue may expand only states whose key is at most OPEN_0's minimum, so the
  // iteration is A* on h0 but for those, and its bound holds without them.
  bool anchorOnlyAt(double w1, double w2) const {
    return opt_.proof_anchor_only && w1 <= 1.0 && w2 <= 1.0;
  }
  Cost g(StateId s) const { return records_.g(s); }
  void setG(StateId s, Cost g) { records_.setG(s, g); }
  void setParent(StateId s, StateId p) { records_.setParent(s, p); }
  std::uint32_t& flags(StateId s) { return records_.flags(s); }
  std::uint32_t flags(StateId s) const { return records_.flags(s); }
  HeuristicValue h(StateId s, std::size_t i) const { return records_.h(s, i); }
  bool inOpen(StateId s, std::size_t i) const { return records_.inOpen(s, i); }
  void setInOpen(StateId s, std::size_t i) { records_.setInOpen(s, i); }
  void clearInOpen(StateId s, std::size_t i) { records_.clearInOpen(s, i); }
  void clearAllOpen(StateId s) { records_.clearAllOpen(s); }

  // Queue i's key at weight w: g + w h_i, or with inflation bases b_i
  // (SearchProblem::hasInflationBases) g + h_i + (w - 1) b_i. For the anchor that is
  // g + w h_w with h_w = (1 - 1/w) b_0 + h_0 / w, consistent and admissible, so every bound
  // holds with h_w as the anchor; the lower bounds still use h_0 itself.
  double keyAt(StateId s, std::size_t i, double w) const {
    const double g0 = static_cast<double>(g(s)), hi = static_cast<double>(h(s, i));
    if (!records_.hasBases()) return g0 + w * hi;
    return g0 + hi + (w - 1.0) * static_cast<double>(records_.base(s, i));
  }
  QueueEntry key(StateId s, std::size_t i) const {
    const HeuristicValue hv = h(s, i);
    return QueueEntry{keyAt(s, i, w1_), hv, s};
  }
  // Expand's admission test for OPEN_i (i >= 1), given key_i: finite h_i and key_i <= w2 * key_0.
  bool admits(const QueueEntry& key_i, double key0) const {
    return key_i.h != kInfiniteHeuristic && key_i.f <= w2_ * key0;
  }

  void prefetchTopRecord(std::size_t i) const {
    if (!open_[i].empty()) records_.prefetch(open_[i].topId());
  }
  /// An entry (key f, state id) of OPEN_i describes a member iff the state is marked as in
  /// OPEN_i and f is its current key.
  bool isMember(std::size_t i, double f, StateId id) const {
    return inOpen(id, i) && key(id, i).f == f;
  }
  /// Drops stale entries from the top of OPEN_i; false if no member is left.
  bool cleanTop(std::size_t i) {
    OpenQueue& q = open_[i];
    while (!q.empty()) {
      if (isMember(i, q.topKey(), q.topId())) return true;
      q.pop();
    }
    return false;
  }
  /// False if the queue would have to grow beyond the memory cap: the search then stops
  /// (kMemoryLimit) without reporting anything more, since OPEN_i is no longer complete.
  bool pushOpen(std::size_t i, const QueueEntry& e) {
    OpenQueue& q = open_[i];
    if (!q.tryPush(e)) {
      const std::size_t growth = q.growthBytes(e);
      if (growth > 0 && !roomFor(growth)) return !stopWith(SearchStatus::kMemoryLimit);
      q.push(e);
    }
    setInOpen(e.id, i);
    return true;
  }

  /// Makes id addressable; a new id (and any unused ids below it) gets a new record: all
  /// zero, which means g = infinity, no parent, no flags, in no queue. Records are written
  /// here, when their ids come into use, rather than when the array grows: growing then
  /// touches no memory, and a new page's first touch is this write.
  bool claim(StateId id) { return id < used_ || claimSlow(id); }
  bool claimSlow(StateId id);

  Cost gOf(StateId s) const override { return g(s); }
  StateId parentOf(StateId s) const override { return records_.parent(s); }
  std::size_t engineBytes() const override;
  void growArrays(std::size_t cap) override;
  void resetArrays(std::size_t used) override;

  MhaEngineOptions opt_;
  double w1_ = 1.0, w2_ = 1.0;
  bool small_keys_ = false;    // the problem allows bucket queues nested per key and h
  bool integer_keys_ = false;  // ... or one stack per key
  int iteration_ = 0;
  int stall_rung_ = 0;          // the stall rule: 0 before it, 1 at stall_mid_w1, 2 done
  std::size_t next_queue_ = 1;  // the inadmissible queue the next step tries (1..N)
  bool dts_ = false;            // opt_.schedule == kDts and there are inadmissible queues
  bool progress_ = false;       // DTS: the current expansion lowered its queue's smallest h
  DtsSchedule schedule_;
  StateId goal_ = kNoState;
  bool goal_improved_ = false;          // g(goal) fell since the last report
  bool incons_this_iteration_ = false;  // a state entered INCONS in this ImprovePath
  Cost known_lb_ = 0;                   // the best proven lower bound on the optimal cost so far
  double known_nominal_ = 0.0;          // the last finished iteration's bound w1 w2 (inf before)

  StateRecords records_;
  ReallocVector<StateId> members_;  // OPEN_0 u INCONS, from collectOpen0AndIncons()
  std::vector<OpenQueue> open_;     // open_[kAnchor] is the anchor queue
  ExpansionObserver observer_;
  bool notify_expanded_ = false;  // SearchProblem::wantsExpansions()
};

}  // namespace detail
}  // namespace amha
