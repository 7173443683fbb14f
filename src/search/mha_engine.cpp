// A-MHA*, Algorithm 1 of the paper (../shared/docs/a-mha-star-paper.tex; lines numbered as
// there, without the end-procedure lines), and where each part is here:
//
//   lines  1-2   key(s, i) = g(s) + w1 h_i(s)         key(), keyAt() (+ (w - 1) b_i with bases)
//   lines  3-15  Expand(s, i)                          expand()
//          4       remove s from every OPEN_i          clearAllOpen()
//          8-9     closed by the anchor: to INCONS     expand(): the kIncons flag
//          11      insert/update s' in OPEN_0          pushOpen(kAnchor, ...)
//          12-15   not in CLOSED_inad: OPEN_i if       admits(), pushOpen(i, ...)
//                  key_i <= w2 key_0
//   lines 16-24  ImprovePath()                         improvePath()
//          17      while g(goal) > w2 OPEN_0.Min()     improvePath(): the goal test
//          18-19   the inadmissible queue's turn       next_queue_ (round robin, or DTS)
//          21, 24  CLOSED_inad, CLOSED_anch            the kClosedInad, kClosedAnch flags
//   lines 25-40  Main()                                run()
//          26-29   weights, g(start), OPEN_i           run()
//          31-32   empty CLOSED and INCONS             clearClosed()
//          34      publish the w1 w2 solution          report(), its certified bound from
//                                                      collectOpen0AndIncons()
//          35-36   stop at w1 = w2 = 1                 run()
//          37      lower the weights                   nextWeights() (the paper's decrements,
//                                                      or the certified schedule)
//          38-40   INCONS into OPEN_0, OPEN_0 into     prepareNextIteration()
//                  each OPEN_i, new keys
//
// Beyond the paper (each off with the paper's preset): publishing cheaper paths and tighter
// certified bounds within an iteration (improvePath, publish_improvements), going on with a
// larger w1 when the first iteration stalls (stall_expansions), skipping iterations that
// would stop at once (nextWeights), and proving with the anchor alone (proof_anchor_only).
#include "mha_engine.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace amha {
namespace detail {

std::size_t MhaEngine::engineBytes() const {
  std::size_t bytes = records_.bytes() + members_.capacity() * sizeof(StateId);
  for (const auto& q : open_) bytes += q.memoryBytes();
  return bytes;
}

void MhaEngine::growArrays(std::size_t cap) {
  // The new records are written by claim() when their ids come into use.
  records_.reserve(cap);
}

bool MhaEngine::claimSlow(StateId id) {
  const std::size_t from = used_;
  if (id >= capacity_ && !ensure(id)) return false;
  used_ = static_cast<std::size_t>(id) + 1;
  records_.zero(from, used_);
  return true;
}

void MhaEngine::resetArrays(std::size_t used) {
  for (auto& q : open_) q.clear();
  records_.zero(0, used);
}

SearchResult MhaEngine::run(SearchProblem& problem, const SearchLimits& limits,
                            const SolutionCallback& on_solution) {
  const std::size_t in_use = 1 + std::min(opt_.max_inadmissible, problem.numHeuristics() - 1);
  const bool bases = problem.hasInflationBases();
  if (records_.configure(in_use, bases) || open_.size() != in_use) {
    // A different heuristic count changes the record layout: start from empty records.
    open_.assign(in_use, OpenQueue());
    capacity_ = 0;
    used_ = 0;
  }
  begin(problem, limits, &on_solution);
  const InterruptScope interrupt_scope(*this);
  w1_ = opt_.w1;
  w2_ = opt_.w2;
  notify_expanded_ = problem.wantsExpansions();
  small_keys_ = problem.smallIntegerKeys();
  integer_keys_ = problem.integerKeys();
  resetQueues();
  iteration_ = 0;
  stall_rung_ = 0;
  stale_states_ = false;
  dts_ = opt_.schedule == QueueSchedule::kDts && nh() > 1;
  next_queue_ = 1;
  if (dts_) {
    schedule_.reset(nh() - 1, opt_.schedule_seed);
    next_queue_ = schedule_.pick();
  }

  const StateId start = problem.start();
  const StateId goal = problem.goal();
  if (!claim(start) || !claim(goal)) {
    finish(SearchStatus::kMemoryLimit);
    return std::move(result_);
  }
  generate(start);
  generate(goal);
  setG(start, 0);
  goal_ = goal;
  goal_improved_ = false;
  incons_this_iteration_ = false;
  known_nominal_ = std::numeric_limits<double>::infinity();
  known_lb_ = h(start, kAnchor) == kInfiniteHeuristic
                  ? 0
                  : static_cast<Cost>(h(start, kAnchor));  // h0 is admissible
  if (h(start, kAnchor) != kInfiniteHeuristic) {
    const QueueEntry k0 = key(start, kAnchor);
    pushOpen(kAnchor, k0);
    for (std::size_t i = 1; i < queuesInUse(); ++i) {
      const QueueEntry ki = key(start, i);
      if (admits(ki, k0.f) && pushOpen(i, ki) && dts_) schedule_.noteQueued(i, ki.h);
    }
  }

  SearchStatus status = SearchStatus::kNoSolution;
  for (;;) {
    if (opt_.check_invariants) checkInvariants();
    if (!improvePath()) {
      status = stop_;
      break;
    }
    if (g(goal) >= kInfiniteCost) {  // OPEN_0 ran empty: nothing reaches the goal
      status = SearchStatus::kNoSolution;
      break;
    }
    const double nominal = w1_ * w2_;
    const Cost lb = collectOpen0AndIncons();
    report(nominal, lb, iteration_, w1_, w2_);
    goal_improved_ = false;
    known_nominal_ = nominal;
    known_lb_ = std::max(known_lb_, lb);
    const bool certified_optimal = result_.solutions.back().certified_bound <= 1.0;
    if ((w1_ <= 1.0 && w2_ <= 1.0) || (certified_optimal && opt_.stop_when_certified_optimal)) {
      status = SearchStatus::kProvenOptimal;
      break;
    }
    if (!opt_.anytime) {
      status = certified_optimal ? SearchStatus::kProvenOptimal : SearchStatus::kBoundReached;
      break;
    }
    ++iteration_;
    double next_w1 = 1.0, next_w2 = 1.0;
    nextWeights(result_.solutions.back().certified_bound, &next_w1, &next_w2);
    if (!prepareNextIteration(next_w1, next_w2) || slowLimitCheck()) {
      status = stop_;
      break;
    }
  }
  finish(status);
  return std::move(result_);
}

void MhaEngine::nextWeights(double certified, double* next_w1, double* next_w2) {
  if (opt_.weight_schedule == WeightSchedule::kCertified) {
    // Below the bound already earned, so that the iteration must expand (and may improve the
    // path): its stop test g(goal) <= w2 min key_0 fails while w1 w2 < cost / LB (key_0 <= w1 (g +
    // h0)).
    const double c = std::min(certified, w1_ * w2_);
    double bound = 1.0 + opt_.certified_ratio * (c - 1.0);
    if (bound - 1.0 <= opt_.final_gap) bound = 1.0;
    *next_w1 = std::clamp(std::pow(bound, opt_.certified_split), 1.0, w1_);
    *next_w2 = std::clamp(bound / *next_w1, 1.0, w2_);
    return;
  }
  // The paper's decrements. An iteration whose stop test already holds after the re-keying
  // (g(goal) <= w2 min over OPEN_0 u INCONS of the anchor's key) expands nothing and reports the
  // same path again: it is skipped (the search after it is the same), so that a large w1 does not
  // report millions of copies. The test's right side falls with every decrement, so the
  // iterations that stop at once come first: a binary search finds the first that does not.
  // members_ is OPEN_0 u INCONS (collectOpen0AndIncons).
  const Cost goal_g = g(problem_->goal());
  auto at = [&](std::uint64_t k, double* w1, double* w2) {
    *w1 = std::max(w1_ - static_cast<double>(k) * opt_.dw1, 1.0);
    *w2 = std::max(w2_ - static_cast<double>(k) * opt_.dw2, 1.0);
  };
  auto stopsAtOnce = [&](std::uint64_t k) {
    double w1, w2;
    at(k, &w1, &w2);
    if (w1 <= 1.0 && w2 <= 1.0) return false;  // the last iteration always runs
    double min_key = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < members_.size(); ++i) {
      const StateId s = members_[i];
      min_key = std::min(min_key, keyAt(s, kAnchor, w1));
    }
    return goal_g < kInfiniteCost && static_cast<double>(goal_g) <= w2 * min_key;
  };
  // The number of decrements to reach (1, 1), and the first k >= 1 whose iteration runs.
  std::uint64_t last = 1;
  if (opt_.dw1 > 0.0)
    last = std::max<std::uint64_t>(last,
                                   static_cast<std::uint64_t>(std::ceil((w1_ - 1.0) / opt_.dw1)));
  if (opt_.dw2 > 0.0)
    last = std::max<std::uint64_t>(last,
                                   static_cast<std::uint64_t>(std::ceil((w2_ - 1.0) / opt_.dw2)));
  std::uint64_t lo = 1, hi = last;  // stopsAtOnce is true below the answer, false from it on
  while (lo < hi) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (stopsAtOnce(mid)) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  at(lo, next_w1, next_w2);
}

void MhaEngine::generate(StateId s) {
  const std::uint32_t f = flags(s);
  if ((f & kGenerated) && !(f & kStaleH)) return;
  // Straight into the record: a copy of a few words through a buffer became a libc memmove
  // call (2 % of the time on Korf's 15-puzzles).
  // The heuristics the queues in use need (h0 alone at a proof with the anchor alone).
  problem_->heuristics(s, records_.heuristicsOut(s), queuesInUse());
  if (records_.hasBases()) problem_->bases(s, records_.basesOut(s), queuesInUse());
  if (f & kGenerated) {  // a stale state's values renewed (SearchProblem::upgradeHeuristics)
    flags(s) &= ~static_cast<std::uint32_t>(kStaleH);
    return;
  }
  flags(s) |= kGenerated;
  ++generated_;
}

bool MhaEngine::improvePath() {
  const StateId goal = problem_->goal();
  const std::size_t n_inad = queuesInUse() - 1;
  for (;;) {
    if (stopped()) return false;  // e.g. a queue could not grow: OPEN is incomplete
    if (!cleanTop(kAnchor)) return true;
    const double min0 = open_[kAnchor].topKey();
    // Lines 17/19 of Algorithm 1: stop once g(goal) <= w2 * OPEN_0.Min(). An unreached goal's
    // g is a sentinel, not a cost: with a huge key it would pass the test (issue 22, item 1).
    const Cost goal_g = g(goal);
    if (goal_g < kInfiniteCost && static_cast<double>(goal_g) <= w2_ * min0) return true;
    // A cheaper path found while the iteration goes on: published now (publish_improvements)
    // with the bounds proven so far, the last finished iteration's and cost / the best lower
    // bound; an iteration that ends here reports it itself (the test above).
    if (goal_improved_) {
      goal_improved_ = false;
      if (opt_.publish_improvements) report(known_nominal_, known_lb_, iteration_, w1_, w2_, true);
    }
    // With w1 = 1 and no state in INCONS yet, OPEN_0's minimum g + h0 is itself a lower bound
    // on the optimal cost (collectOpen0AndIncons), at every step: the certified bound of the
    // path in hand tightens as the anchor goes. Publish it when it has halved its gap since the
    // last report (publish_improvements), so that a long proof is not silent.
    if (opt_.publish_improvements && w1_ <= 1.0 && !incons_this_iteration_ &&
        !result_.solutions.empty() && goal_g < kInfiniteCost) {
      const Solution& last = result_.solutions.back();
      const Cost lb = static_cast<Cost>(min0);
      if (lb > known_lb_) {
        known_lb_ = lb;
        const double c = static_cast<double>(last.cost) / static_cast<double>(lb);
        if (c - 1.0 <= 0.5 * (last.certified_bound - 1.0) && c < last.certified_bound - 1e-3) {
          report(known_nominal_, known_lb_, iteration_, w1_, w2_);
        }
      }
    }
    if (limitHit()) return false;
    if (n_inad == 0 && w1_ <= 1.0 && (expansions_ & 1023) == 0 && problem_->upgradeHeuristics())
      markHeuristicsStale();
    // No path yet after the stall budget: on to an iteration with a larger w1, from OPEN_0 u
    // INCONS as line 38 would: stall_mid_w1 for stall_mid_expansions more (if set), then
    // stall_w1, each once.
    if (opt_.anytime && opt_.stall_expansions > 0 && goal_g >= kInfiniteCost) {
      double next = 0.0;
      if (stall_rung_ == 0 && iteration_ == 0 && expansions_ >= opt_.stall_expansions) {
        const bool mid = opt_.stall_mid_expansions > 0 && opt_.stall_mid_w1 > w1_ &&
                         opt_.stall_mid_w1 < opt_.stall_w1;
        next = mid ? opt_.stall_mid_w1 : opt_.stall_w1;
        stall_rung_ = mid ? 1 : 2;
      } else if (stall_rung_ == 1 &&
                 expansions_ >= opt_.stall_expansions + opt_.stall_mid_expansions) {
        next = opt_.stall_w1;
        stall_rung_ = 2;
      }
      if (next > w1_) {
        collectOpen0AndIncons();
        ++iteration_;
        if (!prepareNextIteration(next, w2_)) return false;
        continue;
      }
    }
    std::size_t q = kAnchor;
    if (n_inad > 0) {
      const std::size_t i = next_queue_;
      if (cleanTop(i) && open_[i].topKey() <= w2_ * min0) q = i;
    }
    const StateId s = open_[q].topId();
    open_[q].pop();
    if (stale_states_ && requeuedWithNewKey(s)) continue;
    // Choose the next step's inadmissible queue now: the next round tests the tops of OPEN_0
    // and of that queue against their records, so start loading those while s is expanded (if
    // expand() changes a top, the hint is merely wasted). DTS thus draws before s's reward is
    // known: its evidence is one expansion old.
    if (n_inad > 0) next_queue_ = dts_ ? schedule_.pick() : next_queue_ % n_inad + 1;
    prefetchTopRecord(kAnchor);
    if (n_inad > 0) prefetchTopRecord(next_queue_);
    progress_ = false;
    expand(s, q);
    if (dts_ && q > 0) schedule_.reward(q, progress_);
    flags(s) |= (q == kAnchor) ? kClosedAnch : kClosedInad;
  }
}

void MhaEngine::expand(StateId s, std::size_t queue) {
  clearAllOpen(s);  // out of every queue: its entries elsewhere are now stale
  ++expansions_;
  if (observer_) observer_(s, queue, iteration_);
  if (notify_expanded_) problem_->expanded(s, g(s), key(s, kAnchor).f);
  problem_->successors(s, succ_);
  const Cost gs = g(s);
  // Make room for new ids first (may move the records), then prefetch every successor's
  // record so that their cache misses overlap instead of queueing up one by one.
  for (const Edge& e : succ_) {
    if (!claim(e.to)) return;  // memory cap: improvePath stops
  }
  for (const Edge& e : succ_) records_.prefetch(e.to, true);
  const std::size_t queues = queuesInUse();
  for (const Edge& e : succ_) {
    const StateId t = e.to;
    generate(t);
    const Cost ng = gs + e.cost;
    if (ng >= g(t)) continue;
    setG(t, ng);
    setParent(t, s);
    goal_improved_ = goal_improved_ || t == goal_;
    const std::uint32_t f = flags(t);
    if (f & kClosedAnch) {
      flags(t) |= kIncons;  // INCONS is the set of states with this flag
      incons_this_iteration_ = true;
      continue;
    }
    if (h(t, kAnchor) == kInfiniteHeuristic) continue;  // provably cannot reach the goal
    // The new g changes every key, so t's old entries are stale; push fresh ones.
    const QueueEntry k0 = key(t, kAnchor);
    if (!pushOpen(kAnchor, k0)) return;
    if (f & kClosedInad) continue;
    for (std::size_t i = 1; i < queues; ++i) {
      const QueueEntry ki = key(t, i);
      if (admits(ki, k0.f)) {
        if (!pushOpen(i, ki)) return;
        if (dts_ && schedule_.noteQueued(i, ki.h) && i == queue) progress_ = true;
      } else {
        // A lower g can make the test fail; keep OPEN_i exactly the states that pass it.
        clearInOpen(t, i);
      }
    }
  }
}

bool MhaEngine::prepareNextIteration(double next_w1, double next_w2) {
  // Every loop here can run over tens of millions of states: check the clock and the cancel
  // flag every 2^16 of them, and give up (the search stops) when one is hit.
  auto interrupted = [this](std::size_t k) { return (k & 0xFFFFu) == 0 && slowLimitCheck(); };
  // Lines 38-40: OPEN_0 := OPEN_0 u INCONS, re-keyed with the new w1. members_ holds that
  // union already: collectOpen0AndIncons() gathered it for the lower bound of the solution just
  // reported, and nothing has changed since. clearClosed() empties INCONS at the end.
  w1_ = next_w1;
  w2_ = next_w2;
  // Better heuristics now: the iteration starts from OPEN_0 u INCONS as ever (its bound needs
  // only h_0 consistent from here on), keyed with them; a state they prove cut off leaves.
  if (problem_->upgradeHeuristics()) markHeuristicsStale();
  if (stale_states_) {  // renewed here, the members are never stale when popped
    std::size_t kept = 0;
    for (std::size_t k = 0; k < members_.size(); ++k) {
      const StateId s = members_[k];
      generate(s);  // renews stale values (a no-op for the others)
      if (h(s, kAnchor) != kInfiniteHeuristic) {
        members_[kept++] = s;
      } else {
        clearAllOpen(s);
      }
    }
    members_.resize(kept);
  }
  // The pass that takes the members out of their queues also measures their keys' span at the
  // new w1, from which the queues' kind follows (denseKeys).
  const bool measure = integer_keys_ && !small_keys_;  // only the per-key buckets need it
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (std::size_t k = 0; k < members_.size(); ++k) {
    clearAllOpen(members_[k]);
    if (!measure) continue;
    const double f = keyAt(members_[k], kAnchor, w1_);
    lo = std::min(lo, f);
    hi = std::max(hi, f);
  }
  resetQueues(denseKeys(lo, hi));
  for (std::size_t k = 0; k < members_.size(); ++k) {
    if (interrupted(k)) return false;
    const StateId s = members_[k];
    open_[kAnchor].appendUnordered(key(s, kAnchor));
    setInOpen(s, kAnchor);
  }
  open_[kAnchor].restoreOrder();
  if (dts_) schedule_.resetProgress();
  // "Copy all states from OPEN_0 to OPEN_i": we re-apply Expand's admission test
  // (key_i <= w2 * key_0, h_i finite). The paper leaves this open. The bound proof only needs
  // line 19's test, so either choice is correct; filtering keeps OPEN_i identical to what
  // Expand would have built with the new weights (one invariant, checked by the tests), and
  // keeps states an inadmissible heuristic rules out (h_i = infinity) out of its queue.
  for (std::size_t i = 1; i < queuesInUse(); ++i) {
    for (std::size_t k = 0; k < members_.size(); ++k) {  // exactly OPEN_0's entries
      if (interrupted(k)) return false;
      const StateId s = members_[k];
      const QueueEntry ki = key(s, i);
      if (admits(ki, key(s, kAnchor).f)) {
        open_[i].appendUnordered(ki);
        setInOpen(s, i);
        if (dts_) schedule_.noteQueued(i, ki.h);
      }
    }
    open_[i].restoreOrder();
  }
  clearClosed();
  incons_this_iteration_ = false;
  return true;
}

void MhaEngine::markHeuristicsStale() {
  stale_states_ = true;
  for (std::size_t i = 0; i < used_; ++i) {
    std::uint32_t& f = flags(static_cast<StateId>(i));
    if (f & kGenerated) f |= kStaleH;
  }
}

bool MhaEngine::requeuedWithNewKey(StateId s) {
  // In an A* iteration after an upgrade (markHeuristicsStale), OPEN_0's keys were computed with
  // the old h_0, each a lower bound of the state's new key (no value fell). The top is renewed
  // when popped; if its key rose it goes back, else it is the minimum and is expanded. So the
  // state expanded has the smallest new key: A* on the new h_0, whose every state expanded so
  // far had its optimal g (both consistent), stays exact (SearchProblem::upgradeHeuristics).
  if (!(flags(s) & kStaleH)) return false;
  const double old_key = key(s, kAnchor).f;
  generate(s);
  if (h(s, kAnchor) == kInfiniteHeuristic) {  // now proven cut off from the goal
    clearAllOpen(s);
    return true;
  }
  const QueueEntry k0 = key(s, kAnchor);
  if (k0.f <= old_key) return false;
  pushOpen(kAnchor, k0);
  return true;
}

namespace {
// The largest w1 * scale for which a small-key domain's queues are nested buckets (the tiles'
// weights, 5 down to 1 in halves, are at most 10).
constexpr double kMaxBucketWeight = 64.0;
}  // namespace

void MhaEngine::resetQueues(bool dense_keys) {
  const double scale = integer_keys_ ? OpenQueue::bucketScaleFor(w1_) : 0.0;
  OpenQueue::Kind kind = OpenQueue::Kind::kHeap;
  // The nested buckets are indexed by g * scale + (w1 * scale) * h: a hostile w1 that is a
  // multiple of 1/64 (999.984375) makes that hundreds of millions of buckets even for small h,
  // gigabytes of bucket headers (the search fuzzer's find). Such iterations keep the heap.
  if (scale > 0 && small_keys_ && w1_ * scale <= kMaxBucketWeight) kind = OpenQueue::Kind::kBuckets;
  if (scale > 0 && !small_keys_ && dense_keys) kind = OpenQueue::Kind::kKeyBuckets;
  for (auto& q : open_) q.reset(kind, scale);
}

bool MhaEngine::denseKeys(double lo, double hi) const {
  // A key's stack takes a 64-byte block and the heads span the keys' range: with sparse keys
  // (SBPL's cubicle, where a turn costs as much as 10 m of driving: 0.003-0.03 states per key)
  // that is 3-4 times the heap's 16 bytes an entry, and no faster. The lattice maps of the
  // Smac benchmark have 0.2-3 at the proof's start. The first iteration, from one state, has
  // nothing to measure: it keeps the heap.
  if (!integer_keys_ || small_keys_ || members_.size() < kMinDensityMembers) return false;
  const double span = std::max(1.0, (hi - lo) * OpenQueue::bucketScaleFor(w1_) + 1.0);
  return static_cast<double>(members_.size()) >= kMinKeyDensity * span;
}

void MhaEngine::clearClosed() {
  const std::uint32_t keep = ~static_cast<std::uint32_t>(kClosedAnch | kClosedInad | kIncons);
  for (std::size_t s = 0; s < used_; ++s) flags(static_cast<StateId>(s)) &= keep;
}

Cost MhaEngine::collectOpen0AndIncons() {
  // Every state whose g changed since its last expansion is in OPEN_0 or INCONS (Expand puts
  // it in one of them; prepareNextIteration moves INCONS into OPEN_0). On an optimal path, the
  // first state whose g is above optimal has a predecessor p with g(p) = g*(p) that is not
  // expanded with that g, so p is in OPEN_0 or INCONS and g(p) + h0(p) <= g*(goal) by
  // admissibility. Hence this minimum is a lower bound on the optimal cost (or the solution is
  // already optimal). States with h0 = infinity cannot lie on any path to the goal.
  // A state is in OPEN_0 iff its membership bit is set (and then its h0 is finite), and INCONS
  // states are closed, in no queue. So one pass over the records in id order finds both sets;
  // it streams through memory, where walking the queue's entries would visit the records in
  // random order (seconds for millions of states). The same pass collects them into members_
  // for prepareNextIteration.
  members_.clear();
  Cost lb = kInfiniteCost;
  for (std::size_t i = 0; i < used_; ++i) {
    const StateId s = static_cast<StateId>(i);
    if (!(flags(s) & kIncons) && !inOpen(s, kAnchor)) continue;
    const HeuristicValue h0 = h(s, kAnchor);
    if (h0 == kInfiniteHeuristic) continue;
    lb = std::min(lb, g(s) + static_cast<Cost>(h0));
    members_.push_back(s);
  }
  return lb;
}

void MhaEngine::checkInvariants() const {
  auto fail = [](const std::string& what) { throw std::logic_error("A-MHA* invariant: " + what); };
  for (std::size_t i = 0; i < nh(); ++i) {
    std::size_t members = 0;
    open_[i].forEach([&](double f, StateId s) {
      if (!isMember(i, f, s)) return;  // stale
      ++members;
      if (flags(s) & kClosedAnch) fail("closed state in an OPEN queue");
      if (i > 0) {
        if (flags(s) & kClosedInad) fail("CLOSED_inad state in OPEN_" + std::to_string(i));
        if (!inOpen(s, kAnchor)) fail("OPEN_i is not a subset of OPEN_0");
        if (!admits(key(s, i), key(s, kAnchor).f))
          fail("state in OPEN_i fails key_i <= w2 * key_0");
      }
    });
    // Every state marked as a member has exactly one entry with its current key.
    std::size_t marked = 0;
    for (std::size_t s = 0; s < used_; ++s) marked += inOpen(static_cast<StateId>(s), i);
    if (marked != members) {
      fail("OPEN_" + std::to_string(i) + ": " + std::to_string(marked) + " states marked, " +
           std::to_string(members) + " member entries");
    }
  }
  for (std::size_t s = 0; s < used_; ++s) {
    const std::uint32_t f = flags(static_cast<StateId>(s));
    if ((f & kIncons) && !(f & kClosedAnch)) fail("INCONS state not in CLOSED_anch");
  }
}

}  // namespace detail
}  // namespace amha
