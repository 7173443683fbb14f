// The interface between search algorithms and domains (tiles, lattice, test graphs).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "amha_planner/search/types.h"

namespace amha {

/// A search problem with one start, one goal state, successors with costs, and heuristics:
/// heuristic 0 is the anchor (admissible and consistent), 1..N are arbitrary (inadmissible).
///
/// One virtual call per expansion (successors) and one per newly generated state (heuristics)
/// keeps the interface cheap; the search caches heuristic values, so a domain computes each
/// state's heuristics once.
class SearchProblem {
 public:
  virtual ~SearchProblem() = default;

  virtual StateId start() const = 0;
  virtual StateId goal() const = 0;

  /// Replaces the contents of `out` with the successors of `s`. May create new state ids
  /// (dense, in discovery order). Must not allocate once `out` has grown to the branching factor.
  virtual void successors(StateId s, std::vector<Edge>& out) = 0;

  /// Number of heuristics, anchor included (N + 1 >= 1).
  virtual std::size_t numHeuristics() const = 0;

  /// Writes h_0(s) .. h_{count-1}(s) into `h` (count <= numHeuristics()). h_0(goal) must be 0.
  virtual void heuristics(StateId s, HeuristicValue* h, std::size_t count) = 0;

  /// True if the heuristics have inflation bases (bases()): for each h_i, a heuristic b_i <= h_i
  /// that a weight inflates in h_i's place. Queue i's key at weight w is then
  /// g + h_i + (w - 1) b_i instead of g + w h_i: only b_i is inflated, h_i's surplus over it
  /// counts once. For the anchor, b_0 must be consistent: the key is then g + w h_w with
  /// h_w = (1 - 1/w) b_0 + h_0 / w, a convex combination of two consistent heuristics, so itself
  /// consistent, and admissible as b_0 <= h_0: every bound holds, and at w = 1 it is A*'s. For
  /// terms that a weight turns into a pull: inflated, a turning cost in h rewards turning early
  /// (w times what the turn saves in h, for once what it costs).
  virtual bool hasInflationBases() const { return false; }
  /// Writes b_0(s) .. b_{count-1}(s) (see hasInflationBases); called right after
  /// heuristics(s, ...) for the same state and count.
  virtual void bases(StateId s, HeuristicValue* b, std::size_t count) {
    (void)s;
    for (std::size_t i = 0; i < count; ++i) b[i] = 0;
  }

  /// True if edge costs and heuristic values are small integers, so that every key
  /// g + w * h stays below a few million: the search may then keep its queues as arrays of
  /// buckets indexed by key instead of heaps.
  virtual bool smallIntegerKeys() const { return false; }
  /// True if edge costs, heuristic values and inflation bases are integers, of any size (the
  /// lattice's millimetres): at a weight that makes every key a whole multiple of 1 / 64 the
  /// search may keep its queues as one stack of states per key value, ties newest first.
  virtual bool integerKeys() const { return smallIntegerKeys(); }

  /// True, once per change, if the domain's heuristics have become better informed since the
  /// search began (e.g. a table that a helper thread has completed): no value lower than before,
  /// and h_0 still admissible and consistent. The search then recomputes the values it caches
  /// and re-keys its queues. It asks when an iteration begins and, in an A* iteration (weight 1,
  /// the anchor's queue alone), every 1024 expansions: A* stays exact across the change, since
  /// every state it expanded before had its optimal g (h_0 was consistent) and every key after
  /// it is the new one (docs/search.md, "Heuristics that improve during a search").
  virtual bool upgradeHeuristics() { return false; }

  /// Whether the search should call expanded() for every state it expands (asked once, when
  /// it begins): a domain that publishes a search's progress to another one (LatticeProblem,
  /// as the backward side of a bidirectional proof) says yes; one virtual call per expansion.
  virtual bool wantsExpansions() const { return false; }
  /// State s expanded with cost-so-far g, its anchor key `key` (g + w1 h_0). In an A* (w1 = 1,
  /// h_0 consistent) the keys never fall and every state with a smaller key was expanded first.
  virtual void expanded(StateId s, Cost g, double key) {
    (void)s;
    (void)g;
    (void)key;
  }

  /// True if the goal provably cannot be reached from the start, found by looking at no more
  /// than `budget` states; false if that is not known. A domain can often tell much sooner than
  /// a search that must exhaust everything reachable from the start: looking from the goal
  /// against the edges' direction, the states that reach it may be few (a goal pose that no
  /// motion can end in, a pocket the robot cannot turn into). Only `true` changes anything: the
  /// search then stops with kNoSolution (and SearchSummary::goal_side_proof), so a domain must
  /// say so only on a proof. The search asks while it has found no path, at expansion counts
  /// spaced by 4x with a budget of a sixteenth of them (docs/search.md, "A goal no path
  /// reaches").
  virtual bool goalUnreachable(std::size_t budget) {
    (void)budget;
    return false;
  }

  /// Bytes the domain holds for its states (hash tables, state storage); counted against the
  /// search's memory cap together with the search's own arrays.
  virtual std::size_t memoryBytes() const { return 0; }

  /// For the duration of a search, the search lends the domain its limit check: it returns
  /// true once the search must stop (time limit, cancel, memory cap). A domain may call it
  /// inside a long operation, such as rebuilding a hash table of tens of millions of states,
  /// and cut the operation short as long as it stays valid; the search then stops at its next
  /// step. Cleared (an empty function) when the search returns.
  virtual void setInterruptCheck(std::function<bool()> check) { (void)check; }
};

}  // namespace amha
