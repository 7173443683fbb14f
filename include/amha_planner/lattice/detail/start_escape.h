// Leaving a start in collision (StartOptions in lattice_planner.h): the cheapest escape from a
// start whose footprint collides to each collision-free state it can reach, found by a Dijkstra
// over the states in collision near the start. The search then starts from those states, each
// at its escape cost (LatticeProblem::startAtExits).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "amha_planner/lattice/detail/lattice_problem.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/search/stop_condition.h"

namespace amha {
namespace lattice {

/// The escape rule. From a state in collision (not LatticeGraph::stateValid), a motion may
///  - cross inscribed cells with the robot's centre (never lethal or unknown ones, except those
///    below),
///  - cross, with its centre or its footprint, the lethal and unknown cells the robot stands on
///    at the start (under its footprint there, or its centre cell),
/// and nothing else that a normal motion may not: no other lethal or unknown cell, never off the
/// map. Every state on the way has its cell centre within `tolerance` metres of the start cell's.
/// Such a motion costs `penalty` x what it costs across cells of cost 252 (the costliest free
/// cells), rounded up. The escape ends at the first collision-free state it reaches (an exit);
/// from there on the normal rules hold, so the robot never re-enters a collision.
class StartEscape {
 public:
  /// The cheapest escape to one collision-free state.
  struct Exit {
    LatticeState state;
    Cost cost = 0;           ///< escape cost (units): the sum of its motions' costs
    std::uint32_t node = 0;  ///< where its path ends (for path())
  };
  /// One motion of an escape: from `from` by `action`.
  struct Step {
    LatticeState from;
    const LatticeAction* action = nullptr;
  };
  enum class Outcome { kFound, kNoExit, kStopped };

  /// `start` must be a state of `graph`'s map; tolerance >= 0 (metres) and penalty >= 1, finite.
  /// Explores every state in collision the rule reaches (`stop`, which may be null, ends it).
  StartEscape(const LatticeGraph& graph, const LatticeState& start, double tolerance,
              double penalty, const StopCondition* stop);

  Outcome outcome() const { return outcome_; }
  /// Every collision-free state the escape reaches, each at its cheapest escape cost.
  const std::vector<Exit>& exits() const { return exits_; }
  /// The motions of exit's escape, from the start on.
  std::vector<Step> path(const Exit& exit) const;
  /// The exit at `state`, or null.
  const Exit* exitAt(const LatticeState& state) const;
  /// States in collision the escape expanded; lethal or unknown cells under the start.
  std::size_t statesExpanded() const { return expanded_; }
  std::size_t cellsUnderStart() const { return allowed_.size(); }

  /// The cost of `a` from (x, y) under the rule, or kInvalidEdge (the tolerance aside).
  Cost motionCost(int x, int y, const LatticeAction& a) const;

 private:
  struct Node {
    LatticeState state;
    Cost g = 0;
    std::int64_t parent = -1;
    const LatticeAction* via = nullptr;
    bool closed = false;
  };
  bool allowed(std::int64_t cell) const;
  std::uint64_t key(const LatticeState& s) const;

  const LatticeGraph& graph_;
  double penalty_;
  std::vector<std::int64_t> allowed_;  // sorted cells: lethal or unknown under the start
  std::vector<Node> nodes_;
  std::unordered_map<std::uint64_t, std::uint32_t> index_;  // state key -> node
  std::vector<Exit> exits_;
  std::unordered_map<std::uint64_t, std::size_t> exit_index_;  // state key -> exits_
  std::size_t expanded_ = 0;
  Outcome outcome_ = Outcome::kNoExit;
};

}  // namespace lattice
}  // namespace amha
